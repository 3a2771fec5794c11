// The page's own heatmaps, scale control, max filter and keyboard shortcuts, in headless
// Chromium (puppeteer-core) on a `tessera view --html` export of texture + reference pairs.
// Prints one JSON object on stdout; view_heatmap_test.py checks it. Screenshots go to OUT.
//
//   node view_heatmap.mjs PUPPETEER_DIR CHROMIUM URL OUT [URL2 URL3]
// URL: texture + reference pairs "low" and "one"; URL2: an image with alpha; URL3: a normal map
// encoded with --normal-map.
import { createRequire } from "node:module";
import { join } from "node:path";

const [dir, chromium, url, out, url2, url3] = process.argv.slice(2);
const puppeteer = createRequire(join(dir, "package.json"))("puppeteer-core");
const WAIT = { timeout: 120000, polling: 50 };  // every wait is bounded

const browser = await puppeteer.launch({
  executablePath: chromium, headless: true,
  args: ["--no-sandbox", "--disable-gpu", "--hide-scrollbars"],
});
const result = { errors: [], steps: {} };
try {
  const page = await browser.newPage();
  page.on("pageerror", (e) => result.errors.push(e.message));
  page.on("console", (m) => { if (m.type() === "error") result.errors.push(m.text()); });
  await page.setViewport({ width: 1366, height: 768 });
  await page.goto(url);
  await page.waitForFunction(() => (document.body.dataset.drawn || "").startsWith("r"), WAIT);
  await scenario(page, result.steps);
} catch (e) {
  result.errors.push("scenario: " + e.message);
} finally {
  await browser.close();
}
console.log(JSON.stringify(result));

/** Draws what the page's state says now and waits for it (draw() resolves once drawn; a
 *  draw started before, by the change just made, gives way to it). */
async function settled(page) {
  await page.evaluate(() => window.tesseraView.draw());
  await page.evaluate(() => new Promise((ok) => requestAnimationFrame(() => requestAnimationFrame(ok))));
}
async function select(page, id, value) {
  await page.select("#" + id, String(value));
  await settled(page);
}
/** Opens input `name`'s result made from the texture file (label "file ..."). */
async function openPair(page, name) {
  const index = await page.evaluate((n) => window.tesseraView.data.inputs.findIndex((i) =>
      i.kind === "image" && i.name.startsWith(n + ".")), name);
  await page.select("#input", String(index));
  await page.waitForFunction(() => document.querySelector("#tabs button"), WAIT);
  const id = await page.$$eval("#tabs button", (bs) => bs.find((b) =>
      b.textContent.startsWith("file ")).dataset.result);
  await page.click(`#tabs button[data-result="${id}"]`);
  await page.waitForFunction((r) => (document.body.dataset.drawn || "").startsWith(r + ":"), WAIT, id);
  await settled(page);
}
/** The right pane's canvas pixels over the image: [x0, y0, w, h] in image texels, at zoom 1
 *  with the image placed on whole pixels. Returns {texels: [x0, y0, w, h], rgba: base64}. */
async function paneAtZoom1(page) {
  await page.evaluate(() => {
    const v = window.tesseraView, s = v.state, c = document.getElementById("canvas-b");
    const im = v.state.shown.im;
    s.zoom = 1;
    document.getElementById("zoom").value = "1";
    // The centre texel lands on a whole pixel: c.clientWidth / 2 - cx is an integer.
    s.cx = Math.floor(im.width / 2) + (c.clientWidth % 2) / 2;
    s.cy = Math.floor(im.height / 2) + (c.clientHeight % 2) / 2;
  });
  await settled(page);
  return page.evaluate(() => {
    const v = window.tesseraView, s = v.state, c = document.getElementById("canvas-b");
    const im = v.state.shown.im;
    const ox = c.clientWidth / 2 - s.cx, oy = c.clientHeight / 2 - s.cy;
    const x0 = Math.max(0, -ox), y0 = Math.max(0, -oy);
    const w = Math.min(im.width - x0, c.width - Math.max(0, ox));
    const h = Math.min(im.height - y0, c.height - Math.max(0, oy));
    const d = c.getContext("2d").getImageData(x0 + ox, y0 + oy, w, h).data;
    let bin = "";
    for (let i = 0; i < d.length; ++i) bin += String.fromCharCode(d[i]);
    return { texels: [x0, y0, w, h], rgba: btoa(bin), dpr: window.devicePixelRatio };
  });
}
/** Counts of the right pane's pixels over the image: bright (inferno's top: R, G > 200). */
async function paneStats(page) {
  return page.evaluate(() => {
    const c = document.getElementById("canvas-b"), d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    let bright = 0, sum = 0;
    for (let i = 0; i < d.length; i += 4) {
      if (d[i] > 200 && d[i + 1] > 200) bright++;
      sum += d[i] + d[i + 1] + d[i + 2];
    }
    return { bright, mean: sum / (d.length / 4) / 3, zoom: window.tesseraView.state.zoom,
             caption: document.getElementById("caption-b").textContent };
  });
}
/** The right pane at zoom 1 against the server's own PNG of map `kind` (static mode: a data:
 *  URI) at its scale (`gain`): {n: texels compared, differ: how many differ, max: scale}. */
