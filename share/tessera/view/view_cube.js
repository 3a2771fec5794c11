// tessera view: inputs that are not encoded as they are. An image that is not a power of two
// (PVRTC1 needs --resize-pot) shows its original and the fix; a result without a reference (a
// texture opened as it is) says so and disables the heatmaps it has none of; a result encoded
// from a resized original says what it was measured against. Shares view.js's scope.
"use strict";

/** True when `settings` cannot encode input `inp` (not a power of two, no --resize-pot). */
function npotBlocked(inp, settings) {
  return !!(inp && inp.needs_resize_pot && !(settings && settings.resize_pot));
}

/** A result-like entry that shows the input's own images (faces, layers) with nothing encoded:
 *  its id is "o" + the input's index. Null when the input carries no originals. */
function originalsResult(index) {
  const inp = D.inputs[index];
  if (!inp || !inp.originals || !inp.originals.length) return null;
  const id = `o${index}`;
  if (!S.results.has(id)) {
    const o = inp.originals[0];
    addResult({
      id, input_index: index, original_only: true, label: "original (not encoded)",
      texture: { width: o.width, height: o.height, levels: 1, faces: inp.faces || 1,
                 layers: inp.layers || 1, format: "not encoded", shape: inp.shape || "2D",
                 premultiplied: false, srgb: false },
      images: inp.originals.map((x) => ({ ...x, decoded: x.original })),
    });
  }
  return id;
}

/** Shows input `index`'s originals (its note says why nothing is encoded). */
function showOriginals(index) {
  const id = originalsResult(index);
  if (!id) return false;
  S.current.set(index, id);
  if (S.input === index) selectResult(id);
  return true;
}

/** The options form's note for input `inp` (empty when none). */
function inputNote(inp) {
  if (!inp.needs_resize_pot) return "";
  return D.mode === "static" ? `${inp.note}. Not encoded: run tessera view --resize-pot.`
                             : `${inp.note}. Tick --resize-pot below to encode it.`;
}

/** The right pane's choices that `im` has (heatmaps need a reference): the others disabled,
 *  with their reason as a tooltip. */
function markRightChoices(r, im) {
  for (const o of $("right").options) {
    if (o.value === "result") continue;
    const has = !!(im && im[o.value]);
    o.disabled = !has;
    o.title = has ? "" : whyNoMap(r, im);
  }
}
function whyNoMap(r, im) {
  if (r && r.original_only) return "not encoded";
  if (im && !im.original) return "no reference: a texture opened as it is";
  return "not for this result";
}

/** The metrics rows of a result that is only the originals, or the rows added to an encoded
 *  one (what it was measured against). */
function originalRows(r, im) {
  const inp = D.inputs[r.input_index];
  return [["image", `${im.width}x${im.height}` + (r.texture.faces === 6 ? `, face ${im.face}` : "")
              + (r.texture.layers > 1 ? `, layer ${im.layer}` : "")],
          ["note", "not encoded", shortNote(inp)]];
}
/** One short line: why input `inp` is not encoded. */
function shortNote(inp) {
  if (!inp.needs_resize_pot) return inp.error || "";
  return D.mode === "static" ? "not a power of two (tessera view --resize-pot encodes it)"
                             : "not a power of two: tick --resize-pot";
}
function referenceRows(r) {
  if (!r.resized_from) return [];
  const [w, h] = r.resized_from;
  return [["reference", "measured against",
           `the original resized from ${w}x${h} to ${r.texture.width}x${r.texture.height} (--resize-pot, Lanczos-3)`]];
}
function noReferenceText(r) {
  return r.texture.faces === 6 || r.texture.layers > 1
      ? "no reference: a texture opened as it is (give its faces too: tessera view FILE --cube +X -X +Y -Y +Z -Z, same stem)"
      : "no reference: a texture opened as it is (open its source image too, same stem, to measure it)";
}
