// tessera view: error heatmaps made in the page from the texels it already has (original and
// decoded RGBA8), at a chosen scale, reduced with a MAX filter when zoomed out (every screen
// pixel shows the worst texel it covers), and their colour bar. At scale 64 a difference map
// is `tessera compare --heatmap`'s, texel for texel: the same error (src/metrics/heatmap.cpp
// difference_heatmap: max abs channel difference over RGB, and alpha when either image has
// alpha) through the same inferno table and float arithmetic (Math.fround below).
"use strict";
// Nine samples of matplotlib's inferno at t = 0, 1/8, ..., 1 (as src/metrics/heatmap.cpp).
const INFERNO = [[0, 0, 4], [31, 12, 72], [85, 15, 109], [136, 34, 106], [186, 54, 85],
                 [227, 89, 51], [249, 140, 10], [249, 201, 50], [252, 255, 164]];
const GAINS = { levels: [8, 16, 32, 64], angle: [2, 5, 10, 20] };  // fixed scales per unit
const SERVER_SCALE = { levels: 64, angle: 10 };  // view_results.cpp kDiffScale, kAngleScale
const fieldCache = new Map();

/** colour_map_rgb(inferno, t) as one little-endian RGBA word, in the C++ float steps. */
function infernoWord(t) {
  const f32 = Math.fround;
  if (!(t === t)) t = 0;
  t = Math.min(1, Math.max(0, t));
  const f = f32(t * 8), i = Math.min(7, Math.trunc(f)), w = f32(f - i), u = f32(1 - w);
  const c = (k) => Math.round(f32(f32(INFERNO[i][k] * u) + f32(INFERNO[i + 1][k] * w)));
  return (0xff000000 | (c(2) << 16) | (c(1) << 8) | c(0)) >>> 0;
}
/** The colour of `value` at `scale` (heatmap(): value * (1 / scale) in float). */
function heatWord(value, scale) {
  return infernoWord(Math.fround(Math.fround(value) * Math.fround(1 / scale)));
}

/** Per-texel error of image `im` for map `kind`: {w, h, levels: [values...], unit, max, p99}
 *  with levels[k] the max-reduced field of level k (Uint8Array, or Float32Array of degrees). */
async function errorField(im, kind) {
  const key = `${im.decoded}|${im.original}|${kind}`;
  if (!fieldCache.has(key)) {
    fieldCache.set(key, Promise.all([texels(im.original, im.width, im.height),
                                     texels(im.decoded, im.width, im.height)])
        .then(([a, b]) => makeField(a.data, b.data, im.width, im.height, kind, im.alpha !== false)));
  }
  return fieldCache.get(key);
}
function makeField(a, b, w, h, kind, alpha) {
  const n = w * h;
  if (kind === "angle_map") {
    const v = new Float32Array(n), unit = (p, i, o) => {
      const x = 2 * p[i] / 255 - 1, y = 2 * p[i + 1] / 255 - 1, z = 2 * p[i + 2] / 255 - 1;
      const len = Math.sqrt(x * x + y * y + z * z);
      if (len <= 0) { o[0] = 0; o[1] = 0; o[2] = 1; } else { o[0] = x / len; o[1] = y / len; o[2] = z / len; }
    };
    const u = [0, 0, 0], q = [0, 0, 0];
    for (let t = 0; t < n; ++t) {  // view_results.cpp angle_map()
      unit(a, t * 4, u);
      unit(b, t * 4, q);
      const d = Math.min(1, Math.max(-1, u[0] * q[0] + u[1] * q[1] + u[2] * q[2]));
      v[t] = Math.acos(d) * 180 / 3.14159265358979323846;
    }
    return finishField(v, w, h, "angle");
  }
  const v = new Uint8Array(n), pm = kind === "heatmap_premultiplied";
  const ch = alpha || pm ? 4 : 3;
  for (let t = 0, i = 0; t < n; ++t, i += 4) {
    let m = 0;
    for (let c = 0; c < ch; ++c) {
      let x = a[i + c], y = b[i + c];
      if (pm && c < 3) {  // image::premultiply_alpha, straight: (c a + 127) / 255
        x = ((x * a[i + 3] + 127) / 255) | 0;
        y = ((y * b[i + 3] + 127) / 255) | 0;
      }
      const d = x > y ? x - y : y - x;
      if (d > m) m = d;
    }
    v[t] = m;
  }
  return finishField(v, w, h, "levels");
}
/** The field's max and 99th percentile (a histogram: 256 levels, or 0.01 degree bins). */
function finishField(v, w, h, unit) {
  const bins = unit === "levels" ? 256 : 18001, step = unit === "levels" ? 1 : 0.01;
  const hist = new Uint32Array(bins);
  let max = 0;
  for (let i = 0; i < v.length; ++i) {
    const x = v[i];
    if (x > max) max = x;
    hist[Math.min(bins - 1, Math.floor(x / step))]++;
  }
  let p99 = 0;
  for (let i = 0, seen = 0; i < bins; ++i) {
    seen += hist[i];
    if (seen >= 0.99 * v.length) { p99 = unit === "levels" ? i : (i + 1) * step; break; }
  }
  return { w, h, unit, max, p99, levels: [v] };
}
/** Level k of the field's max pyramid (each value the max of a 2^k x 2^k block). */
function fieldLevel(F, k) {
  while (F.levels.length <= k) {
    const j = F.levels.length, src = F.levels[j - 1];
    const sw = Math.ceil(F.w / 2 ** (j - 1)), sh = Math.ceil(F.h / 2 ** (j - 1));
    const dw = Math.ceil(sw / 2), dh = Math.ceil(sh / 2), dst = new src.constructor(dw * dh);
    for (let y = 0; y < dh; ++y) {
      const y0 = 2 * y * sw, y1 = Math.min(2 * y + 1, sh - 1) * sw;
      for (let x = 0; x < dw; ++x) {
        const x0 = 2 * x, x1 = Math.min(2 * x + 1, sw - 1);
        dst[y * dw + x] = Math.max(src[y0 + x0], src[y0 + x1], src[y1 + x0], src[y1 + x1]);
      }
    }
    F.levels.push(dst);
  }
  return F.levels[k];
}

