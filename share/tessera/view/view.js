// tessera view: the page's core (state, data, controls, drawing, pointer). Plain JavaScript, no
// libraries, nothing fetched from elsewhere. The page's scripts are concatenated into one
// <script> in the order of kViewScripts (tools/tessera/view_export.cpp), so their top-level
// names are shared; view_start.js, last, starts the page.
// Data: the JSON in #tessera-data (mode "server": inputs and a token, results fetched and
// encoded through /api/...; mode "static": every result and blob inline as data: URIs).
// Texels arrive as PNG, read by view_png.js (exact values: a canvas would premultiply them);
// heatmaps and colour bars as PNG/SVG. window.tesseraView exposes the state for tests.
"use strict";
const D = JSON.parse(document.getElementById("tessera-data").textContent);
const $ = (id) => document.getElementById(id);
const S = {  // the page's state
  input: 0, result: null, level: 0, face: 0, layer: 0, zoom: "fit", cx: 0, cy: 0,
  results: new Map(), pinned: [], current: new Map(), jobs: 0, pointer: null,
};
const texelCache = new Map(), imageCache = new Map(), viewCache = new Map();

// ---- blobs ---------------------------------------------------------------------------------
function blobUrl(key) {
  return D.mode === "static" ? D.blobs[key] : `/blob/${key}?token=${encodeURIComponent(D.token)}`;
}
async function blobBytes(key) {
  if (D.mode === "static") {
    const text = atob(D.blobs[key].slice(D.blobs[key].indexOf(",") + 1));
    const out = new Uint8Array(text.length);
    for (let i = 0; i < text.length; ++i) out[i] = text.charCodeAt(i);
    return out;
  }
  const r = await fetch(blobUrl(key));
  if (!r.ok) throw Object.assign(new Error(`blob ${key}: HTTP ${r.status}`), { status: r.status });
  return new Uint8Array(await r.arrayBuffer());
}
/** {width, height, data} of an image's texels (RGBA8, read exactly: view_png.js, or decoded
 *  from a .pvr: view_pvrtc.js), cached. */
function texels(key, width, height) {
  if (!texelCache.has(key)) {
    const made = key.startsWith("pvrtc:") ? pvrtcTexels(key)
        : blobBytes(key).then(decodePng).then((data) => ({ width, height, data }));
    texelCache.set(key, made.catch((e) => { texelCache.delete(key); throw e; }));
  }
  return texelCache.get(key);
}
function image(key) {
  if (!imageCache.has(key)) {
    imageCache.set(key, new Promise((ok, bad) => {
      const im = new Image();
      im.onload = () => ok(im);
      im.onerror = () => bad(new Error("image " + key + " did not load"));
      im.src = blobUrl(key);
    }));
  }
  return imageCache.get(key);
}

// ---- server calls --------------------------------------------------------------------------
async function api(path, body) {
  const sep = path.includes("?") ? "&" : "?";
  const r = await fetch(`${path}${sep}token=${encodeURIComponent(D.token)}`, body === undefined
      ? {} : { method: "POST", headers: { "Content-Type": "application/json" },
               body: JSON.stringify(body) });
  const j = await r.json().catch(() => ({ error: `HTTP ${r.status}` }));
  if (!r.ok) throw new Error(j.error || `HTTP ${r.status}`);
  return j;
}
const sleep = (ms) => new Promise((ok) => setTimeout(ok, ms));

/** Encodes the current input with `settings` in the server; the shown result stays until the
 *  new one is there. Polls the job's progress (bounded: the job ends or errs). */
async function encode(settings) {
  const input = S.input;
  S.jobs++;
  showBusy(0);
  try {
    let job = await api("/api/encode", { input, settings });
    while (job.state === "queued" || job.state === "running") {
      showBusy(job.fraction);
      await sleep(100);
      job = await api(`/api/job?id=${job.id}`);
    }
    if (job.state === "error") throw new Error(job.error);
    job.result.job = job.id;  // gone when the server evicts the result (checkEvicted)
    addResult(job.result);
    S.current.set(input, job.result.id);
    if (S.input === input) selectResult(job.result.id);
    showError("");
  } catch (e) {
    showError(e.message);
  } finally {
    S.jobs--;
    if (!S.jobs) $("busy").hidden = true;
  }
}
function showBusy(f) {
  $("busy").hidden = false;
  $("progress").value = f;
  $("busy-text").textContent = `encoding ${Math.round(f * 100)}%`;
}
function showError(text) {
  $("error").hidden = !text;
  $("error").textContent = text;
  document.body.dataset.error = text;
}

