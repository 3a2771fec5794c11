// tessera view: pictures drawn from tiles made on demand. A full-size canvas of a 4096² image
// takes seconds to fill; a Picture fills only the 512² tiles that are on screen, at the
// reduction level the zoom needs (level k: one tile texel per 2^k image texels), so the first
// draw at fit touches about one texel per screen pixel.
"use strict";
const TILE = 512;

/** An image of w x h texels drawn through tiles. `fill(k, x0, y0, tw, th, out)` writes the
 *  tile of level k whose top-left level texel is (x0, y0) into `out` (an ImageData, tw x th).
 *  `reduce` "nearest" picks level k <= the zoom (what a nearest-sampled full-size canvas
 *  shows); "max" picks k >= it, so every level texel covers a screen pixel's centre and a
 *  max-reduced heatmap hides no bad texel. */
class Picture {
  constructor(w, h, fill, reduce = "nearest") {
    this.w = w;
    this.h = h;
    this.fill = fill;
    this.reduce = reduce;
    this.tiles = new Map();
  }
  /** The reduction level for `zd` device pixels per texel. */
  levelFor(zd) {
    if (zd >= 1) return 0;
    const k = this.reduce === "max" ? Math.ceil(Math.log2(1 / zd) - 1e-9) : Math.floor(Math.log2(1 / zd) + 1e-9);
    const top = Math.ceil(Math.log2(Math.max(this.w, this.h)));
    return Math.max(0, Math.min(top, k));
  }
  tile(k, tx, ty) {
    const key = `${k}:${tx}:${ty}`;
    let c = this.tiles.get(key);
    if (c) return c;
    const f = 2 ** k, lw = Math.ceil(this.w / f), lh = Math.ceil(this.h / f);
    const x0 = tx * TILE, y0 = ty * TILE;
    const tw = Math.min(TILE, lw - x0), th = Math.min(TILE, lh - y0);
    c = document.createElement("canvas");
    c.width = tw;
    c.height = th;
    const ctx = c.getContext("2d");
    const out = ctx.createImageData(tw, th);
    this.fill(k, x0, y0, tw, th, out);
    ctx.putImageData(out, 0, 0);
    this.tiles.set(key, c);
    return c;
  }
  /** Draws the part on screen with the pane transform `tr` (CSS pixels), inside `clip`
   *  ([left, width] CSS pixels) when given. */
  drawTo(ctx, dpr, tr, clip) {
    const zd = tr.z * dpr, k = this.levelFor(zd), f = 2 ** k, s = zd * f;
    const lw = Math.ceil(this.w / f), lh = Math.ceil(this.h / f);
    const left = clip ? clip[0] * dpr : 0, right = clip ? (clip[0] + clip[1]) * dpr : ctx.canvas.width;
    const ox = tr.ox * dpr, oy = tr.oy * dpr;
    const x0 = Math.max(0, Math.floor((left - ox) / s)), x1 = Math.min(lw, Math.ceil((right - ox) / s));
    const y0 = Math.max(0, Math.floor(-oy / s)), y1 = Math.min(lh, Math.ceil((ctx.canvas.height - oy) / s));
    if (x1 <= x0 || y1 <= y0) return;
    ctx.save();
    if (clip) { ctx.beginPath(); ctx.rect(left, 0, right - left, ctx.canvas.height); ctx.clip(); }
    ctx.setTransform(s, 0, 0, s, ox, oy);
    ctx.imageSmoothingEnabled = false;
    for (let ty = Math.floor(y0 / TILE); ty * TILE < y1; ++ty) {
      for (let tx = Math.floor(x0 / TILE); tx * TILE < x1; ++tx) {
        ctx.drawImage(this.tile(k, tx, ty), tx * TILE, ty * TILE);
      }
    }
    ctx.restore();
  }
}

/** Fills a tile of texels `t` as `channel` shows them (alpha composited as a renderer blends:
 *  straight c*a + bg*(1-a), premultiplied c + bg*(1-a)); level k samples every 2^k-th texel. */
function fillChannel(t, channel, premultiplied) {
  const src32 = new Uint32Array(t.data.buffer, t.data.byteOffset, t.width * t.height);
  const s = t.data, W = t.width;
  const sq = Math.max(1, Math.round(Math.max(t.width, t.height) / 32));
  const shift = { r: 0, g: 8, b: 16, a: 24 }[channel];
  return (k, x0, y0, tw, th, out) => {
    const d = out.data, d32 = new Uint32Array(d.buffer, d.byteOffset, tw * th);
    for (let y = 0, o = 0; y < th; ++y) {
      const sy = (y0 + y) << k, row = sy * W;
      for (let x = 0; x < tw; ++x, ++o) {
        const sx = (x0 + x) << k, v = src32[row + sx];
        if (channel === "rgb") {
          d32[o] = v | 0xff000000;
        } else if (shift !== undefined) {
          const c = (v >>> shift) & 255;
          d32[o] = 0xff000000 | (c << 16) | (c << 8) | c;
        } else {
          const i = (row + sx) * 4, a = s[i + 3], kk = a / 255, w = premultiplied ? 1 : kk;
          const bg = channel === "black" ? 0 : channel === "white" ? 255
              : ((Math.floor(sx / sq) + Math.floor(sy / sq)) & 1) ? 204 : 153;
          const b = bg * (1 - kk), p = o * 4;
          d[p] = s[i] * w + b; d[p + 1] = s[i + 1] * w + b; d[p + 2] = s[i + 2] * w + b; d[p + 3] = 255;
        }
      }
    }
  };
}
