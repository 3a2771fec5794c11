// tessera view: the texels of the page's images, read exactly. The server and the static export
// send texels as PNG (tools/tessera/view_png.cpp: 8-bit RGB or RGBA, not interlaced); a canvas
// would premultiply translucent texels (and may convert colours), so this reads the PNG itself:
// its IDAT stream through the browser's DecompressionStream, then the row filters undone here.
"use strict";
async function inflate(parts) {
  const stream = new Blob(parts).stream().pipeThrough(new DecompressionStream("deflate"));
  return new Uint8Array(await new Response(stream).arrayBuffer());
}
/** RGBA8 texels (Uint8ClampedArray) of a PNG's bytes, exact; throws on a PNG it cannot read. */
async function decodePng(bytes) {
  const dv = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const sig = [137, 80, 78, 71, 13, 10, 26, 10];
  if (bytes.length < 8 || sig.some((v, i) => bytes[i] !== v)) throw new Error("texels: not a PNG");
  let p = 8, w = 0, h = 0, type = -1;
  const idat = [];
  while (p + 8 <= bytes.length) {
    const n = dv.getUint32(p), kind = String.fromCharCode(...bytes.subarray(p + 4, p + 8));
    if (kind === "IHDR") {
      w = dv.getUint32(p + 8); h = dv.getUint32(p + 12); type = bytes[p + 17];
      if (bytes[p + 16] !== 8 || (type !== 2 && type !== 6) || bytes[p + 20] !== 0) {
        throw new Error("texels: a PNG other than 8-bit RGB/RGBA, not interlaced");
      }
    } else if (kind === "IDAT") {
      idat.push(bytes.subarray(p + 8, p + 8 + n));
    } else if (kind === "IEND") {
      break;
    }
    p += 12 + n;
  }
  const raw = await inflate(idat);
  const bpp = type === 6 ? 4 : 3, stride = w * bpp;
  if (raw.length < h * (stride + 1)) throw new Error("texels: a PNG cut short");
  const out = new Uint8ClampedArray(w * h * 4);
  const out32 = new Uint32Array(out.buffer), little = new Uint8Array(new Uint32Array([1]).buffer)[0] === 1;
  let prev = new Uint8Array(stride), cur = new Uint8Array(stride);
  for (let y = 0; y < h; ++y) {
    const f = raw[y * (stride + 1)], src = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    unfilter(f, src, cur, prev, bpp);
    if (bpp === 4) {
      out.set(cur, y * stride);
    } else if (little) {  // a texel a store: 0xAABBGGRR
      for (let x = 0, i = 0, o = y * w; x < w; ++x, i += 3) {
        out32[o + x] = 0xff000000 | (cur[i + 2] << 16) | (cur[i + 1] << 8) | cur[i];
      }
    } else {
      for (let x = 0, o = y * w * 4; x < w; ++x, o += 4) {
        out[o] = cur[x * 3]; out[o + 1] = cur[x * 3 + 1]; out[o + 2] = cur[x * 3 + 2]; out[o + 3] = 255;
      }
    }
    [prev, cur] = [cur, prev];
  }
  return out;
}
/** Undoes PNG filter `f` of one row: `src` filtered, `cur` out, `prev` the row above (zeros for
 *  the first row). */
function unfilter(f, src, cur, prev, bpp) {
  const n = src.length;
  if (f === 0) {
    cur.set(src);
  } else if (f === 1) {
    for (let x = 0; x < bpp; ++x) cur[x] = src[x];
    for (let x = bpp; x < n; ++x) cur[x] = src[x] + cur[x - bpp];
  } else if (f === 2) {
    for (let x = 0; x < n; ++x) cur[x] = src[x] + prev[x];
  } else if (f === 3) {
    for (let x = 0; x < bpp; ++x) cur[x] = src[x] + (prev[x] >> 1);
    for (let x = bpp; x < n; ++x) cur[x] = src[x] + ((cur[x - bpp] + prev[x]) >> 1);
  } else if (f === 4) {
    // The first texel has no left neighbours: Paeth of (0, b, 0) is b.
    for (let x = 0; x < bpp; ++x) cur[x] = src[x] + prev[x];
    for (let x = bpp; x < n; ++x) {
      const a = cur[x - bpp], b = prev[x], c = prev[x - bpp];
      const p = b - c, q = a - c, pa = p < 0 ? -p : p, pb = q < 0 ? -q : q;
      const pc = p + q < 0 ? -(p + q) : p + q;
      cur[x] = src[x] + (pa <= pb && pa <= pc ? a : pb <= pc ? b : c);
    }
  } else {
    throw new Error(`texels: PNG filter ${f}`);
  }
}