// ---- results -------------------------------------------------------------------------------
function addResult(r) {
  S.results.set(r.id, r);
}
function resultsOf(input) {
  return [...S.results.values()].filter((r) => r.input_index === input);
}
function label(r) {
  if (!r.settings) return r.label || "texture";
  if (r.settings.label) return r.settings.label;
  const s = r.settings, parts = [s.format === "pvrtc1-2" ? "2bpp" : "4bpp", s.quality];
  for (const k of ["alpha_bleed", "alpha_weighted", "premultiply", "normal_map", "srgb"]) {
    if (s[k]) parts.push(k.replace("alpha_", "").replace("_map", ""));
  }
  if (s.mip_levels) parts.push(`${s.mip_levels} mips`);
  if (s.resize_pot) parts.push("resized");
  return parts.join(" ");
}
function currentImage(r = S.results.get(S.result)) {
  if (!r) return null;
  return r.images.find((i) => i.level === S.level && i.face === S.face && i.layer === S.layer)
      || r.images[0];
}
function fmt(v, digits = 2) {
  return v === null ? "inf" : v === undefined ? "-" : Number(v).toFixed(digits);
}

// ---- controls ------------------------------------------------------------------------------
function fillSelect(sel, values, current) {
  sel.innerHTML = "";
  for (const [value, text] of values) {
    const o = document.createElement("option");
    o.value = value;
    o.textContent = text;
    sel.appendChild(o);
  }
  sel.value = String(current);
}
const MAX_TABS = 8;  // unpinned results shown as tabs per input, the most recent
const ZOOMS = ["fit", 0.25, 0.5, 1, 2, 4, 8, 16, 32];
function setupControls() {
  fillSelect($("input"), D.inputs.map((i) => [i.index, i.name + (i.error ? " (error)" : "")]), 0);
  fillSelect($("zoom"), ZOOMS.map((z) => [z, z === "fit" ? "fit" : `${z}x`]), "fit");
  $("input").onchange = () => selectInput(Number($("input").value));
  for (const id of ["mode", "channel", "blend", "right", "left", "gain"]) $(id).onchange = () => draw();
  for (const id of ["level", "face", "layer"]) {
    $(id).onchange = () => { S[id] = Number($(id).value); refresh(); };
  }
  $("zoom").onchange = () => {
    const chosen = $("zoom").value;
    if (S.zoom === "fit") fixZoom($("canvas-a"));  // from fit: keep the centre
    S.zoom = chosen === "fit" ? "fit" : Number(chosen);
    $("zoom").value = chosen;
    draw();
  };
  $("wipe").oninput = () => draw();
  $("options").onchange = () => {
    if (D.mode !== "server") return;
    if (npotBlocked(D.inputs[S.input], formSettings())) showOriginals(S.input);
    else encode(formSettings());
  };
  $("pin").onclick = togglePin;
  $("copy").onclick = () => navigator.clipboard && navigator.clipboard.writeText($("command").textContent);
  for (const c of [$("canvas-a"), $("canvas-b")]) attachPointer(c);
  window.addEventListener("resize", () => draw());
  $("version").textContent = `tessera ${D.version}` + (D.mode === "static" ? " · static view" : "");
}
function formSettings() {
  const f = $("options").elements, s = {};
  for (const k of ["format", "quality", "mip_filter"]) s[k] = f[k].value;
  for (const k of ["alpha_bleed", "alpha_weighted", "premultiply", "normal_map", "srgb", "resize_pot"]) s[k] = f[k].checked;
  s.mip_levels = Number(f.mip_levels.value) || 0;
  return s;
}
function setForm(s) {
  const f = $("options").elements;
  for (const k of ["format", "quality", "mip_filter"]) f[k].value = s[k];
  for (const k of ["alpha_bleed", "alpha_weighted", "premultiply", "normal_map", "srgb", "resize_pot"]) f[k].checked = !!s[k];
  f.mip_levels.value = s.mip_levels || 0;
}
function togglePin() {
  const at = S.pinned.indexOf(S.result);
  if (at >= 0) {
    S.pinned.splice(at, 1);
    tellPin(S.result, false);
  } else if (S.result) {
    if (S.pinned.length === 4) tellPin(S.pinned.shift(), false);  // at most four
    S.pinned.push(S.result);
    tellPin(S.result, true);
  }
  refresh();
}
/** The server keeps pinned results when it evicts others under its memory budget. */
function tellPin(id, pinned) {
  if (D.mode === "server") {
    api(`/api/pin?id=${encodeURIComponent(id)}&pinned=${pinned ? 1 : 0}`).catch((e) => showError(e.message));
  }
}

