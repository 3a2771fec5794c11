// The KTX 2.0 oracle: reads .ktx2 files with ktx-parse (an independent JavaScript parser) and
// prints, as one JSON array, what it finds in each: the header, the raw index, the Data Format
// Descriptor, the key/value data, and per level its place in the file, uncompressedByteLength
// and the sha256 of its bytes (inflated with fzstd, a separate JavaScript Zstandard decoder,
// when supercompressionScheme is 2). ktx2_oracle_test.py (beside this file) compares that with
// what tessera meant to write.
//
// Usage: node ktx2_oracle.mjs KTX_PARSE_DIR FILE.ktx2...
//   KTX_PARSE_DIR holds node_modules/ktx-parse and node_modules/fzstd (scripts/setup.sh).
import { createHash } from 'node:crypto';
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';

const [dir, ...files] = process.argv.slice(2);
if (!dir || files.length === 0) {
  console.error('usage: node ktx2_oracle.mjs KTX_PARSE_DIR FILE.ktx2...');
  process.exit(2);
}
const require = createRequire(join(dir, 'oracle.js'));
const { read } = await import(pathToFileURL(require.resolve('ktx-parse')).href);
const fzstd = await import(pathToFileURL(require.resolve('fzstd')).href);
const decompress = fzstd.decompress ?? fzstd.default.decompress;

const sha256 = (bytes) => createHash('sha256').update(bytes).digest('hex');
const hex = (bytes) => Buffer.from(bytes).toString('hex');

function describe(file) {
  const bytes = new Uint8Array(readFileSync(file));  // a buffer of its own: offsets from 0
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const c = read(bytes);
  const dfd = c.dataFormatDescriptor[0];
  const keyValue = {};
  for (const [k, v] of Object.entries(c.keyValue)) keyValue[k] = typeof v === 'string' ? v : hex(v);
  return {
    file,
    fileSize: bytes.byteLength,
    vkFormat: c.vkFormat,
    typeSize: c.typeSize,
    pixelWidth: c.pixelWidth,
    pixelHeight: c.pixelHeight,
    pixelDepth: c.pixelDepth,
    layerCount: c.layerCount,
    faceCount: c.faceCount,
    levelCount: c.levelCount,
    supercompressionScheme: c.supercompressionScheme,
    // ktx-parse keeps no index; these come straight from the header bytes.
    index: {
      dfdByteOffset: view.getUint32(48, true),
      dfdByteLength: view.getUint32(52, true),
      kvdByteOffset: view.getUint32(56, true),
      kvdByteLength: view.getUint32(60, true),
      sgdByteOffset: Number(view.getBigUint64(64, true)),
      sgdByteLength: Number(view.getBigUint64(72, true)),
    },
    dfd: {
      vendorId: dfd.vendorId,
      descriptorType: dfd.descriptorType,
      versionNumber: dfd.versionNumber,
      colorModel: dfd.colorModel,
      colorPrimaries: dfd.colorPrimaries,
      transferFunction: dfd.transferFunction,
      flags: dfd.flags,
      texelBlockDimension: dfd.texelBlockDimension,
      bytesPlane: dfd.bytesPlane,
      samples: dfd.samples,
    },
    keyValue,
    levels: c.levels.map((l) => {
      const data = c.supercompressionScheme === 2 ? decompress(l.levelData) : l.levelData;
      return {
        byteOffset: l.levelData.byteOffset - bytes.byteOffset,
        byteLength: l.levelData.byteLength,
        uncompressedByteLength: l.uncompressedByteLength,
        decompressedLength: data.byteLength,
        sha256: sha256(data),
      };
    }),
  };
}

const out = files.map((file) => {
  try {
    return describe(file);
  } catch (e) {
    return { file, error: String(e && e.message ? e.message : e) };
  }
});
process.stdout.write(JSON.stringify(out, null, 1) + '\n');
