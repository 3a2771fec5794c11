// tessera view: the decoded texels of a PVRTC1 result, decoded in the page from the result's .pvr
// blob (smaller than a PNG of the texels, and no PNG to make): an image's key is then
// "pvrtc:FILE:LEVEL:LAYER:FACE" (tools/tessera/view_results.cpp). Bit-exact with tessera's
// decoder (src/pvrtc/format/decode.cpp, pvrtc_kernel.h): the same integer math, step by step.
"use strict";
const pvrFiles = new Map();  // blob key -> Promise of readPvr3's texture

/** The PVR v3 file `bytes` as src/texture_file/container_pvr.cpp reads it: 52-byte little-endian
 *  header, metadata, then per level (largest first) per surface (layer) per face one image. */
function readPvr3(bytes) {
  const dv = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (bytes.length < 52 || dv.getUint32(0, true) !== 0x03525650) throw new Error("texels: not a PVR v3 file");
  const format = dv.getUint32(8, true);
  if (dv.getUint32(12, true) !== 0 || format > 3) throw new Error(`texels: PVR pixel format ${format} is not PVRTC1`);
  const t = { twoBpp: format < 2, hasAlpha: (format & 1) !== 0,
    premultiplied: (dv.getUint32(4, true) & 2) !== 0, srgb: dv.getUint32(16, true) === 1,
    height: dv.getUint32(24, true), width: dv.getUint32(28, true), layers: dv.getUint32(36, true),
    faces: dv.getUint32(40, true), levels: [], bytes };
  const mips = dv.getUint32(44, true);
  let at = 52 + dv.getUint32(48, true);
  for (let l = 0; l < mips; ++l) {
    const w = Math.max(1, t.width >> l), h = Math.max(1, t.height >> l);
    const size = pvrtcBlocksX(t.twoBpp, w) * pvrtcBlocksY(h) * 8;
    t.levels.push({ at, size, width: w, height: h });
    at += size * t.layers * t.faces;
  }
  if (dv.getUint32(32, true) !== 1 || at !== bytes.length) throw new Error("texels: a PVR file tessera cannot read");
  return t;
}
function pvrtcBlocksX(twoBpp, w) { return Math.max(Math.floor(w / (twoBpp ? 8 : 4)), 2); }
function pvrtcBlocksY(h) { return Math.max(Math.floor(h / 4), 2); }

/** Texels {width, height, data} of the image a "pvrtc:" key names. */
async function pvrtcTexels(key) {
  const [, file, level, layer, face] = key.split(":");
  if (!pvrFiles.has(file)) {
    pvrFiles.set(file, blobBytes(file).then(readPvr3, (e) => { pvrFiles.delete(file); throw e; }));
  }
  const t = await pvrFiles.get(file), l = t.levels[+level];
  if (!l || +layer >= t.layers || +face >= t.faces) throw new Error(`texels: no image ${key}`);
  const at = l.at + (+layer * t.faces + +face) * l.size;
  const data = decodePvrtc(t.bytes.subarray(at, at + l.size), t.twoBpp, l.width, l.height, t.hasAlpha);
  return { width: l.width, height: l.height, data };
}

/** pvrtc_kernel.h's morton(): the data index of block (bx, by) of a bw x bh grid. */
function pvrtcMorton(bx, by, bw, bh) {
  const mn = Math.min(bw, bh);
  let idx = 0, shift = 0, log = 0;
  for (let bit = 1; bit < mn; bit <<= 1) {
    if (by & bit) idx |= 1 << shift;
    if (bx & bit) idx |= 1 << (shift + 1);
    shift += 2;
  }
  while ((1 << log) < mn) ++log;
  return idx | ((bw > bh ? bx >> log : by >> log) << shift);
}

function x4(v) { return (v << 1) | (v >> 3); }  // expand4to5
function x3(v) { return (v << 2) | (v >> 1); }  // expand3to5
/** expand_a / expand_b: an endpoint (16-bit field) to r, g, b in 0..31 and a in 0..15, at o. */
function pvrtcExpand(c, isB, e, o) {
  if (c & 0x8000) {
    e[o] = (c >> 10) & 31; e[o + 1] = (c >> 5) & 31; e[o + 2] = isB ? c & 31 : x4((c >> 1) & 15); e[o + 3] = 15;
  } else {
    e[o] = x4((c >> 8) & 15); e[o + 1] = x4((c >> 4) & 15);
    e[o + 2] = isB ? x4(c & 15) : x3((c >> 1) & 7); e[o + 3] = (c >> 11) & 0xe;
  }
}