async function againstServer(page, kind, gain) {
  await select(page, "right", kind);
  await select(page, "gain", gain);
  const z = await paneAtZoom1(page);
  return page.evaluate(async (z, kind) => {
    const v = window.tesseraView, im = v.state.shown.im;
    const img = new Image();
    img.src = v.data.blobs[im[kind]];
    await img.decode();
    const c = document.createElement("canvas");
    c.width = img.width;
    c.height = img.height;
    const ctx = c.getContext("2d");
    ctx.drawImage(img, 0, 0);
    const [x0, y0, w, h] = z.texels, want = ctx.getImageData(x0, y0, w, h).data;
    const got = Uint8Array.from(atob(z.rgba), (ch) => ch.charCodeAt(0));
    let differ = 0;
    for (let i = 0; i < want.length; i += 4) {
      if (got[i] !== want[i] || got[i + 1] !== want[i + 1] || got[i + 2] !== want[i + 2]) differ++;
    }
    return { n: w * h, differ, caption: document.getElementById("caption-b").textContent,
             bar: { ...document.getElementById("colourbar").dataset } };
  }, z, kind);
}
async function key(page, k) {
  await page.keyboard.press(k);
  await settled(page);
  return page.evaluate(() => ({ right: document.getElementById("right").value,
                                mode: document.getElementById("mode").value,
                                channel: document.getElementById("channel").value,
                                zoom: window.tesseraView.state.zoom,
                                help: !document.getElementById("keys-help").hidden }));
}
async function readoutAtCentre(page) {
  const box = await (await page.$("#canvas-b")).boundingBox();
  await page.mouse.move(box.x + box.width / 2 + 1, box.y + box.height / 2);
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.waitForFunction(() => document.getElementById("readout").dataset.decoded, WAIT);
  return page.evaluate(() => ({ ...document.getElementById("readout").dataset }));
}

/** Pages of one input each: an image with alpha (URL2) and a normal map (URL3). The colour x
 *  alpha and angular maps at the server's scales are the server's PNGs. */
async function serverMaps(page, s) {
  for (const [u, name, kinds] of [[url2, "alpha", [["heatmap", "64"], ["heatmap_premultiplied", "64"]]],
                                  [url3, "nrm", [["angle_map", "10"], ["heatmap", "64"]]]]) {
    await page.goto(u);
    await page.waitForFunction(() => (document.body.dataset.drawn || "").startsWith("r"), WAIT);
    for (const [kind, gain] of kinds) {
      s[`${name}_${kind}`] = await againstServer(page, kind, gain);
      if (kind === "angle_map") {
        await select(page, "zoom", "fit");
        await select(page, "gain", "max");
        s.angle_max = await page.evaluate(() => ({ ...document.getElementById("colourbar").dataset,
            caption: document.getElementById("caption-b").textContent }));
        await page.screenshot({ path: join(out, "heat-angle-max.png") });
      }
    }
  }
}

async function scenario(page, s) {
  if (url2 && url3) {
    await serverMaps(page, s);
    await page.goto(url);
    await page.waitForFunction(() => (document.body.dataset.drawn || "").startsWith("r"), WAIT);
  }
  // A low error everywhere: the scale changes what is drawn.
  await openPair(page, "low");
  await select(page, "right", "heatmap");
  await select(page, "gain", "64");
  s.low64 = await paneStats(page);
  s.low64.bar = await page.$eval("#colourbar", (c) => ({ ...c.dataset, hidden: c.hidden, w: c.width }));
  await (await page.$("#stage")).screenshot({ path: join(out, "heat-low-64.png") });
  await select(page, "gain", "max");
  s.lowmax = await paneStats(page);
  s.lowmax.bar = await page.$eval("#colourbar", (c) => ({ ...c.dataset, hidden: c.hidden }));
  await (await page.$("#stage")).screenshot({ path: join(out, "heat-low-max.png") });
  await select(page, "gain", "p99");
  s.lowp99 = await paneStats(page);
  // Scale 64 at zoom 1: the pixels of `tessera compare --heatmap`.
  await select(page, "gain", "64");
  s.low_zoom1 = await paneAtZoom1(page);
  await page.screenshot({ path: join(out, "heat-low-zoom1.png") });
  // One bad texel in a 1024² image: at fit (zoom < 1) it still shows.
  await openPair(page, "one");
  await select(page, "right", "heatmap");
  await select(page, "zoom", "fit");
  s.one_fit = await paneStats(page);
  s.one_fit.fit_zoom = await page.evaluate(() => {
    const c = document.getElementById("canvas-b"), im = window.tesseraView.state.shown.im;
    return Math.min(c.clientWidth / im.width, c.clientHeight / im.height);
  });
  await page.screenshot({ path: join(out, "heat-one-fit.png") });
  await select(page, "gain", "64");
  s.one_zoom1 = await paneAtZoom1(page);
  await select(page, "zoom", "fit");
  // Keyboard shortcuts.
  await select(page, "right", "result");
  await page.focus("#canvas-b").catch(() => {});
  await page.evaluate(() => document.activeElement && document.activeElement.blur());
  const k = s.keys = {};
  k.two = await key(page, "2");
  k.four = await key(page, "4");  // no angular map here: stays
  k.one = await key(page, "1");
  k.h = await key(page, "h");
  k.h2 = await key(page, "h");
  k.plus = await key(page, "+");
  k.plus2 = await key(page, "+");
  k.minus = await key(page, "-");
  k.c = await key(page, "c");
  k.w = await key(page, "w");
  k.w2 = await key(page, "w");
  k.help = await key(page, "?");
  await page.screenshot({ path: join(out, "heat-keys-help.png") });
  k.help2 = await key(page, "?");
  // Typing in a form field is not a shortcut.
  await page.focus("#zoom");
  k.in_field = await key(page, "w");
  await page.evaluate(() => document.activeElement.blur());
  // The readout after a key zoom, over the result and over the heatmap.
  await select(page, "channel", "rgb");
  k.zoom_before_readout = await key(page, "+");
  s.readout_result = await readoutAtCentre(page);
  await key(page, "2");
  s.readout_heatmap = await readoutAtCentre(page);
  s.readout_heatmap.text = await page.$eval("#readout", (e) => e.textContent);
  await page.screenshot({ path: join(out, "heat-one-keys.png") });
}