function selectInput(index) {
  S.input = index;
  const inp = D.inputs[index];
  $("input").value = String(index);
  showError(inp.error ? inp.error : "");
  const form = $("options");
  const editable = D.mode === "server" && inp.kind === "image" && !inp.error;
  for (const el of form.elements) el.disabled = !editable;
  $("options-note").textContent = inp.kind === "texture"
      ? "A texture file, shown as decoded: open its source image to try options."
      : D.mode === "static" ? "A static view: these results were encoded by tessera view --html."
      : "";
  if (inputNote(inp)) $("options-note").textContent += (editable ? "" : " ") + inputNote(inp);
  $("options-note").hidden = !$("options-note").textContent;
  if (inp.kind === "texture") setForm({ format: "pvrtc1-4", quality: "normal", mip_filter: "box" });
  const mine = resultsOf(index);
  const id = S.current.get(index) || (mine.length ? mine[0].id : null);
  S.level = S.face = S.layer = 0;
  // Alpha is what an artist checks first: an input with alpha opens composited.
  $("channel").value = inp.has_alpha ? "checker" : "rgb";
  const first = D.initial && D.initial.length ? D.initial[0] : formSettings();
  if (id) selectResult(id);
  else if ((!editable || npotBlocked(inp, first)) && showOriginals(index)) setForm(first);
  else {
    S.result = null;
    refresh();
    if (editable) afterOriginal(() => encode(first));
  }
}
function selectResult(id) {
  const r = S.results.get(id);
  S.result = id;
  S.current.set(r.input_index, id);
  if (r.settings) setForm(r.settings);
  const t = r.texture;
  S.level = Math.min(S.level, t.levels - 1);
  S.face = Math.min(S.face, t.faces - 1);
  S.layer = Math.min(S.layer, t.layers - 1);
  if ($("mode").value === "cross" && t.faces !== 6) $("mode").value = "side";
  refresh();
  checkEvicted(r);
}

/** Rebuilds everything that depends on the current result and image, then draws. */
function refresh() {
  const r = S.results.get(S.result);
  const tabs = $("tabs");
  tabs.innerHTML = "";
  // Every result of the input stays a tab (the pinned, the current, texture files, and the
  // MAX_TABS most recent others): an earlier setting is one click away; one the server has
  // evicted is encoded again when clicked (view_flow.js).
  const mine = resultsOf(S.input);
  const recent = new Set(mine.filter((x) => x.settings && !S.pinned.includes(x.id))
      .slice(-MAX_TABS).map((x) => x.id));
  const shown = mine.filter((x) => D.mode === "static" || !x.settings
      || S.pinned.includes(x.id) || x.id === S.result || recent.has(x.id));
  for (const x of shown) {
    const b = document.createElement("button");
    b.type = "button";
    b.textContent = label(x);
    b.dataset.result = x.id;
    b.className = (x.id === S.result ? "current " : "") + (S.pinned.includes(x.id) ? "pinned" : "");
    b.onclick = () => selectResult(x.id);
    tabs.appendChild(b);
  }
  const inp = D.inputs[S.input] || {};
  const t = r ? r.texture : { levels: 1, faces: 1, layers: 1, width: inp.width, height: inp.height };
  fillSelect($("level"), [...Array(t.levels).keys()].map((l) => [l, `${l} (${Math.max(1, t.width >> l)}x${Math.max(1, t.height >> l)})`]), S.level);
  fillSelect($("face"), [...Array(t.faces).keys()].map((f) => [f, t.faces === 6 ? ["+X", "-X", "+Y", "-Y", "+Z", "-Z"][f] : String(f)]), S.face);
  fillSelect($("layer"), [...Array(t.layers).keys()].map((l) => [l, String(l)]), S.layer);
  $("face").disabled = t.faces === 1;
  $("layer").disabled = t.layers === 1;
  $("level").disabled = t.levels === 1;
  const left = [["original", "original"]];
  for (const id of S.pinned) {
    const p = S.results.get(id);
    if (p && p.input_index === S.input && id !== S.result) left.push([id, "pinned: " + label(p)]);
  }
  const keepLeft = $("left").value;
  fillSelect($("left"), left, left.some(([v]) => v === keepLeft) ? keepLeft : "original");
  markRightChoices(r, currentImage(r));
  showMetrics(r);
  showPinned();
  draw();
}