const PVRTC_MOD0 = [0, 3, 5, 8], PVRTC_MOD1 = [0, 4, 4, 8], PVRTC_PUNCH = 0x10;

/** modulation_map: per padded texel, the weight of B in eighths (| PVRTC_PUNCH: alpha 0). */
function pvrtcModulation(twoBpp, lo, hi, nbx, nby) {
  const bw = twoBpp ? 8 : 4, pw = nbx * bw, ph = nby * 4, m = new Uint8Array(pw * ph);
  if (!twoBpp) {
    for (let by = 0, i = 0; by < nby; ++by) {
      for (let bx = 0; bx < nbx; ++bx, ++i) {
        const bits = lo[i], mode1 = hi[i] & 1;
        for (let y = 0; y < 4; ++y) {
          for (let x = 0, o = (by * 4 + y) * pw + bx * 4; x < 4; ++x) {
            const v = (bits >>> (2 * (4 * y + x))) & 3;
            m[o + x] = mode1 ? PVRTC_MOD1[v] | (v === 2 ? PVRTC_PUNCH : 0) : PVRTC_MOD0[v];
          }
        }
      }
    }
    return m;
  }
  // 2 bpp (unpack_2bpp_block): the stored values and each block's mode, then the texels whose
  // value is interpolated from their neighbours (wrapping).
  const stored = new Uint8Array(pw * ph), modes = new Uint8Array(nbx * nby);
  for (let by = 0, i = 0; by < nby; ++by) {
    for (let bx = 0; bx < nbx; ++bx, ++i) {
      let bits = lo[i], mode = hi[i] & 1;
      const o = by * 4 * pw + bx * 8;
      if (mode === 0) {
        for (let k = 0; k < 32; ++k) stored[o + (k >> 3) * pw + (k & 7)] = (bits >>> k) & 1 ? 3 : 0;
      } else {
        if (bits & 1) {
          mode = bits & (1 << 20) ? 3 : 2;
          bits = bits & (1 << 21) ? bits | (1 << 20) : bits & ~(1 << 20);
        }
        bits = (bits & 2 ? bits | 1 : bits & ~1) >>> 0;
        for (let y = 0; y < 4; ++y) {
          for (let x = 0; x < 8; ++x) {
            if (((x ^ y) & 1) === 0) {
              stored[o + y * pw + x] = bits & 3;
              bits >>>= 2;
            }
          }
        }
      }
      modes[i] = mode;
    }
  }
  const wmask = pw - 1, hmask = ph - 1;
  for (let y = 0; y < ph; ++y) {
    const row = y * pw, up = ((y - 1) & hmask) * pw, dn = ((y + 1) & hmask) * pw;
    for (let x = 0; x < pw; ++x) {
      const mode = modes[(y >> 2) * nbx + (x >> 3)];
      if (mode === 0 || ((x ^ y) & 1) === 0) {
        m[row + x] = PVRTC_MOD0[stored[row + x]];
        continue;
      }
      const l = PVRTC_MOD0[stored[row + ((x - 1) & wmask)]], r = PVRTC_MOD0[stored[row + ((x + 1) & wmask)]];
      const u = PVRTC_MOD0[stored[up + x]], d = PVRTC_MOD0[stored[dn + x]];
      m[row + x] = mode === 1 ? (u + d + l + r + 2) >> 2 : mode === 2 ? (l + r + 1) >> 1 : (u + d + 1) >> 1;
    }
  }
  return m;
}

/** pvrtc::decode then decode_texture_image: RGBA8 texels (Uint8ClampedArray) of one PVRTC1
 *  image of width x height (powers of two); alpha 255 when the format has none. */
