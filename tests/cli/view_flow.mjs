// Drives `tessera view`'s workflow in headless Chromium (puppeteer-core) and prints what the page
// showed as one JSON object on stdout; view_flow_test.py checks it. Screenshots go to OUT.
//
//   node view_flow.mjs PUPPETEER_DIR CHROMIUM URL OUT overview|open|evict|shot [FILE...]
//   overview: the overview's order, then a click on its first item.
//   open:     FILEs through the "open…" picker (uploadFile); the inputs and errors after each.
//   evict:    input 0, then input 1 in two settings (evicting input 0's result under
//             --memory), then input 0 again: the note and the result encoded again.
//   shot:     the overview at 1366x768 and 390x844 (OUT/FILE for the first).
import { createRequire } from "node:module";
import { join } from "node:path";

const [dir, chromium, url, out, mode, ...files] = process.argv.slice(2);
const puppeteer = createRequire(join(dir, "package.json"))("puppeteer-core");
const WAIT = { timeout: 300000, polling: 50 };  // every wait is bounded

const browser = await puppeteer.launch({
  executablePath: chromium, headless: true,
  args: ["--no-sandbox", "--disable-gpu", "--hide-scrollbars"],
});
const result = { errors: [], external: [], steps: {} };
try {
  const page = await browser.newPage();
  page.on("pageerror", (e) => result.errors.push(e.message));
  page.on("console", (m) => {
    // A blob the server evicted answers 404, which is what the evict scenario is about.
    if (m.type() === "error" && !(mode === "evict" && m.text().includes("404"))) result.errors.push(m.text());
  });
  await page.setRequestInterception(true);
  page.on("request", (req) => {
    const u = req.url();
    const local = u.startsWith("data:") || u.startsWith("file:") || u.startsWith(new URL(url).origin);
    if (!local) { result.external.push(u); req.abort(); } else req.continue();
  });
  await page.setViewport({ width: 1366, height: 768 });
  await page.goto(url);
  await page.waitForFunction(() => (document.body.dataset.drawn || "").startsWith("r"), WAIT);
  if (mode === "overview") await overview(page);
  else if (mode === "open") await open(page);
  else if (mode === "evict") await evict(page);
  else if (mode === "shot") await shot(page);
} catch (e) {
  result.errors.push("scenario: " + e.message);
} finally {
  await browser.close();
}
console.log(JSON.stringify(result));

function drawnNow() {
  return (document.body.dataset.drawn || "").startsWith(window.tesseraView.state.result + ":");
}

async function showOverview(page) {
  await page.click("#overview-button");
  await page.waitForFunction(() => document.body.dataset.overview === "ready"
      && [...document.querySelectorAll("#overview-grid img")].every((i) => i.complete), WAIT);
}

async function overview(page) {
  await showOverview(page);
  result.steps.order = await page.$$eval("#overview-grid button", (bs) => bs.map((b) => ({
    index: Number(b.dataset.index), psnr: b.dataset.psnr, state: b.dataset.state,
    name: b.querySelector(".name").textContent, thumbnail: !!b.querySelector("img") && b.querySelector("img").naturalWidth })));
  await page.screenshot({ path: join(out, "flow-overview-1366x768.png") });
  await page.click("#overview-grid button:nth-child(2)");
  await page.waitForFunction(drawnNow, WAIT);
  result.steps.clicked = await page.evaluate(() => ({ input: window.tesseraView.state.input,
    overview_hidden: document.getElementById("overview").hidden }));
  const links = await page.$$eval("#downloads a", (as) => as.map((a) => [a.dataset.as, a.download]));
  result.steps.downloads = links;
  // The page's own download link of the KTX 2.0 file: its bytes, to compare with compress.
  result.steps.ktx2 = await page.evaluate(async () => {
    const a = document.querySelector('#downloads a[data-as="ktx2"]');
    if (!a) return null;  // a static view has none
    const bytes = new Uint8Array(await (await fetch(a.href)).arrayBuffer());
    let bin = "";
    for (const b of bytes) bin += String.fromCharCode(b);
    return { name: a.download, file: btoa(bin), command: document.getElementById("command").textContent };
  });
}

async function open(page) {
  const picker = await page.$("#open-file");
  result.steps.open = [];
  for (const f of files) {
    const before = await page.evaluate(() => window.tesseraView.data.inputs.length);
    await picker.uploadFile(f);
    await page.waitForFunction((n) => window.tesseraView.data.inputs.length > n
        && document.getElementById("note").hidden, WAIT, before);
    const inp = await page.evaluate(() => window.tesseraView.data.inputs.at(-1));
    if (!inp.error && inp.kind === "image") await page.waitForFunction(drawnNow, WAIT);
    result.steps.open.push(await page.evaluate(() => ({
      input: window.tesseraView.data.inputs.at(-1), selected: window.tesseraView.state.input,
      options: document.querySelectorAll("#input option").length,
      error: document.getElementById("error").hidden ? "" : document.getElementById("error").textContent,
      command: document.getElementById("command").textContent })));
  }
  await page.screenshot({ path: join(out, "flow-open-1366x768.png") });
}

async function pick(page, quality) {
  const before = await page.evaluate(() => window.tesseraView.state.result);
  await page.select('#options select[name="quality"]', quality);
  await page.waitForFunction((b) => window.tesseraView.state.result !== b && !window.tesseraView.state.jobs, WAIT, before);
  await page.waitForFunction(drawnNow, WAIT);
}

async function evict(page) {
  const first = await page.evaluate(() => {
    const S = window.tesseraView.state;
    return { id: S.result, settings: S.results.get(S.result).settings };
  });
  await page.evaluate(() => window.tesseraView.selectInput(1));
  await page.waitForFunction(() => window.tesseraView.state.input === 1 && !window.tesseraView.state.jobs
      && (document.body.dataset.drawn || "").startsWith(window.tesseraView.state.result + ":"), WAIT);
  await pick(page, "fast");
  result.steps.first = first;
  result.steps.evicted_before = await page.evaluate(async (id) => {
    const r = await fetch(`/api/pin?id=${id}&pinned=0&token=${window.tesseraView.data.token}`);
    return r.status;
  }, first.id);
  await page.evaluate(() => window.tesseraView.selectInput(0));  // its tab: the evicted result
  await page.waitForFunction((id) => window.tesseraView.state.result !== id && !window.tesseraView.state.jobs
      && (document.body.dataset.drawn || "").startsWith(window.tesseraView.state.result + ":"), WAIT, first.id);
  result.steps.after = await page.evaluate(() => {
    const S = window.tesseraView.state;
    return { id: S.result, settings: S.results.get(S.result).settings, input: S.input,
             note: document.body.dataset.note || "", tabs: document.querySelectorAll("#tabs button").length,
             error: document.getElementById("error").hidden ? "" : document.getElementById("error").textContent };
  });
  await page.screenshot({ path: join(out, "flow-evicted-1366x768.png") });
}

async function shot(page) {
  await showOverview(page);
  await page.screenshot({ path: join(out, files[0] || "flow-overview-1366x768.png") });
  await page.setViewport({ width: 390, height: 844 });
  await new Promise((ok) => setTimeout(ok, 300));
  await page.screenshot({ path: join(out, "flow-overview-390x844.png") });
  result.steps.phone_overflow = await page.evaluate(() => document.documentElement.scrollWidth > window.innerWidth);
}
