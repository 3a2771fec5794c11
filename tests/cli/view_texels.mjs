// Reads every image's texels the way the page reads them (tesseraView.texels: the PNG blobs
// decoded by view_png.js, the .pvr blobs by view_pvrtc.js) in headless Chromium and prints them as one JSON object on stdout:
// view_texels_test.py checks them against the input and `tessera decompress`.
//
//   node view_texels.mjs PUPPETEER_DIR CHROMIUM URL
import { createRequire } from "node:module";
import { join } from "node:path";

const [dir, chromium, url] = process.argv.slice(2);
const puppeteer = createRequire(join(dir, "package.json"))("puppeteer-core");
const WAIT = { timeout: 120000, polling: 50 };  // every wait is bounded

const browser = await puppeteer.launch({
  executablePath: chromium, headless: true, args: ["--no-sandbox", "--disable-gpu"],
});
const result = { errors: [], results: [] };
try {
  const page = await browser.newPage();
  page.on("pageerror", (e) => result.errors.push(e.message));
  page.on("console", (m) => { if (m.type() === "error") result.errors.push(m.text()); });
  await page.goto(url);
  await page.waitForFunction(() => (document.body.dataset.drawn || "").startsWith("r"), WAIT);
  result.results = await page.evaluate(async () => {
    const b64 = (a) => { let s = ""; for (const v of a) s += String.fromCharCode(v); return btoa(s); };
    const out = [];
    for (const r of window.tesseraView.state.results.values()) {
      const images = [];
      for (const im of r.images) {
        const one = { level: im.level, layer: im.layer, face: im.face, width: im.width,
                      height: im.height, key: im.decoded };
        for (const k of ["decoded", "original"]) {
          if (im[k]) one[k] = b64((await window.tesseraView.texels(im[k], im.width, im.height)).data);
        }
        images.push(one);
      }
      out.push({ command: r.command, images });
    }
    return out;
  });
} catch (e) {
  result.errors.push("texels: " + e.message);
} finally {
  await browser.close();
}
console.log(JSON.stringify(result));