function showMetrics(r) {
  const body = $("metrics").tBodies[0];
  body.innerHTML = "";
  const im = currentImage(r);
  const rows = r && im && r.original_only ? originalRows(r, im) : [];
  if (r && im && !r.original_only) {
    const m = im.metrics || {};
    rows.push(["image", `${im.width}x${im.height}, level ${im.level}` +
        (r.texture.faces === 6 ? `, face ${im.face}` : "") + (r.texture.layers > 1 ? `, layer ${im.layer}` : "")]);
    if (im.metrics) {
      rows.push(["psnr_rgb", "PSNR RGB (dB)", fmt(m.psnr_rgb)]);
      if ("psnr_alpha" in m) rows.push(["psnr_alpha", "PSNR alpha (dB)", fmt(m.psnr_alpha)]);
      if ("psnr_premultiplied" in m) rows.push(["psnr_premultiplied", "PSNR colour x alpha (dB)", fmt(m.psnr_premultiplied)]);
      rows.push(["ssim_gray", "SSIM grey", fmt(m.ssim_gray, 4)]);
      rows.push(["max_abs", "max abs difference", String(m.max_abs)]);
      if ("angular_error_mean_deg" in m) {
        rows.push(["angular_error_mean_deg", "angle mean (°)", fmt(m.angular_error_mean_deg, 3)]);
        rows.push(["angular_error_p99_deg", "angle p99 (°)", fmt(m.angular_error_p99_deg, 3)]);
        rows.push(["angular_error_max_deg", "angle max (°)", fmt(m.angular_error_max_deg, 3)]);
      }
      rows.push(...referenceRows(r));
    } else {
      rows.push(["note", noReferenceText(r)]);
    }
    rows.push(["format", "format", r.texture.format + (r.texture.srgb ? ", sRGB" : "") + (r.texture.premultiplied ? ", premultiplied" : "")]);
    rows.push(["shape", "shape", `${r.texture.shape}, ${r.texture.levels} level(s)`]);
    rows.push(["bytes", "file size (bytes)", String(r.bytes)]);
    if ("encode_ms" in r) rows.push(["encode_ms", "encode time (ms)", fmt(r.encode_ms, 1)]);
  }
  for (const row of rows) {
    const tr = body.insertRow();
    tr.dataset.metric = row[0];
    const a = tr.insertCell(), b = tr.insertCell();
    a.textContent = row.length === 3 ? row[1] : row[0];
    b.textContent = row.length === 3 ? row[2] : row[1];
    b.className = "num";
    b.dataset.value = row.length === 3 ? row[2] : "";
  }
  $("command").textContent = r && r.command ? r.command : r && r.original_only ? "(not encoded)"
      : r ? "(a texture file, opened as it is)" : "";
  $("pin").hidden = !!(r && r.original_only);
  const dl = $("download");
  dl.hidden = !r || !!r.original_only;
  if (r && !r.original_only) {
    dl.href = blobUrl(r.file);
    dl.download = r.file_name;
    dl.textContent = `download ${r.file_name}`;
  }
  showDownloads(r);
  $("pin").textContent = S.pinned.includes(S.result) ? "unpin" : "pin";
}
function showPinned() {
  const body = $("pinned").tBodies[0];
  body.innerHTML = "";
  for (const id of S.pinned) {
    const r = S.results.get(id);
    const tr = body.insertRow();
    const m = (r.images[0] && r.images[0].metrics) || {};
    for (const [text, num] of [[`${D.inputs[r.input_index].name}: ${label(r)}`, false],
        [fmt(m.psnr_rgb), true], [fmt(m.ssim_gray, 4), true], [String(r.bytes), true],
        [fmt(r.encode_ms, 1), true]]) {
      const c = tr.insertCell();
      c.textContent = text;
      if (num) c.className = "num";
    }
    tr.onclick = () => { if (r.input_index !== S.input) selectInput(r.input_index); selectResult(id); };
  }
}

