// Drives `tessera view` with a non-power-of-two image, a lone cube map file, a --cube and an
// --array input in headless Chromium (puppeteer-core) and prints what the page showed as one
// JSON object on stdout; view_cube_test.py checks it against `tessera compress --cube/--array`,
// `decompress` and `compare`. Screenshots go to OUT.
//
//   node view_cube.mjs PUPPETEER_DIR CHROMIUM URL OUT cube|static|shot [SHOT.png [RIGHT]]
// "static" opens an --html export of good.png, bad.png and npot.png.
// "shot" only opens the first input in the cube cross with RIGHT (default: its heatmap) and
// saves SHOT.png (docs/images/tessera-view-cube.png was made so).
import { createRequire } from "node:module";
import { join } from "node:path";

const [dir, chromium, url, out, mode, shotPath, shotRight = "heatmap"] = process.argv.slice(2);
const puppeteer = createRequire(join(dir, "package.json"))("puppeteer-core");
const WAIT = { timeout: 120000, polling: 50 };  // every wait is bounded

const browser = await puppeteer.launch({
  executablePath: chromium, headless: true,
  args: ["--no-sandbox", "--disable-gpu", "--hide-scrollbars"],
});
const result = { errors: [], external: [], steps: {} };
try {
  const page = await browser.newPage();
  page.on("pageerror", (e) => result.errors.push(e.message));
  page.on("console", (m) => { if (m.type() === "error") result.errors.push(m.text()); });
  await page.setRequestInterception(true);
  page.on("request", (req) => {
    const u = req.url();
    const local = u.startsWith("data:") || (url.startsWith("file:") ? u.startsWith("file:")
                                                                     : u.startsWith(new URL(url).origin));
    if (!local) { result.external.push(u); req.abort(); } else req.continue();
  });
  await page.setViewport({ width: 1366, height: 768 });
  await page.goto(url);
  await page.waitForFunction(() => (document.body.dataset.drawn || "") !== "", WAIT);
  if (mode === "shot") await docsShot(page);
  else if (mode === "static") await staticScenario(page);
  else await scenario(page);
} catch (e) {
  result.errors.push("scenario: " + e.message);
} finally {
  await browser.close();
}
console.log(JSON.stringify(result));

/** Waits until the current result (an id starting with `prefix`) is drawn; what the page shows:
 *  drawn key, captions, command, metrics, options note and the download's bytes (base64). */
async function snapshot(page, prefix = "r") {
  await page.waitForFunction((p) => {
    const r = window.tesseraView.state.result || "";
    return r.startsWith(p) && (document.body.dataset.drawn || "").startsWith(r + ":");
  }, WAIT, prefix);
  return page.evaluate(async () => {
    const metrics = {};
    for (const tr of document.querySelectorAll("#metrics tr")) {
      metrics[tr.dataset.metric] = tr.cells[1].dataset.value || tr.cells[1].textContent;
    }
    const a = document.getElementById("download");
    let file = "";
    if (!a.hidden) {
      const bytes = new Uint8Array(await (await fetch(a.href)).arrayBuffer());
      let bin = "";
      for (const b of bytes) bin += String.fromCharCode(b);
      file = btoa(bin);
    }
    const text = (id) => document.getElementById(id).textContent;
    return { drawn: document.body.dataset.drawn, command: text("command"), metrics, file,
             file_name: a.download, caption_a: text("caption-a"), caption_b: text("caption-b"),
             note: document.getElementById("options-note").hidden ? "" : text("options-note"),
             error: text("error"), tabs: document.querySelectorAll("#tabs button").length };
  });
}

/** A hash of what `canvas` shows now (every texel of its backing store). */
async function canvasHash(page, canvas) {
  return page.evaluate((id) => {
    const c = document.getElementById(id);
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    let h = 2166136261, lit = 0;
    for (let i = 0; i < d.length; i += 4) {
      h = Math.imul(h ^ (d[i] | (d[i + 1] << 8) | (d[i + 2] << 16)), 16777619) >>> 0;
      if (d[i] !== 17 || d[i + 1] !== 17 || d[i + 2] !== 17) ++lit;  // not the #111 ground
    }
    return { hash: h, lit };
  }, canvas);
}

async function redraw(page) {
  await page.evaluate(() => window.tesseraView.draw());
  await page.evaluate(() => new Promise((ok) => requestAnimationFrame(() => requestAnimationFrame(ok))));
}

async function shot(page, name, width, height) {
  await page.setViewport({ width, height });
  await redraw(page);
  await new Promise((ok) => setTimeout(ok, 300));
  await page.screenshot({ path: name.startsWith("/") ? name : join(out, name) });
}

