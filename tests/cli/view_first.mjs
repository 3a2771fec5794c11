// Drives `tessera view` in headless Chromium (puppeteer-core) with the page's encode requests
// held back, so the input has no result yet: the page must draw the input's original (the
// server's "original" blob) with the right pane saying "encoding…", its readout reading the
// original; then the requests go on and the result is drawn as usual. Prints what the page
// showed as one JSON object on stdout (view_first_test.py checks it). Screenshots go to OUT.
//
//   node view_first.mjs PUPPETEER_DIR CHROMIUM URL OUT
import { createRequire } from "node:module";
import { join } from "node:path";

const [dir, chromium, url, out] = process.argv.slice(2);
const puppeteer = createRequire(join(dir, "package.json"))("puppeteer-core");
const WAIT = { timeout: 120000, polling: 50 };  // every wait is bounded

const browser = await puppeteer.launch({
  executablePath: chromium, headless: true,
  args: ["--no-sandbox", "--disable-gpu", "--hide-scrollbars"],
});
const result = { errors: [], steps: {} };
const held = [];
let holding = true;
try {
  const page = await browser.newPage();
  page.on("pageerror", (e) => result.errors.push(e.message));
  page.on("console", (m) => { if (m.type() === "error") result.errors.push(m.text()); });
  await page.setRequestInterception(true);
  page.on("request", (req) => {
    if (holding && req.url().includes("/api/encode")) held.push(req);
    else req.continue();
  });
  await page.setViewport({ width: 1366, height: 768 });
  await page.goto(url);
  await page.waitForFunction(() => (document.body.dataset.drawn || "").startsWith("original:"), WAIT);
  const s = result.steps;
  s.first = await state(page);
  s.held = held.length;
  await page.select("#zoom", "32");
  await page.waitForFunction(() => document.body.dataset.drawn === "original:0:32", WAIT);
  s.texel = await texelAtCentre(page);
  await shot(page, "view-first-original-1366x768.png");
  await page.select("#mode", "wipe");
  await page.waitForFunction(() => document.getElementById("caption-a").textContent.startsWith("wipe: original"), WAIT);
  s.wipe = await state(page);
  await shot(page, "view-first-original-wipe-1366x768.png");
  await page.select("#mode", "side");
  await page.setViewport({ width: 390, height: 844 });
  await page.evaluate(() => window.tesseraView.draw());
  await shot(page, "view-first-original-390x844.png");
  s.phone_overflow = await page.evaluate(() => document.documentElement.scrollWidth > window.innerWidth + 1);
  await page.setViewport({ width: 1366, height: 768 });
  // The encode goes on: the result replaces the "encoding…" pane, the readout gets its texel.
  holding = false;
  for (const req of held.splice(0)) req.continue();
  await page.waitForFunction(() => (document.body.dataset.drawn || "").startsWith("r"), WAIT);
  s.after = await state(page);
  s.after_texel = await texelAtCentre(page);
  await shot(page, "view-first-result-1366x768.png");
} catch (e) {
  result.errors.push("scenario: " + e.message);
} finally {
  await browser.close();
}
console.log(JSON.stringify(result));

async function state(page) {
  return page.evaluate(() => ({
    drawn: document.body.dataset.drawn,
    results: window.tesseraView.state.results.size,
    caption_a: document.getElementById("caption-a").textContent,
    caption_b: document.getElementById("caption-b").textContent,
    busy: !document.getElementById("busy").hidden,
  }));
}

/** Moves the pointer to the middle of the left pane and reads the readout there. */
async function texelAtCentre(page) {
  const box = await (await page.$("#canvas-a")).boundingBox();
  await page.mouse.move(box.x + box.width / 2 + 1, box.y + box.height / 2 + 1);
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.waitForFunction(() => document.getElementById("readout").dataset.original, WAIT);
  return page.evaluate(() => ({ ...document.getElementById("readout").dataset,
                                text: document.getElementById("readout").textContent }));
}

async function shot(page, name) {
  await page.evaluate(() => new Promise((ok) => requestAnimationFrame(() => requestAnimationFrame(ok))));
  await page.screenshot({ path: join(out, name) });
}
