// tessera view: starts the page once every script is loaded (last in kViewScripts).
"use strict";
setupControls();
for (const r of D.results || []) addResult(r);
window.tesseraView = { state: S, data: D, centreOn, selectInput, selectResult, draw, texels };
if (D.inputs.length) selectInput(0);