async function selectInput(page, index) {
  await page.select("#input", String(index));
  await page.waitForFunction((i) => window.tesseraView.state.input === i, WAIT, index);
}

async function scenario(page) {
  const s = result.steps;
  // Input 0: 100x60, not a power of two: its original and the fix, then --resize-pot.
  s.npot = await snapshot(page, "o");
  s.npot.original_lit = (await canvasHash(page, "canvas-a")).lit;
  await shot(page, "view-npot-1366x768.png", 1366, 768);
  await page.click("#options input[name=resize_pot]");
  s.npot_resized = await snapshot(page, "r");
  s.npot_resized.original_lit = (await canvasHash(page, "canvas-a")).lit;
  // Input 1: a cube map file with no reference: heatmaps disabled, said so.
  await selectInput(page, 1);
  s.lone = await snapshot(page, "r");
  s.lone.heatmap_disabled = await page.$eval("#right option[value=heatmap]", (o) => o.disabled);
  await page.select("#right", "heatmap");
  await redraw(page);
  s.lone.heatmap_caption = await page.$eval("#caption-b", (c) => c.textContent);
  await shot(page, "view-no-reference-1366x768.png", 1366, 768);
  await page.select("#right", "result");
  // Input 2: --cube: every face against its source, the result and its heatmap.
  await selectInput(page, 2);
  s.cube = await snapshot(page, "r");
  s.faces = [];
  for (let f = 0; f < 6; ++f) {
    await page.select("#face", String(f));
    await page.waitForFunction((k) => document.body.dataset.drawn.includes(k), WAIT, `:0:${f}:0:`);
    const face = await snapshot(page, "r");
    face.result = await canvasHash(page, "canvas-b");
    face.original = await canvasHash(page, "canvas-a");
    await page.select("#right", "heatmap");
    await redraw(page);
    face.heatmap = await canvasHash(page, "canvas-b");
    face.heatmap_caption = await page.$eval("#caption-b", (c) => c.textContent);
    await page.select("#right", "result");
    s.faces.push(face);
  }
  await page.select("#face", "0");
  await page.select("#mode", "cross");
  await page.waitForFunction(() => document.body.dataset.drawn.includes(":0:cross:"), WAIT);
  await redraw(page);
  s.cross_result = await canvasHash(page, "canvas-a");
  await page.select("#right", "heatmap");
  await redraw(page);
  s.cross_heatmap = await canvasHash(page, "canvas-a");
  s.cross_caption = await page.$eval("#caption-a", (c) => c.textContent);
  await shot(page, "view-cube-cross-heatmap-1366x768.png", 1366, 768);
  await shot(page, "view-cube-cross-heatmap-390x844.png", 390, 844);
  s.phone_overflow = await page.evaluate(() => document.documentElement.scrollWidth > window.innerWidth + 1);
  await page.setViewport({ width: 1366, height: 768 });
  await page.select("#right", "result");
  await page.select("#mode", "side");
  // Input 3: --array of 3 layers.
  await selectInput(page, 3);
  s.array = await snapshot(page, "r");
  s.layers = [];
  for (let l = 0; l < 3; ++l) {
    await page.select("#layer", String(l));
    await page.waitForFunction((k) => document.body.dataset.drawn.includes(k), WAIT, `:0:0:${l}:`);
    s.layers.push(await snapshot(page, "r"));
  }
  await shot(page, "view-array-1366x768.png", 1366, 768);
}

/** The docs' screenshot: the first input in the cube cross with its error heatmap. */
async function docsShot(page) {
  await snapshot(page, "r");
  await page.select("#mode", "cross");
  await page.waitForFunction(() => document.body.dataset.drawn.includes(":cross:"), WAIT);
  await page.select("#right", shotRight);
  await shot(page, shotPath, 1366, 768);
  result.steps.shot = shotPath;
}

/** The --html export with a bad input: the good one drawn, the bad one's error, the NPOT one's
 *  original and note. */
async function staticScenario(page) {
  const s = result.steps;
  s.good = await snapshot(page, "r");
  await selectInput(page, 1);
  await page.waitForFunction(() => document.getElementById("error").textContent.length > 0, WAIT);
  s.bad_error = await page.$eval("#error", (e) => e.textContent);
  await selectInput(page, 2);
  s.npot = await snapshot(page, "o");
  s.npot.original_lit = (await canvasHash(page, "canvas-a")).lit;
  await shot(page, "static-npot-390x844.png", 390, 844);
  s.phone_overflow = await page.evaluate(() => document.documentElement.scrollWidth > window.innerWidth + 1);
}