// ---- drawing -------------------------------------------------------------------------------
/** An opaque picture of texels `t` as `channel` shows them (view_tiles.js), cached. */
function channelCanvas(key, t, channel, premultiplied) {
  const ck = `${key}|${channel}|${premultiplied}`;
  if (!viewCache.has(ck)) {
    viewCache.set(ck, new Picture(t.width, t.height, fillChannel(t, channel, premultiplied)));
  }
  return viewCache.get(ck);
}

/** What a pane shows: {canvas-like source, texels, caption} for `side` ("a" or "b"). */
async function paneSource(side, im, r) {
  const premult = $("blend").value === "auto" ? r.texture.premultiplied : $("blend").value === "premultiplied";
  const channel = $("channel").value;
  if (side === "a") {
    const left = $("left").value;
    if (left !== "original") {
      const p = S.results.get(left), pi = currentImage(p);
      const t = await texels(pi.decoded, pi.width, pi.height);
      return { src: channelCanvas(pi.decoded, t, channel, premult), texels: t, caption: "pinned: " + label(p) };
    }
    if (!im.original) return { src: null, texels: null, caption: "no original (a texture opened as it is)" };
    const t = await texels(im.original, im.width, im.height);
    const caption = r.resized_from ? `original, resized to ${r.texture.width}x${r.texture.height} (--resize-pot)` : "original";
    return { src: channelCanvas(im.original, t, channel, premult), texels: t, caption };
  }
  if (r.original_only) return { src: null, texels: null, caption: "not encoded: " + shortNote(D.inputs[r.input_index]) };
  const t = await texels(im.decoded, im.width, im.height);
  const right = $("right").value;
  if (right !== "result" && im[right]) {
    const captions = { heatmap: "error heatmap (max abs channel difference)",
                       heatmap_premultiplied: "error heatmap of colour x alpha (what blending shows)",
                       angle_map: "angular error" };
    const src = await heatPicture(im, right);
    return { src, texels: t, caption: `${captions[right]}; ${src.note}` };
  }
  if (right !== "result") return { src: channelCanvas(im.decoded, t, channel, premult), texels: t, caption: `${label(r)} (no ${right.replace("_", " ")}: ${whyNoMap(r, im)})` };
  return { src: channelCanvas(im.decoded, t, channel, premult), texels: t, caption: label(r) };
}

function zoomOf(canvas, w, h) {
  if (S.zoom !== "fit") return S.zoom;
  return Math.max(1 / 64, Math.min(canvas.clientWidth / w, canvas.clientHeight / h));
}
function prepare(canvas) {
  const dpr = window.devicePixelRatio || 1;
  const w = Math.max(1, Math.round(canvas.clientWidth * dpr)), h = Math.max(1, Math.round(canvas.clientHeight * dpr));
  if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
  const ctx = canvas.getContext("2d");
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  ctx.fillStyle = "#111";
  ctx.fillRect(0, 0, w, h);
  ctx.imageSmoothingEnabled = false;
  return { ctx, dpr };
}
/** Screen transform of a pane: texel (x, y) lands at (ox + x z, oy + y z) CSS pixels. */
function transform(canvas, w, h) {
  const z = zoomOf(canvas, w, h);
  const cx = S.zoom === "fit" ? w / 2 : S.cx, cy = S.zoom === "fit" ? h / 2 : S.cy;
  return { z, ox: canvas.clientWidth / 2 - cx * z, oy: canvas.clientHeight / 2 - cy * z };
}
function blit(ctx, dpr, src, tr, clip) {
  if (src.drawTo) { src.drawTo(ctx, dpr, tr, clip); return; }
  ctx.save();
  if (clip) { ctx.beginPath(); ctx.rect(clip[0] * dpr, 0, clip[1] * dpr, ctx.canvas.height); ctx.clip(); }
  ctx.setTransform(tr.z * dpr, 0, 0, tr.z * dpr, tr.ox * dpr, tr.oy * dpr);
  ctx.drawImage(src, 0, 0);
  ctx.restore();
}