/** The chosen scale of field F: #gain is "max", "p99" or a fixed value in F's unit. */
function heatScale(F) {
  const g = $("gain").value, floor = F.unit === "levels" ? 1 : 0.01;
  if (g === "max") return Math.max(floor, F.max);
  if (g === "p99") return Math.max(floor, F.p99);
  return Number(g);
}
function scaleText(F, scale) {
  const g = $("gain").value;
  const v = F.unit === "levels" ? `${scale} levels of 255` : `${+scale.toFixed(2)}°`;
  return g === "max" ? `scale ${v} (image max)` : g === "p99" ? `scale ${v} (99th percentile)`
      : `scale ${v}`;
}

/** The Picture of heatmap `kind` of image `im` at the chosen scale (max-reduced levels). */
async function heatPicture(im, kind) {
  const F = await errorField(im, kind), scale = heatScale(F);
  const ck = `heat|${im.decoded}|${im.original}|${kind}|${scale}`;
  if (!viewCache.has(ck)) {
    let lut = null;
    if (F.unit === "levels") {
      lut = new Uint32Array(256);
      for (let v = 0; v < 256; ++v) lut[v] = heatWord(v, scale);
    }
    const fill = (k, x0, y0, tw, th, out) => {
      const v = fieldLevel(F, k), lw = Math.ceil(F.w / 2 ** k);
      const d32 = new Uint32Array(out.data.buffer, out.data.byteOffset, tw * th);
      for (let y = 0, o = 0; y < th; ++y) {
        for (let x = 0, i = (y0 + y) * lw + x0; x < tw; ++x, ++i, ++o) {
          d32[o] = lut ? lut[v[i]] : heatWord(v[i], scale);
        }
      }
    };
    const p = new Picture(F.w, F.h, fill, "max");
    p.field = F;
    p.scale = scale;
    viewCache.set(ck, p);
  }
  const p = viewCache.get(ck);
  p.note = scaleText(F, scale);  // "image max" and "99th percentile" may share a picture
  return p;
}

// ---- controls: scale, colour bar -----------------------------------------------------------
let gainUnit = "";
/** Shows the scale control and colour bar when the right pane is a heatmap of `im`. */
function showHeatControls(im) {
  const kind = $("right").value, on = kind !== "result" && !!im[kind];
  $("gain-label").hidden = !on;
  $("colourbar").hidden = !on;
  if (!on) return;
  const unit = kind === "angle_map" ? "angle" : "levels";
  if (unit !== gainUnit) {  // the fixed values follow the unit; the auto choices stay
    const keep = $("gain").value;
    const u = unit === "angle" ? "°" : " levels";
    fillSelect($("gain"), [["max", "auto: image max"], ["p99", "auto: 99th percentile"],
                           ...GAINS[unit].map((g) => [g, `${g}${u}`])],
               keep === "max" || keep === "p99" ? keep : "max");
    gainUnit = unit;
  }
  errorField(im, kind).then((F) => drawColourBar(F, heatScale(F))).catch(() => {});
}
/** The colour bar: inferno from 0 to the scale, ticks in the field's unit. */
function drawColourBar(F, scale) {
  const c = $("colourbar"), dpr = window.devicePixelRatio || 1;
  const w = Math.max(1, c.clientWidth || 320), h = 46;
  c.width = Math.round(w * dpr);
  c.height = Math.round(h * dpr);
  const ctx = c.getContext("2d");
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  ctx.fillStyle = "#1b1d21";
  ctx.fillRect(0, 0, w, h);
  const x0 = 8, bw = w - 16;
  for (let x = 0; x < bw; ++x) {
    const word = heatWord((x + 0.5) / bw * scale, scale);
    ctx.fillStyle = `rgb(${word & 255},${(word >>> 8) & 255},${(word >>> 16) & 255})`;
    ctx.fillRect(x0 + x, 2, 1, 14);
  }
  ctx.fillStyle = "#e4e6ea";
  ctx.strokeStyle = "#e4e6ea";
  ctx.font = "11px system-ui, sans-serif";
  const ticks = niceTicks(scale);
  ticks.forEach((v, i) => {
    const x = x0 + v / scale * bw;
    ctx.fillRect(Math.round(x), 16, 1, 4);
    ctx.textAlign = i === 0 ? "left" : v === scale && x > x0 + bw - 12 ? "right" : "center";
    ctx.fillText(String(+v.toFixed(2)) + (v === scale ? "+" : ""), x, 30);  // "+": saturated
  });
  ctx.textAlign = "left";
  ctx.fillText(F.unit === "levels" ? "levels of 255 (max abs channel difference)"
      : "degrees (angle between normals)", x0, 43);
  c.dataset.scale = String(scale);
  c.dataset.unit = F.unit;
}
/** 0, the scale and round values between (at most about six ticks). */
function niceTicks(scale) {
  const raw = scale / 5, p = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 5, 10].map((m) => m * p).find((s) => s >= raw);
  const out = [];
  for (let v = 0; v < scale - step * 0.3; v += step) out.push(v);
  out.push(scale);
  return out;
}
