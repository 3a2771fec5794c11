// tessera view: an artist's workflow over many inputs (after view.js, same scope): the overview
// of every input sorted worst-first, files opened or dropped on the page (server mode), the
// downloads of a result in every container, and results the server evicted encoded again.
"use strict";
const OPEN_LIMIT = 256 * 1024 * 1024;  // the server's cap on POST /api/open (view_http.h)
const OV = { shown: false, timer: 0, items: [] };

function showNote(text) {
  $("note").hidden = !text;
  $("note").textContent = text;
  document.body.dataset.note = text;
}
function refillInputs() {
  fillSelect($("input"), D.inputs.map((i) => [i.index, i.name + (i.error ? " (error)" : "")]), S.input);
}

// ---- overview ------------------------------------------------------------------------------
/** Worst first: inputs that could not be read, then the measured ones by PSNR (lowest first;
 *  null = identical, the best) and, at equal PSNR, the larger max error first; then those still
 *  encoding, then textures (nothing to measure them against); each group in input order. */
function worstFirst(a, b) {
  const group = (x) => x.state === "error" ? 0 : x.state === "done" ? 1 : x.state === "texture" ? 3 : 2;
  if (group(a) !== group(b)) return group(a) - group(b);
  if (group(a) === 1) {
    const pa = a.psnr === null ? Infinity : a.psnr, pb = b.psnr === null ? Infinity : b.psnr;
    if (pa !== pb) return pa - pb;
    if (a.max_abs !== b.max_abs) return b.max_abs - a.max_abs;
  }
  return a.index - b.index;
}
const sameSettings = (a, b) => ["format", "quality", "alpha_bleed", "alpha_weighted", "premultiply",
  "normal_map", "srgb", "mip_levels"].every((k) => a[k] === b[k])
  && (!a.mip_levels || a.mip_filter === b.mip_filter);

/** A static view's overview: the exported results at the overview's settings. */
function staticOverview() {
  return D.inputs.map((inp) => {
    const r = resultsOf(inp.index).find((x) => x.settings && sameSettings(x.settings, D.overview_settings));
    const e = { index: inp.index, name: inp.name, kind: inp.kind, thumbnail: inp.thumbnail || "",
                psnr: null, max_abs: null };
    if (inp.error) return { ...e, state: "error", error: inp.error };
    if (!r) return { ...e, state: "texture" };
    return { ...e, state: "done", psnr: r.metrics.psnr_rgb, max_abs: r.metrics.max_abs };
  });
}

function overviewCell(x) {
  const b = document.createElement("button");
  b.type = "button";
  b.dataset.index = x.index;
  b.dataset.state = x.state;
  b.dataset.psnr = x.psnr === null ? "inf" : String(x.psnr);
  b.className = "state-" + x.state;
  if (x.thumbnail) {
    const im = document.createElement("img");
    im.alt = "";
    im.src = blobUrl(x.thumbnail);
    b.appendChild(im);
  }
  const name = document.createElement("span");
  name.className = "name";
  name.textContent = x.name;
  name.title = x.name;
  const score = document.createElement("span");
  score.className = "score";
  score.textContent = x.state === "done" ? `${fmt(x.psnr)} dB · max ${x.max_abs}`
      : x.state === "error" ? "cannot read" : x.state === "texture" ? "texture as it is"
      : x.state === "running" ? "encoding…" : "queued";
  if (x.error) b.title = x.error;
  b.append(name, score);
  b.onclick = () => { showOverview(false); selectInput(x.index); };
  return b;
}

function drawOverview() {
  const items = [...OV.items].sort(worstFirst), grid = $("overview-grid");
  grid.replaceChildren(...items.map(overviewCell));
  const waiting = items.filter((x) => !["done", "error", "texture"].includes(x.state)).length;
  const s = D.mode === "static" ? D.overview_settings : OV.settings;
  $("overview-note").textContent = `${items.length} input(s), worst first (lowest PSNR RGB at `
      + `${s ? label({ settings: s }) : "the default settings"}; ties: largest max error)`
      + (waiting ? ` · ${waiting} still encoding` : "");
  document.body.dataset.overview = waiting ? "pending" : "ready";
}

async function pollOverview() {
  clearTimeout(OV.timer);
  if (!OV.shown) return;
  if (D.mode === "static") {
    OV.items = staticOverview();
    drawOverview();
    return;
  }
  try {
    const j = await api("/api/overview");
    OV.items = j.inputs;
    OV.settings = j.settings;
    drawOverview();
    if (OV.items.some((x) => !["done", "error", "texture"].includes(x.state))) {
      OV.timer = setTimeout(pollOverview, 500);
    }
  } catch (e) {
    showError(e.message);
  }
}

