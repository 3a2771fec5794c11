// tessera view: starts the page once every script is loaded (last in kViewScripts).
"use strict";
setupControls();
setupFlow();
for (const r of D.results || []) addResult(r);
window.tesseraView = { state: S, data: D, centreOn, selectInput, selectResult, draw, texels,
                       showOverview };
if (D.inputs.length) selectInput(0);