let drawing = 0;
async function draw() {
  const ticket = ++drawing;
  const r = S.results.get(S.result);
  const mode = $("mode").value;
  document.body.classList.toggle("single", mode !== "side");
  $("wipe").hidden = mode !== "wipe";
  const ca = $("canvas-a"), cb = $("canvas-b");
  if (!r) {
    S.shown = null;
    if (!(await drawOriginal(ticket).catch(() => false))) { prepare(ca); prepare(cb); }
    return;
  }
  const im = currentImage(r);
  showHeatControls(im);
  try {
    if (mode === "cross") return await drawCross(r, ticket);
    const [a, b] = await Promise.all([paneSource("a", im, r), paneSource("b", im, r)]);
    if (ticket !== drawing) return;
    S.shown = { a, b, im, cross: false };
    if (mode === "side") {
      for (const [c, p, cap] of [[ca, a, "caption-a"], [cb, b, "caption-b"]]) {
        const { ctx, dpr } = prepare(c);
        if (p.src) blit(ctx, dpr, p.src, transform(c, im.width, im.height));
        $(cap).textContent = p.caption;
      }
    } else {
      const { ctx, dpr } = prepare(ca);
      const tr = transform(ca, im.width, im.height);
      const split = ca.clientWidth * Number($("wipe").value) / 1000;
      if (a.src) blit(ctx, dpr, a.src, tr, [0, split]);
      if (b.src) blit(ctx, dpr, b.src, tr, [split, ca.clientWidth - split]);
      ctx.fillStyle = "#fff";
      ctx.fillRect(Math.round(split * dpr), 0, Math.max(1, dpr), ca.height);
      $("caption-a").textContent = `wipe: ${a.caption} (left) | ${b.caption} (right)`;
    }
    refreshReadout();
    document.body.dataset.drawn = `${S.result}:${im.level}:${im.face}:${im.layer}:${S.zoom}`;
  } catch (e) {
    if (!reencodeEvicted(e)) showError(e.message);
  }
}

const CROSS = [[2, 1], [0, 1], [1, 0], [1, 2], [1, 1], [3, 1]];  // +X -X +Y -Y +Z -Z in a 4x3 cross
async function drawCross(r, ticket) {
  const faces = [];
  for (let f = 0; f < 6; ++f) {
    const im = r.images.find((i) => i.level === S.level && i.layer === S.layer && i.face === f);
    faces.push({ im, p: await paneSource(r.original_only ? "a" : "b", im, r) });
  }
  if (ticket !== drawing) return;
  const ca = $("canvas-a"), n = faces[0].im.width;
  const { ctx, dpr } = prepare(ca);
  const tr = transform(ca, 4 * n, 3 * n);
  faces.forEach(({ p }, f) => {
    blit(ctx, dpr, p.src, { z: tr.z, ox: tr.ox + CROSS[f][0] * n * tr.z, oy: tr.oy + CROSS[f][1] * n * tr.z });
  });
  S.shown = { cross: true, faces, n };
  $("caption-a").textContent = `cube map as a cross (level ${S.level}): ${faces[0].p.caption}`;
  refreshReadout();
  document.body.dataset.drawn = `${S.result}:${S.level}:cross:${S.layer}:${S.zoom}`;
}