function showOverview(on) {
  OV.shown = on;
  $("overview").hidden = !on;
  document.body.classList.toggle("overview", on);
  $("overview-button").setAttribute("aria-pressed", String(on));
  $("overview-button").textContent = on ? "back to the image" : "overview";
  if (on) pollOverview();
  else draw();
}

// ---- open and drop (server mode) -----------------------------------------------------------
/** Sends each file to the server as a new input; the last one opened is shown. */
async function openFiles(files) {
  let last = -1;
  for (const f of files) {
    if (f.size > OPEN_LIMIT) {
      showError(`${f.name}: larger than the server takes (256 MiB)`);
      continue;
    }
    showNote(`opening ${f.name}…`);
    try {
      const r = await fetch(`/api/open?name=${encodeURIComponent(f.name)}&token=${encodeURIComponent(D.token)}`,
          { method: "POST", headers: { "Content-Type": "application/octet-stream" }, body: f });
      const j = await r.json().catch(() => ({ error: `HTTP ${r.status}` }));
      if (!r.ok) throw new Error(`${f.name}: ${j.error || "HTTP " + r.status}`);
      if (!D.inputs.some((i) => i.index === j.input.index)) D.inputs.push(j.input);
      for (const x of j.results) addResult(x);
      last = j.input.index;
    } catch (e) {
      showError(e.message);
    }
  }
  showNote("");
  refillInputs();
  if (last >= 0) {
    if (OV.shown) pollOverview();
    else selectInput(last);
  }
}

// ---- downloads -----------------------------------------------------------------------------
/** Links to the result in the other containers, its decoded image and its heatmap (server:
 *  /api/download; static: the blobs the export holds). */
function showDownloads(r) {
  const box = $("downloads");
  box.replaceChildren();
  if (!r || !r.file_name) return;  // none, or an original shown without an encode
  const stem = r.file_name.replace(/\.[^.]*$/, ""), im = r.images[0];
  const server = D.mode === "server";  // the server converts on request
  const wanted = [["ktx", `${stem}.ktx`, server ? r.file : r.files && r.files.ktx],
    ["ktx2", `${stem}.ktx2`, server ? r.file : r.files && r.files.ktx2],
    ["png", `${stem}_decoded.png`, server ? r.file : ""],
    ["heatmap", `${stem}_heatmap.png`, im && im.heatmap]];
  for (const [as, name, key] of wanted) {
    if (!key) continue;
    const a = document.createElement("a");
    a.href = D.mode === "server"
        ? `/api/download?id=${encodeURIComponent(r.id)}&as=${as}&token=${encodeURIComponent(D.token)}`
        : blobUrl(key);
    a.download = name;
    a.dataset.as = as;
    a.textContent = as === "png" ? "decoded .png" : as === "heatmap" ? "heatmap .png" : "." + as;
    box.appendChild(a);
  }
}

// ---- evicted results -----------------------------------------------------------------------
/** A blob of the shown result is gone (404): the server evicted the result under --memory.
 *  Its settings are encoded again, as picking them again would; the tab stays until the new
 *  result replaces it. True when handled. */
function reencodeEvicted(err) {
  const r = S.results.get(S.result);
  if (D.mode !== "server" || err.status !== 404 || !r || !r.settings || r.evicted) return false;
  r.evicted = true;
  showNote(`${label(r)}: the server dropped this result to stay under --memory; encoding it again`);
  encode(r.settings).then(() => {
    if (S.result !== r.id) S.results.delete(r.id);
  });
  return true;
}

/** Whether the server still holds result `r` (its job goes with it): a result whose texels the
 *  page has cached would draw, but its downloads would not be there. */
async function checkEvicted(r) {
  if (D.mode !== "server" || !r.job || r.evicted) return;
  const res = await fetch(`/api/job?id=${encodeURIComponent(r.job)}&token=${encodeURIComponent(D.token)}`)
      .catch(() => null);
  if (res && res.status === 404 && S.result === r.id) reencodeEvicted({ status: 404 });
}

function setupFlow() {
  $("overview-button").onclick = () => showOverview(!OV.shown);
  if (D.mode !== "server") return;
  $("open-button").hidden = false;
  $("open-button").onclick = () => $("open-file").click();
  $("open-file").onchange = () => { openFiles([...$("open-file").files]); $("open-file").value = ""; };
  const body = document.body;
  body.addEventListener("dragover", (ev) => { ev.preventDefault(); body.classList.add("dropping"); });
  body.addEventListener("dragleave", () => body.classList.remove("dropping"));
  body.addEventListener("drop", (ev) => {
    ev.preventDefault();
    body.classList.remove("dropping");
    if (ev.dataTransfer && ev.dataTransfer.files.length) openFiles([...ev.dataTransfer.files]);
  });
}
