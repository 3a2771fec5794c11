// Drives `tessera view` in headless Chromium (puppeteer-core, Debian's browser) through a fixed
// scenario and prints what the page showed as one JSON object on stdout; view_browser_test.py
// checks it against `tessera compress` / `compare` / `decompress`. Screenshots go to OUT.
//
//   node view_browser.mjs PUPPETEER_DIR CHROMIUM URL OUT server|static
import { createRequire } from "node:module";
import { join } from "node:path";

const [dir, chromium, url, out, mode] = process.argv.slice(2);
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
    const local = mode === "static" ? u.startsWith("data:") || u.startsWith("file:")
                                    : u.startsWith("data:") || u.startsWith(new URL(url).origin);
    if (!local) { result.external.push(u); req.abort(); } else req.continue();
  });
  await page.setViewport({ width: 1366, height: 768 });
  await page.goto(url);
  await page.waitForFunction(() => (document.body.dataset.drawn || "").startsWith("r"), WAIT);
  result.steps.first = await snapshot(page);
  if (mode === "server") await serverScenario(page);
  else await staticScenario(page);
} catch (e) {
  result.errors.push("scenario: " + e.message);
} finally {
  await browser.close();
}
console.log(JSON.stringify(result));

/** What the page shows now: drawn key, command, metrics, the texture's bytes (base64). */
async function snapshot(page) {
  await page.waitForFunction(() => (document.body.dataset.drawn || "").startsWith(
      window.tesseraView.state.result + ":"), WAIT);
  return page.evaluate(async () => {
    const metrics = {};
    for (const tr of document.querySelectorAll("#metrics tr")) {
      metrics[tr.dataset.metric] = tr.cells[1].dataset.value || tr.cells[1].textContent;
    }
    const a = document.getElementById("download");
    const bytes = new Uint8Array(await (await fetch(a.href)).arrayBuffer());
    let bin = "";
    for (const b of bytes) bin += String.fromCharCode(b);
    return { drawn: document.body.dataset.drawn, command: document.getElementById("command").textContent,
             metrics, file: btoa(bin), file_name: a.download,
             tabs: document.querySelectorAll("#tabs button").length };
  });
}

async function waitDrawnChange(page, before) {
  await page.waitForFunction((b) => document.body.dataset.drawn && document.body.dataset.drawn !== b,
                             WAIT, before);
}

/** Zooms to 32x (from fit: the centre stays) and reads the texel under the middle of `canvas`. */
async function texelAtCentre(page, canvas, zoom) {
  if (zoom) {
    await page.select("#zoom", zoom);
    await page.waitForFunction((z) => document.body.dataset.drawn.endsWith(":" + z), WAIT, zoom);
  }
  const box = await (await page.$(canvas)).boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.waitForFunction(() => document.getElementById("readout").dataset.decoded, WAIT);
  return page.evaluate(() => ({ ...document.getElementById("readout").dataset,
                                text: document.getElementById("readout").textContent }));
}

/** The readout's texel at page point (x, y) (the pointer moved there). */
async function readoutAt(page, x, y) {
  await page.mouse.move(x + 1, y);
  await page.mouse.move(x, y);
  await page.waitForFunction(() => document.getElementById("readout").dataset.decoded, WAIT);
  return page.evaluate(() => ({ x: document.getElementById("readout").dataset.x,
                                y: document.getElementById("readout").dataset.y }));
}

/** One wheel step out at an off-centre point of `canvas`: the texel under it before and after. */
async function wheelAt(page, canvas) {
  const box = await (await page.$(canvas)).boundingBox();
  const x = box.x + box.width * 0.4, y = box.y + box.height * 0.4;
  const before = await readoutAt(page, x, y);
  const zoom = await page.evaluate(() => window.tesseraView.state.zoom);
  await page.mouse.wheel({ deltaY: 100 });
  await page.waitForFunction((z) => window.tesseraView.state.zoom !== z &&
      document.body.dataset.drawn.endsWith(":" + window.tesseraView.state.zoom), WAIT, zoom);
  const after = await readoutAt(page, x, y);
  return { before, after, zoom_before: zoom,
           zoom_after: await page.evaluate(() => window.tesseraView.state.zoom) };
}

async function shot(page, name, width, height) {
  await page.setViewport({ width, height });
  await page.evaluate(() => new Promise((ok) => requestAnimationFrame(() => requestAnimationFrame(ok))));
  await page.evaluate(() => window.tesseraView.draw());
  await new Promise((ok) => setTimeout(ok, 300));
  await page.screenshot({ path: join(out, name) });
}

