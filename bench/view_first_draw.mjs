// tessera view: time from navigation to the first draw (document.body.dataset.drawn set: the
// input's original, "original:...", while its first encode runs, or a result, "r..."), and to
// the first result's draw, with a fresh `tessera view INPUT --no-open` server per run (so the
// first encode is counted), in headless Chromium at 1366x768. Prints one line per run and the
// medians.
//
//   node bench/view_first_draw.mjs TESSERA PUPPETEER_DIR INPUT [RUNS=3] [CHROMIUM=/usr/bin/chromium]
//
// PUPPETEER_DIR holds node_modules/puppeteer-core (scripts/setup.sh; -DTESSERA_PUPPETEER).
// A 4096² input: upscale a photo of ../shared/data/images into /tmp, e.g. with python3-pil:
//   Image.open("ldr-rgb-diffuse.png").resize((4096, 4096), Image.BICUBIC).save("/tmp/big.png")
import { spawn } from "node:child_process";
import { createRequire } from "node:module";
import { join } from "node:path";

const [tessera, dir, input, runsArg, chromiumArg] = process.argv.slice(2);
if (!tessera || !dir || !input) {
  console.error("usage: node view_first_draw.mjs TESSERA PUPPETEER_DIR INPUT [RUNS] [CHROMIUM]");
  process.exit(2);
}
const runs = Number(runsArg || 3), chromium = chromiumArg || "/usr/bin/chromium";
const puppeteer = createRequire(join(dir, "package.json"))("puppeteer-core");

/** Starts the server; resolves to [process, URL] once it prints its URL. */
function serve() {
  return new Promise((ok, bad) => {
    const p = spawn(tessera, ["view", input, "--no-open"], { stdio: ["ignore", "pipe", "inherit"] });
    let text = "";
    p.stdout.on("data", (b) => {
      text += b;
      const line = text.split("\n").find((l) => l.startsWith("http://"));
      if (line) ok([p, line.trim()]);
    });
    p.on("exit", (rc) => bad(new Error(`tessera view exited ${rc}`)));
  });
}

const firsts = [], times = [], pageTimes = [];
const browser = await puppeteer.launch({ executablePath: chromium, headless: true,
                                         args: ["--no-sandbox", "--disable-gpu"] });
try {
  for (let i = 0; i < runs; ++i) {
    const [server, url] = await serve();
    try {
      const page = await browser.newPage();
      await page.setViewport({ width: 1366, height: 768 });
      const t0 = performance.now();
      await page.goto(url);
      // Three waits at once: the first draw, the encode's result reaching the page, its draw
      // (from the result in the page to its draw is what the page itself spends).
      const since = () => performance.now() - t0, WAIT = { timeout: 600000, polling: 20 };
      const [[what, first], encoded, ms] = await Promise.all([
        page.waitForFunction(() => document.body.dataset.drawn, WAIT)
            .then(async (h) => [await h.jsonValue(), since()]),
        page.waitForFunction(() => window.tesseraView && window.tesseraView.state.results.size, WAIT)
            .then(since),
        page.waitForFunction(() => (document.body.dataset.drawn || "").startsWith("r"), WAIT)
            .then(since)]);
      firsts.push(first);
      times.push(ms);
      pageTimes.push(ms - encoded);
      console.log(`run ${i + 1}: first draw (${what.split(":")[0]}) ${(first / 1000).toFixed(2)} s; ` +
                  `result drawn ${(ms / 1000).toFixed(2)} s (in the page at ` +
                  `${(encoded / 1000).toFixed(2)} s, page drawing ${((ms - encoded) / 1000).toFixed(2)} s)`);
      await page.close();
    } finally {
      server.removeAllListeners("exit");
      server.kill("SIGTERM");
    }
  }
} finally {
  await browser.close();
}
const median = (v) => [...v].sort((a, b) => a - b)[v.length >> 1] / 1000;
console.log(`median of ${runs}: first draw ${median(firsts).toFixed(2)} s, result drawn ` +
            `${median(times).toFixed(2)} s (page drawing ${median(pageTimes).toFixed(2)} s)`);