function decodePvrtc(bytes, twoBpp, width, height, hasAlpha) {
  const bw = twoBpp ? 8 : 4, nbx = pvrtcBlocksX(twoBpp, width), nby = pvrtcBlocksY(height);
  const nb = nbx * nby, pw = nbx * bw, ph = nby * 4;
  if (bytes.length < nb * 8) throw new Error("texels: a PVRTC image cut short");
  const dv = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const lo = new Uint32Array(nb), hi = new Uint32Array(nb);
  const mx = new Uint32Array(nbx), my = new Uint32Array(nby);
  for (let bx = 0; bx < nbx; ++bx) mx[bx] = pvrtcMorton(bx, 0, nbx, nby);
  for (let by = 0; by < nby; ++by) my[by] = pvrtcMorton(0, by, nbx, nby);
  const ea = new Int32Array(nb * 4), eb = new Int32Array(nb * 4);
  for (let by = 0, i = 0; by < nby; ++by) {
    for (let bx = 0; bx < nbx; ++bx, ++i) {
      const at = (mx[bx] | my[by]) * 8;
      lo[i] = dv.getUint32(at, true);
      hi[i] = dv.getUint32(at + 4, true);
      pvrtcExpand(hi[i] & 0xffff, false, ea, i * 4);
      pvrtcExpand(hi[i] >>> 16, true, eb, i * 4);
    }
  }
  const m = pvrtcModulation(twoBpp, lo, hi, nbx, nby);
  const out = new Uint8ClampedArray(width * height * 4);
  const half = bw >> 1, wmask = pw - 1, hmask = ph - 1, stepScale = 8 / bw;
  const sum = (e, r0, r1, b, k, wy0, wy1) => e[(r0 + b) * 4 + k] * wy0 + e[(r1 + b) * 4 + k] * wy1;
  // upscale_rows: between the centres of blocks bx and bx + 1 the bilinear sum (weights scaled
  // to 32) starts at 8 L and grows by (R - L) * 8 / bw per texel; then modulate.
  for (let y = 0; y < height; ++y) {
    const yy = (y - 2) & hmask, b0 = yy >> 2, dy = yy & 3, b1 = (b0 + 1) & (nby - 1);
    const r0 = b0 * nbx, r1 = b1 * nbx, wy0 = 4 - dy, wy1 = dy, mrow = y * pw, orow = y * width;
    for (let bx = 0; bx < nbx; ++bx) {
      const bx1 = (bx + 1) & (nbx - 1);
      let ar = sum(ea, r0, r1, bx, 0, wy0, wy1), ag = sum(ea, r0, r1, bx, 1, wy0, wy1);
      let ab = sum(ea, r0, r1, bx, 2, wy0, wy1), aa = sum(ea, r0, r1, bx, 3, wy0, wy1);
      let br = sum(eb, r0, r1, bx, 0, wy0, wy1), bg = sum(eb, r0, r1, bx, 1, wy0, wy1);
      let bb = sum(eb, r0, r1, bx, 2, wy0, wy1), ba = sum(eb, r0, r1, bx, 3, wy0, wy1);
      const sar = (sum(ea, r0, r1, bx1, 0, wy0, wy1) - ar) * stepScale;
      const sag = (sum(ea, r0, r1, bx1, 1, wy0, wy1) - ag) * stepScale;
      const sab = (sum(ea, r0, r1, bx1, 2, wy0, wy1) - ab) * stepScale;
      const saa = (sum(ea, r0, r1, bx1, 3, wy0, wy1) - aa) * stepScale;
      const sbr = (sum(eb, r0, r1, bx1, 0, wy0, wy1) - br) * stepScale;
      const sbg = (sum(eb, r0, r1, bx1, 1, wy0, wy1) - bg) * stepScale;
      const sbb = (sum(eb, r0, r1, bx1, 2, wy0, wy1) - bb) * stepScale;
      const sba = (sum(eb, r0, r1, bx1, 3, wy0, wy1) - ba) * stepScale;
      ar *= 8; ag *= 8; ab *= 8; aa *= 8; br *= 8; bg *= 8; bb *= 8; ba *= 8;
      const x0 = bx * bw + half;
      for (let d = 0; d < bw; ++d) {
        const x = (x0 + d) & wmask;
        if (x < width) {
          const me = m[mrow + x], mb = me & 15, ma = 8 - mb, o = (orow + x) * 4;
          out[o] = (((ar >> 7) + (ar >> 2)) * ma + ((br >> 7) + (br >> 2)) * mb) >> 3;
          out[o + 1] = (((ag >> 7) + (ag >> 2)) * ma + ((bg >> 7) + (bg >> 2)) * mb) >> 3;
          out[o + 2] = (((ab >> 7) + (ab >> 2)) * ma + ((bb >> 7) + (bb >> 2)) * mb) >> 3;
          out[o + 3] = !hasAlpha ? 255 : me & PVRTC_PUNCH ? 0
              : (((aa >> 5) + (aa >> 1)) * ma + ((ba >> 5) + (ba >> 1)) * mb) >> 3;
        }
        ar += sar; ag += sag; ab += sab; aa += saa; br += sbr; bg += sbg; bb += sbb; ba += sba;
      }
    }
  }
  return out;
}
