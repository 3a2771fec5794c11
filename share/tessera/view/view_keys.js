// tessera view: keyboard shortcuts (not while typing in a form field, nor with Ctrl/Alt/Meta):
// 1-4 the right pane (result, heatmap, heatmap colour x alpha, angular error: those the image
// has), + and - zoom on the centre, c the next channel, h result / heatmap, w side by side /
// wipe, ? shows or hides the list.
"use strict";
const RIGHT_KEYS = ["result", "heatmap", "heatmap_premultiplied", "angle_map"];

/** Sets a select's value and runs its change handler, as a person choosing it would. */
function choose(id, value) {
  const sel = $(id);
  if (sel.disabled || sel.value === String(value)) return;
  sel.value = String(value);
  sel.dispatchEvent(new Event("change"));
}
/** One zoom step in (+1) or out (-1), on the centre of what is shown. */
function zoomStep(dir) {
  if (S.zoom === "fit") fixZoom($("canvas-a"));
  const steps = ZOOMS.slice(1);
  let i = steps.findIndex((z) => z >= S.zoom);
  if (i < 0) i = steps.length - 1;
  setZoom(steps[Math.max(0, Math.min(steps.length - 1, i + dir))]);
}
function onKey(ev) {
  if (ev.ctrlKey || ev.altKey || ev.metaKey || ev.defaultPrevented) return;
  const t = ev.target;
  if (t && (t.isContentEditable || ["INPUT", "SELECT", "TEXTAREA"].includes(t.tagName))) return;
  const r = S.results.get(S.result), im = r ? currentImage(r) : null;
  const k = ev.key;
  if (k >= "1" && k <= "4") {
    const want = RIGHT_KEYS[Number(k) - 1];
    if (want === "result" || (im && im[want])) choose("right", want);
  } else if (k === "+" || k === "=") {
    zoomStep(1);
  } else if (k === "-" || k === "_" || k === "\u2212") {
    zoomStep(-1);
  } else if (k === "c" || k === "C") {
    const opts = [...$("channel").options].map((o) => o.value);
    choose("channel", opts[(opts.indexOf($("channel").value) + 1) % opts.length]);
  } else if (k === "h" || k === "H") {
    choose("right", $("right").value === "result" && im && im.heatmap ? "heatmap" : "result");
  } else if (k === "w" || k === "W") {
    choose("mode", $("mode").value === "wipe" ? "side" : "wipe");
  } else if (k === "?") {
    $("keys-help").hidden = !$("keys-help").hidden;
  } else {
    return;
  }
  ev.preventDefault();
}
document.addEventListener("keydown", onKey);