async function serverScenario(page) {
  const s = result.steps;
  // Options tried live: quality, then --alpha-weighted; each re-encodes in the server.
  await page.select("#options select[name=quality]", "high");
  await page.waitForFunction(() => document.getElementById("command").textContent.includes("--quality high"), WAIT);
  s.high = await snapshot(page);
  await page.click("#options input[name=alpha_weighted]");
  await page.waitForFunction(() => document.getElementById("command").textContent.includes("--alpha-weighted"), WAIT);
  s.weighted = await snapshot(page);
  await page.click("#pin");
  s.pinned_rows = await page.$$eval("#pinned tbody tr", (r) => r.length);
  await shot(page, "view-1366x768.png", 1366, 768);
  // Error heatmap with its colour bar.
  let before = await page.evaluate(() => document.body.dataset.drawn);
  await page.select("#right", "heatmap");
  await page.waitForFunction(() => document.getElementById("colourbar").dataset.scale, WAIT);
  s.colourbar = await page.$eval("#colourbar", (c) => !c.hidden && c.width > 0 && c.dataset.unit === "levels");
  await shot(page, "view-heatmap-1366x768.png", 1366, 768);
  await page.select("#right", "heatmap_premultiplied");
  await page.waitForFunction(() => document.getElementById("caption-b").textContent.includes("colour x alpha"), WAIT);
  s.premultiplied_heatmap = await page.$eval("#caption-b", (c) => c.textContent);
  await shot(page, "view-heatmap-premultiplied-1366x768.png", 1366, 768);
  await page.select("#right", "result");
  s.sprite_texel = await texelAtCentre(page, "#canvas-b", "32");
  await shot(page, "view-zoom32-1366x768.png", 1366, 768);
  s.wheel = await wheelAt(page, "#canvas-b");
  await page.select("#zoom", "fit");
  await page.select("#mode", "wipe");
  await shot(page, "view-wipe-1366x768.png", 1366, 768);
  await page.select("#mode", "side");
  await shot(page, "view-390x844.png", 390, 844);
  s.phone_overflow = await page.evaluate(() => document.documentElement.scrollWidth > window.innerWidth + 1);
  // The cube map: level 1, face 3 (-Y), its texel, then the cross.
  await page.setViewport({ width: 1366, height: 768 });
  await page.select("#input", "1");
  await page.waitForFunction(() => window.tesseraView.state.input === 1 &&
      document.body.dataset.drawn.startsWith(window.tesseraView.state.result + ":"), WAIT);
  s.cube_first = await snapshot(page);
  before = s.cube_first.drawn;
  // The pointer over the face, still while the level and face change: the readout follows.
  const cb = await (await page.$("#canvas-b")).boundingBox();
  await page.mouse.move(cb.x + cb.width / 2, cb.y + cb.height / 2);
  await page.waitForFunction(() => document.getElementById("readout").textContent.includes("level 0"), WAIT);
  await page.select("#level", "1");
  await page.select("#face", "3");
  await page.waitForFunction(() => document.body.dataset.drawn.includes(":1:3:0:"), WAIT);
  s.cube_readout = await page.$eval("#readout", (e) => e.textContent);  // not moved since level 0
  s.cube = await snapshot(page);
  s.cube_texel = await texelAtCentre(page, "#canvas-b", null);
  await page.select("#level", "0");
  await page.select("#mode", "cross");
  await page.waitForFunction(() => document.body.dataset.drawn.includes(":0:cross:"), WAIT);
  await shot(page, "view-cube-cross-1366x768.png", 1366, 768);
  await page.select("#mode", "side");
  // A bad input: a one-line error on the page; the server still answers.
  await page.select("#input", "2");
  await page.waitForFunction(() => document.getElementById("error").textContent.length > 0, WAIT);
  s.bad_error = await page.$eval("#error", (e) => e.textContent);
  await page.select("#input", "0");
  await waitDrawnChange(page, before);
  s.back = await snapshot(page);
}

async function staticScenario(page) {
  const s = result.steps;
  s.results = [];
  const tabs = await page.$$eval("#tabs button", (b) => b.map((x) => x.dataset.result));
  for (const id of tabs) {
    await page.click(`#tabs button[data-result="${id}"]`);
    await page.waitForFunction((r) => document.body.dataset.drawn.startsWith(r + ":"), WAIT, id);
    s.results.push(await snapshot(page));
  }
  s.texel = await texelAtCentre(page, "#canvas-b", "32");
  await page.select("#zoom", "fit");
  await shot(page, "static-1366x768.png", 1366, 768);
  await shot(page, "static-390x844.png", 390, 844);
}