// ---- pointer: texel values, pan, zoom ------------------------------------------------------
function texelUnder(canvas, ev) {
  const sh = S.shown;
  if (!sh) return null;
  const rect = canvas.getBoundingClientRect();
  const px = ev.clientX - rect.left, py = ev.clientY - rect.top;
  if (sh.cross) {
    const tr = transform(canvas, 4 * sh.n, 3 * sh.n);
    const gx = Math.floor((px - tr.ox) / tr.z), gy = Math.floor((py - tr.oy) / tr.z);
    const f = CROSS.findIndex(([cx, cy]) => Math.floor(gx / sh.n) === cx && Math.floor(gy / sh.n) === cy);
    if (f < 0) return null;
    return { x: gx - CROSS[f][0] * sh.n, y: gy - CROSS[f][1] * sh.n, face: f, b: sh.faces[f].p.texels, w: sh.n };
  }
  const tr = transform(canvas, sh.im.width, sh.im.height);
  const x = Math.floor((px - tr.ox) / tr.z), y = Math.floor((py - tr.oy) / tr.z);
  if (x < 0 || y < 0 || x >= sh.im.width || y >= sh.im.height) return null;
  return { x, y, face: sh.im.face, a: sh.a.texels, b: sh.b.texels, w: sh.im.width };
}
function readout(t) {
  if (!t) { $("readout").textContent = "move over the image for texel values"; return; }
  const at = (img) => img ? Array.from(img.data.slice((t.y * t.w + t.x) * 4, (t.y * t.w + t.x) * 4 + 4)) : null;
  const a = at(t.a), b = at(t.b);
  const lines = [`texel (${t.x}, ${t.y})` + (S.shown.cross ? ` face ${t.face}` : "") + ` level ${S.level}`];
  if (a) lines.push(`${$("left").value === "original" ? "original" : "left"} ${a.join(" ")}`);
  lines.push(b ? `decoded  ${b.join(" ")}` : S.result ? "not encoded" : "decoded  (encoding…)");
  if (a && b) lines.push(`difference ${b.map((v, i) => (v - a[i] >= 0 ? "+" : "") + (v - a[i])).join(" ")}`);
  $("readout").textContent = lines.join("\n");
  const ro = $("readout").dataset;
  ro.x = t.x; ro.y = t.y; ro.decoded = b ? b.join(",") : ""; ro.original = a ? a.join(",") : "";
}
/** The texel under the pointer's last place, read again after a change (input, result, level,
 *  face, view, zoom): the readout never shows a texel of what is no longer drawn. */
function refreshReadout() {
  const p = S.pointer;
  readout(p ? texelUnder(p.canvas, p) : null);
}
function attachPointer(canvas) {
  let drag = null;
  canvas.addEventListener("pointerleave", () => { S.pointer = null; });
  canvas.addEventListener("pointermove", (ev) => {
    S.pointer = { canvas, clientX: ev.clientX, clientY: ev.clientY };
    if (drag && S.zoom !== "fit") {
      const z = S.zoom;
      S.cx = drag.cx - (ev.clientX - drag.x) / z;
      S.cy = drag.cy - (ev.clientY - drag.y) / z;
      draw();
    }
    readout(texelUnder(canvas, ev));
  });
  canvas.addEventListener("pointerdown", (ev) => {
    if (S.zoom === "fit") fixZoom(canvas);
    drag = { x: ev.clientX, y: ev.clientY, cx: S.cx, cy: S.cy };
    canvas.setPointerCapture(ev.pointerId);
  });
  canvas.addEventListener("pointerup", () => { drag = null; });
  canvas.addEventListener("wheel", (ev) => {
    ev.preventDefault();
    if (S.zoom === "fit") fixZoom(canvas);
    const steps = ZOOMS.slice(1);
    let i = steps.findIndex((z) => z >= S.zoom);
    i = Math.max(0, Math.min(steps.length - 1, i + (ev.deltaY < 0 ? 1 : -1)));
    // On the cursor: the point under it stays under it (texel = centre + offset / zoom).
    const rect = canvas.getBoundingClientRect();
    const dx = ev.clientX - rect.left - canvas.clientWidth / 2;
    const dy = ev.clientY - rect.top - canvas.clientHeight / 2;
    S.cx += dx / S.zoom - dx / steps[i];
    S.cy += dy / S.zoom - dy / steps[i];
    setZoom(steps[i]);
  }, { passive: false });
}
function fixZoom(canvas) {
  const sh = S.shown;
  const w = sh && !sh.cross ? sh.im.width : sh ? 4 * sh.n : 1, h = sh && !sh.cross ? sh.im.height : sh ? 3 * sh.n : 1;
  const z = zoomOf(canvas, w, h);
  S.cx = w / 2; S.cy = h / 2;
  S.zoom = ZOOMS.slice(1).reduce((best, v) => Math.abs(v - z) < Math.abs(best - z) ? v : best, 1);
  $("zoom").value = String(S.zoom);
}
function setZoom(z) {
  S.zoom = z;
  $("zoom").value = String(z);
  draw();
}
/** Zooms to `z` centred on texel (x, y) of the current image. */
function centreOn(x, y, z) {
  S.cx = x + 0.5; S.cy = y + 0.5;
  setZoom(z);
}
