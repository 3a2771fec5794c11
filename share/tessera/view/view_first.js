// tessera view: the input's own original, drawn before its first result exists. An encode of a
// 4096² image takes many seconds in the server; the server serves each image input's texels at
// once (its "original" blob), so the page shows the input while the encode runs, the right pane
// saying so, and draws the result as usual when it comes. The texel readout reads the original.
"use strict";

/** Draws the current input's original when it has no result yet (server mode); false when
 *  there is nothing to draw (a texture, an error, a static view: draw() clears the panes). */
async function drawOriginal(ticket) {
  const inp = D.inputs[S.input];
  if (!inp || !inp.original || inp.error) return false;
  const mode = $("mode").value === "wipe" ? "wipe" : "side";
  document.body.classList.toggle("single", mode !== "side");
  const t = await texels(inp.original, inp.width, inp.height);
  if (ticket !== drawing || S.result) return true;  // a newer draw, or the result, took over
  const im = { width: inp.width, height: inp.height, level: 0, face: 0, layer: 0 };
  const premult = $("blend").value === "premultiplied";
  const a = { src: channelCanvas(inp.original, t, $("channel").value, premult), texels: t,
              caption: "original" };
  const b = { src: null, texels: null, caption: "encoding…" };
  S.shown = { a, b, im, cross: false };
  const ca = $("canvas-a"), cb = $("canvas-b");
  const { ctx, dpr } = prepare(ca), tr = transform(ca, im.width, im.height);
  if (mode === "side") {
    blit(ctx, dpr, a.src, tr);
    const right = prepare(cb);
    encodingNote(right.ctx, right.dpr, cb.width / 2);
    $("caption-a").textContent = a.caption;
    $("caption-b").textContent = b.caption;
  } else {  // the original left of the wipe, the note right of it
    const split = ca.clientWidth * Number($("wipe").value) / 1000;
    blit(ctx, dpr, a.src, tr, [0, split]);
    ctx.fillStyle = "#fff";
    ctx.fillRect(Math.round(split * dpr), 0, Math.max(1, dpr), ca.height);
    encodingNote(ctx, dpr, (split * dpr + ca.width) / 2);
    $("caption-a").textContent = `wipe: ${a.caption} (left) | ${b.caption} (right)`;
  }
  refreshReadout();
  document.body.dataset.drawn = `original:${S.input}:${S.zoom}`;
  return true;
}

function encodingNote(ctx, dpr, x) {
  ctx.fillStyle = "#888";
  ctx.font = `${14 * dpr}px sans-serif`;
  ctx.textAlign = "center";
  ctx.fillText("encoding…", x, ctx.canvas.height / 2);
}

/** Runs `then` (the first encode) once the current input's original is in the page (or could
 *  not be had): the server makes the original's blob on request, and an encode started at the
 *  same time would share the CPU with it and delay the first draw. */
function afterOriginal(then) {
  const index = S.input, inp = D.inputs[index];
  if (!inp || !inp.original) { then(); return; }
  showBusy(0);
  texels(inp.original, inp.width, inp.height).catch(() => {}).then(() => {
    if (S.input === index) then();  // else: encoded when the input is chosen again
    else if (!S.jobs) $("busy").hidden = true;
  });
}
