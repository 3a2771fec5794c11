// Ptex (.ptx) reader: header, extended header, face info, constant data, level info and the
// level-0 face data in all four encodings. Every size is checked against the bytes before use.
//
// The file, little-endian (Ptex file-format documentation, Burley & Lacewell 2008; the layout of
// the public Ptex library's files):
//
//   Header (64 bytes)      magic "Ptex", version 1, mesh type (0 triangle, 1 quad), data type
//                          (0 u8, 1 u16, 2 half, 3 float), alpha channel (-1 = none), channel
//                          count, level count, face count, the sizes of the blocks below, the
//                          minor version, the level-data size and the meta-data sizes.
//   Extended header        `extheadersize` bytes (40 in current files): border modes, edge
//                          filter mode, large-meta-data sizes, edit-data size and position.
//   Face info              zlib: 20 bytes per face — ulog2, vlog2 (int8), adjacent edges
//                          (2 bits per edge), flags (1 constant, 2 has edits, 4 neighbourhood
//                          constant, 8 subface), 4 adjacent faces (int32, -1 = none).
//   Constant data          zlib: one pixel per face (the face's average colour).
//   Level info             16 bytes per level: level-data size (u64), level-header size
//                          (u32), face count (u32).
//   Level data             per level: a zlib array of one u32 per face (bits 0..29 block size,
//                          30..31 encoding), then the faces' blocks back to back. Encodings:
//                          0 constant (one raw pixel), 1 zip, 2 zip of the running difference
//                          (u8 / u16 only), 3 tiled (tile resolution, u32 tile-header size,
//                          zlib tile headers, then the tiles, each encoded like a face).
//                          Zipped pixel data is planar: each channel's plane of u x v values,
//                          rows of increasing v.
//   Meta data, edits       skipped (files with edits are refused as unsupported).
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "tessera/io.h"
#include "tessera/ptex.h"

namespace tessera::ptex {

namespace {

constexpr std::uint32_t kMagic = 0x78657450u;  // "Ptex" little-endian
constexpr std::size_t kHeaderSize = 64;
constexpr std::size_t kExtHeaderSize = 40;
constexpr std::size_t kFaceInfoSize = 20;
constexpr std::size_t kLevelInfoSize = 16;

enum Encoding : std::uint32_t { kConstant = 0, kZipped = 1, kDiffZipped = 2, kTiled = 3 };

std::uint16_t rd16(const std::uint8_t* p) { return std::uint16_t(p[0] | (p[1] << 8)); }
std::uint32_t rd32(const std::uint8_t* p) {
  return std::uint32_t(p[0]) | (std::uint32_t(p[1]) << 8) | (std::uint32_t(p[2]) << 16) |
         (std::uint32_t(p[3]) << 24);
}
std::uint64_t rd64(const std::uint8_t* p) {
  return std::uint64_t(rd32(p)) | (std::uint64_t(rd32(p + 4)) << 32);
}

int data_size(DataType t) {
  switch (t) {
    case DataType::u8:
      return 1;
    case DataType::u16:
      return 2;
    case DataType::half:
      return 2;
    case DataType::f32:
      return 4;
  }
  return 1;
}

/// Parsing context: the bytes and the name for messages.
struct Ctx {
  std::span<const std::uint8_t> bytes;
  std::string name;
  Status error(ErrorCode code, const std::string& what) const {
    return Status::error(code, name + ": " + what);
  }
  Status corrupt(const std::string& what) const { return error(ErrorCode::corrupt_data, what); }
  /// True when [pos, pos + size) lies inside the bytes (no overflow).
  bool in_range(std::uint64_t pos, std::uint64_t size) const {
    return pos <= bytes.size() && size <= bytes.size() - pos;
  }
};

/// deflate cannot expand data by more than about 1032:1, so a zipped block of `zipped` bytes
/// that claims to hold more than this cannot be genuine: checked before allocating its output.
bool plausible_zip(std::uint64_t zipped, std::uint64_t unzipped) {
  return unzipped <= zipped * 1040 + 64;
}

/// Inflates exactly `out.size()` bytes from `in`; the stream must end there.
bool inflate_exact(std::span<const std::uint8_t> in, std::span<std::uint8_t> out) {
  z_stream zs;
  std::memset(&zs, 0, sizeof zs);
  if (inflateInit(&zs) != Z_OK) return false;
  zs.next_in = const_cast<Bytef*>(in.data());
  zs.avail_in = uInt(in.size());
  zs.next_out = out.data();
  zs.avail_out = uInt(out.size());
  // An empty output still needs one call to see the end of the stream.
  std::uint8_t dummy = 0;
  if (out.empty()) {
    zs.next_out = &dummy;
    zs.avail_out = 1;
  }
  const int rc = inflate(&zs, Z_FINISH);
  const bool ok = rc == Z_STREAM_END && zs.total_out == out.size();
  inflateEnd(&zs);
  return ok;
}

float to_float(const std::uint8_t* p, DataType t) {
  switch (t) {
    case DataType::u8:
      return float(p[0]) / 255.0f;
    case DataType::u16:
      return float(rd16(p)) / 65535.0f;
    case DataType::half:
      return half_to_float(rd16(p));
    case DataType::f32: {
      float f;
      const std::uint32_t u = rd32(p);
      std::memcpy(&f, &u, 4);
      return f;
    }
  }
  return 0.0f;
}

/// What face/tile decoding needs from the header.
struct Format {
  DataType type;
  int channels;
  int pixel_size;
};

/// Fills the w x h block at (x0, y0) of `dst` (row stride `stride` texels) with one pixel.
void fill_block(const Format& f, const std::uint8_t* pixel, float* dst, int stride, int x0, int y0,
                int w, int h) {
  float px[64];
  for (int c = 0; c < f.channels; ++c) px[c] = to_float(pixel + c * data_size(f.type), f.type);
  for (int y = 0; y < h; ++y) {
    float* row = dst + (std::size_t(y0 + y) * std::size_t(stride) + std::size_t(x0)) *
                           std::size_t(f.channels);
    for (int x = 0; x < w; ++x)
      std::memcpy(row + std::size_t(x) * f.channels, px, sizeof(float) * std::size_t(f.channels));
  }
}

/// Decodes one non-tiled block (constant, zip or diff-zip) of w x h texels into `dst` at
/// (x0, y0). `block` is exactly the block's bytes.
Status decode_block(const Ctx& ctx, const std::string& where, const Format& f,
                    std::uint32_t encoding, std::span<const std::uint8_t> block, float* dst,
                    int stride, int x0, int y0, int w, int h) {
  if (encoding == kConstant) {
    if (block.size() < std::size_t(f.pixel_size)) {
      return ctx.corrupt(where + ": constant block smaller than a pixel");
    }
    fill_block(f, block.data(), dst, stride, x0, y0, w, h);
    return Status::success();
  }
  if (encoding != kZipped && encoding != kDiffZipped) {
    return ctx.corrupt(where + ": tiled data inside a tile");
  }
  const std::size_t ds = std::size_t(data_size(f.type));
  const std::size_t plane = std::size_t(w) * std::size_t(h);
  if (!plausible_zip(block.size(), std::uint64_t(plane) * std::uint64_t(f.pixel_size))) {
    return ctx.corrupt(where + ": zipped block too small for its texels");
  }
  std::vector<std::uint8_t> raw(plane * std::size_t(f.pixel_size));
  if (!inflate_exact(block, raw)) return ctx.corrupt(where + ": zlib data corrupt or wrong size");
  if (encoding == kDiffZipped) {
    // Running sum over the whole block (all planes), in the data type's width.
    if (f.type == DataType::u8) {
      std::uint8_t prev = 0;
      for (std::uint8_t& b : raw) prev = b = std::uint8_t(b + prev);
    } else if (f.type == DataType::u16) {
      std::uint16_t prev = 0;
      for (std::size_t i = 0; i + 1 < raw.size(); i += 2) {
        prev = std::uint16_t(rd16(&raw[i]) + prev);
        raw[i] = std::uint8_t(prev & 0xFF);
        raw[i + 1] = std::uint8_t(prev >> 8);
      }
    }
  }
  // Planar: channel c's plane is w * h values, rows of increasing v.
  for (int c = 0; c < f.channels; ++c) {
    const std::uint8_t* src = raw.data() + std::size_t(c) * plane * ds;
    for (int y = 0; y < h; ++y) {
      float* row = dst + (std::size_t(y0 + y) * std::size_t(stride) + std::size_t(x0)) *
                             std::size_t(f.channels);
      for (int x = 0; x < w; ++x) {
        row[std::size_t(x) * f.channels + std::size_t(c)] =
            to_float(src + (std::size_t(y) * std::size_t(w) + std::size_t(x)) * ds, f.type);
      }
    }
  }
  return Status::success();
}

/// Decodes a level-0 face block (any encoding) of w x h texels into `dst`.
Status decode_face(const Ctx& ctx, const std::string& where, const Format& f,
                   std::uint32_t encoding, std::span<const std::uint8_t> block, int ulog2,
                   int vlog2, float* dst, EncodingCounts& counts) {
  const int w = 1 << ulog2, h = 1 << vlog2;
  if (encoding != kTiled) {
    if (encoding == kConstant) ++counts.constant;
    if (encoding == kZipped) ++counts.zipped;
    if (encoding == kDiffZipped) ++counts.diff_zipped;
    return decode_block(ctx, where, f, encoding, block, dst, w, 0, 0, w, h);
  }
  ++counts.tiled;
  if (block.size() < 6) return ctx.corrupt(where + ": tiled block shorter than its header");
  const int tu = std::int8_t(block[0]), tv = std::int8_t(block[1]);
  if (tu < 0 || tv < 0 || tu > ulog2 || tv > vlog2) {
    return ctx.corrupt(where + ": tile resolution out of range");
  }
  const std::uint32_t tile_header_size = rd32(block.data() + 2);
  if (tile_header_size > block.size() - 6) {
    return ctx.corrupt(where + ": tile header runs past the block");
  }
  const int ntu = 1 << (ulog2 - tu), ntv = 1 << (vlog2 - tv);
  const std::size_t ntiles = std::size_t(ntu) * std::size_t(ntv);
  if (!plausible_zip(tile_header_size, std::uint64_t(ntiles) * 4)) {
    return ctx.corrupt(where + ": tile header too small for " + std::to_string(ntiles) + " tiles");
  }
  std::vector<std::uint8_t> hdr(ntiles * 4);
  if (!inflate_exact(block.subspan(6, tile_header_size), hdr)) {
    return ctx.corrupt(where + ": tile header zlib data corrupt");
  }
  std::size_t pos = 6 + std::size_t(tile_header_size);
  for (std::size_t t = 0; t < ntiles; ++t) {
    const std::uint32_t fdh = rd32(&hdr[t * 4]);
    const std::uint32_t size = fdh & 0x3FFFFFFFu;
    if (size > block.size() - pos) return ctx.corrupt(where + ": tile data runs past the block");
    const int tx = int(t % std::size_t(ntu)), ty = int(t / std::size_t(ntu));
    Status s = decode_block(ctx, where + " tile " + std::to_string(t), f, fdh >> 30,
                            block.subspan(pos, size), dst, w, tx << tu, ty << tv, 1 << tu, 1 << tv);
    if (!s.ok()) return s;
    pos += size;
  }
  return Status::success();
}

}  // namespace

float half_to_float(std::uint16_t h) {
  const std::uint32_t sign = std::uint32_t(h >> 15) << 31;
  const int exp = (h >> 10) & 0x1F;
  const std::uint32_t mant = h & 0x3FFu;
  float f;
  if (exp == 0) {
    f = std::ldexp(float(mant), -24);  // zero or subnormal
    return sign ? -f : f;
  }
  std::uint32_t bits;
  if (exp == 31) {
    bits = sign | 0x7F800000u | (mant << 13);
  } else {
    bits = sign | (std::uint32_t(exp - 15 + 127) << 23) | (mant << 13);
  }
  std::memcpy(&f, &bits, 4);
  return f;
}

namespace {

/// Where the blocks lie, from the header: sizes and byte positions.
struct Layout {
  int nlevels = 0;
  std::uint32_t nfaces = 0;
  std::uint32_t faceinfo_size = 0, const_size = 0, levelinfo_size = 0;
  std::uint64_t leveldata_size = 0;
  std::uint64_t faceinfo_pos = 0, const_pos = 0, levelinfo_pos = 0, leveldata_pos = 0;
};

/// The header and the extended header into `file`; the block layout, checked against the bytes.
Result<Layout> read_header(const Ctx& ctx, PtexFile& file) {
  const std::span<const std::uint8_t> bytes = ctx.bytes;
  if (bytes.size() < kHeaderSize) return ctx.corrupt("shorter than a Ptex header (64 bytes)");
  const std::uint8_t* h = bytes.data();
  if (rd32(h) != kMagic) return ctx.corrupt("not a Ptex file (bad magic)");
  if (rd32(h + 4) != 1) {
    return ctx.error(ErrorCode::unsupported, "Ptex version " + std::to_string(rd32(h + 4)) +
                                                 " (only version 1 is supported)");
  }
  Layout L;
  const std::uint32_t mesh = rd32(h + 8), dtype = rd32(h + 12);
  if (mesh > 1) return ctx.corrupt("mesh type " + std::to_string(mesh) + " out of range");
  if (dtype > 3) return ctx.corrupt("data type " + std::to_string(dtype) + " out of range");
  file.mesh_type = MeshType(mesh);
  file.data_type = DataType(dtype);
  file.alpha_channel = std::int32_t(rd32(h + 16));
  file.channels = rd16(h + 20);
  L.nlevels = rd16(h + 22);
  L.nfaces = rd32(h + 24);
  const std::uint32_t ext_size = rd32(h + 28);
  L.faceinfo_size = rd32(h + 32);
  L.const_size = rd32(h + 36);
  L.levelinfo_size = rd32(h + 40);
  file.minor_version = int(rd32(h + 44));
  L.leveldata_size = rd64(h + 48);
  // The meta data size (h + 56) is not needed: meta data follows the level data.
  if (file.channels < 1 || file.channels > 64) {
    return ctx.corrupt("channel count " + std::to_string(file.channels) + " out of range 1..64");
  }
  if (file.alpha_channel < -1 || file.alpha_channel >= file.channels) file.alpha_channel = -1;
  if (L.nlevels < 1 || L.nlevels > kMaxFaceLog2 + 1) {
    return ctx.corrupt("level count " + std::to_string(L.nlevels) + " out of range");
  }
  if (L.nfaces < 1) return ctx.corrupt("no faces");
  // zlib cannot expand by more than ~1032:1, so the face count is bounded by the block size.
  if (!plausible_zip(L.faceinfo_size, std::uint64_t(L.nfaces) * kFaceInfoSize) ||
      L.nfaces > (1u << 24)) {
    return ctx.corrupt("face count " + std::to_string(L.nfaces) +
                       " does not fit the face-info block");
  }
  if (L.levelinfo_size != std::uint64_t(L.nlevels) * kLevelInfoSize) {
    return ctx.corrupt("level-info size " + std::to_string(L.levelinfo_size) + " for " +
                       std::to_string(L.nlevels) + " levels");
  }

  // Extended header (older files may have a shorter one; missing fields read as 0).
  std::uint8_t ext[kExtHeaderSize] = {};
  if (!ctx.in_range(kHeaderSize, ext_size)) return ctx.corrupt("extended header runs past EOF");
  std::memcpy(ext, h + kHeaderSize, std::min<std::size_t>(ext_size, kExtHeaderSize));
  file.border_mode_u = rd16(ext);
  file.border_mode_v = rd16(ext + 4);
  const std::uint64_t edit_size = rd64(ext + 24);
  if (edit_size > 0) {
    return ctx.error(ErrorCode::unsupported, "files with edit data are not supported");
  }

  // Block offsets.
  std::uint64_t pos = kHeaderSize + std::uint64_t(ext_size);
  L.faceinfo_pos = pos;
  pos += L.faceinfo_size;
  L.const_pos = pos;
  pos += L.const_size;
  L.levelinfo_pos = pos;
  pos += L.levelinfo_size;
  L.leveldata_pos = pos;
  if (!ctx.in_range(L.faceinfo_pos,
                    std::uint64_t(L.faceinfo_size) + L.const_size + L.levelinfo_size) ||
      !ctx.in_range(L.leveldata_pos, L.leveldata_size)) {
    return ctx.corrupt("header block sizes run past the end of the file (truncated?)");
  }
  return L;
}

/// The face-info block: every face's resolution, adjacency and flags.
Status read_face_info(const Ctx& ctx, const Layout& L, PtexFile& file) {
  std::vector<std::uint8_t> fi(std::size_t(L.nfaces) * kFaceInfoSize);
  if (!inflate_exact(ctx.bytes.subspan(std::size_t(L.faceinfo_pos), L.faceinfo_size), fi)) {
    return ctx.corrupt("face-info zlib data corrupt or wrong size");
  }
  file.faces.resize(L.nfaces);
  for (std::uint32_t f = 0; f < L.nfaces; ++f) {
    const std::uint8_t* p = &fi[std::size_t(f) * kFaceInfoSize];
    FaceInfo& info = file.faces[f];
    info.ulog2 = std::int8_t(p[0]);
    info.vlog2 = std::int8_t(p[1]);
    if (info.ulog2 < 0 || info.vlog2 < 0 || info.ulog2 > kMaxFaceLog2 ||
        info.vlog2 > kMaxFaceLog2) {
      return ctx.error(ErrorCode::unsupported, "face " + std::to_string(f) + ": resolution 2^" +
                                                   std::to_string(info.ulog2) + " x 2^" +
                                                   std::to_string(info.vlog2) +
                                                   " out of range 0..15");
    }
    for (int e = 0; e < 4; ++e) {
      info.adj_edges[std::size_t(e)] = (p[2] >> (2 * e)) & 3;
      const std::int32_t a = std::int32_t(rd32(p + 4 + 4 * e));
      if (a < -1 || a >= std::int32_t(L.nfaces)) {
        return ctx.corrupt("face " + std::to_string(f) + ": adjacent face " + std::to_string(a) +
                           " out of range");
      }
      info.adj_faces[std::size_t(e)] = a;
    }
    info.constant = (p[3] & 1) != 0;
    info.subface = (p[3] & 8) != 0;
  }
  return Status::success();
}

/// The constant-data block: one pixel per face, as floats.
Status read_constant_data(const Ctx& ctx, const Layout& L, const Format& fmt, PtexFile& file) {
  file.constant_data.resize(std::size_t(L.nfaces) * std::size_t(file.channels));
  if (!plausible_zip(L.const_size, std::uint64_t(L.nfaces) * std::uint64_t(fmt.pixel_size))) {
    return ctx.corrupt("constant-data block too small for " + std::to_string(L.nfaces) + " faces");
  }
  std::vector<std::uint8_t> cd(std::size_t(L.nfaces) * std::size_t(fmt.pixel_size));
  if (!inflate_exact(ctx.bytes.subspan(std::size_t(L.const_pos), L.const_size), cd)) {
    return ctx.corrupt("constant-data zlib data corrupt or wrong size");
  }
  const int ds = data_size(fmt.type);
  for (std::size_t i = 0; i < file.constant_data.size(); ++i) {
    file.constant_data[i] = to_float(&cd[i * std::size_t(ds)], fmt.type);
  }
  return Status::success();
}

/// The level-info block (sizes must add up to the level-data block), then the budget for
/// decoded texels, checked before any face is allocated.
Status read_level_info(const Ctx& ctx, const Layout& L, const ParseOptions& options,
                       PtexFile& file) {
  std::uint64_t total = 0;
  for (int l = 0; l < L.nlevels; ++l) {
    const std::uint8_t* p = ctx.bytes.data() + L.levelinfo_pos + std::size_t(l) * kLevelInfoSize;
    LevelInfo li{rd64(p), rd32(p + 8), rd32(p + 12)};
    if (li.face_count > L.nfaces || (l == 0 && li.face_count != L.nfaces)) {
      return ctx.corrupt("level " + std::to_string(l) + ": face count " +
                         std::to_string(li.face_count) + " does not match " +
                         std::to_string(L.nfaces) + " faces");
    }
    if (li.data_size > L.leveldata_size - total || li.header_size > li.data_size) {
      return ctx.corrupt("level " + std::to_string(l) + ": data size runs past the level data");
    }
    total += li.data_size;
    file.levels.push_back(li);
  }
  std::uint64_t floats = 0;
  for (const FaceInfo& f : file.faces) {
    floats += (std::uint64_t(1) << (f.ulog2 + f.vlog2)) * std::uint64_t(file.channels);
  }
  if (floats > options.max_floats) {
    return ctx.error(ErrorCode::too_large, "faces hold " + std::to_string(floats) +
                                               " values, more than the limit " +
                                               std::to_string(options.max_floats));
  }
  return Status::success();
}

/// Face `f` of level 0 into file.texels[f]: the constant pixel, or its data decoded.
Status read_level0_face(const Ctx& ctx, const Format& fmt, std::uint32_t f, std::uint32_t d,
                        std::span<const std::uint8_t> data, PtexFile& file) {
  const FaceInfo& info = file.faces[f];
  std::vector<float>& tex = file.texels[f];
  tex.resize((std::size_t(1) << (info.ulog2 + info.vlog2)) * std::size_t(file.channels));
  const std::string where = "level 0 face " + std::to_string(f);
  if (!info.constant) {
    return decode_face(ctx, where, fmt, d >> 30, data, info.ulog2, info.vlog2, tex.data(),
                       file.encodings);
  }
  // The constant-data pixel is authoritative for constant faces.
  for (int c = 0; c < file.channels; ++c) {
    tex[std::size_t(c)] = file.constant_data[std::size_t(f) * file.channels + c];
  }
  for (std::size_t i = std::size_t(file.channels); i < tex.size(); ++i) {
    tex[i] = tex[i % std::size_t(file.channels)];
  }
  ++file.encodings.constant;
  return Status::success();
}

/// Every level: face-data headers, block sizes within the level. Level 0 is decoded.
Status read_levels(const Ctx& ctx, const Layout& L, const Format& fmt, PtexFile& file) {
  std::uint64_t level_pos = L.leveldata_pos;
  file.texels.resize(L.nfaces);
  for (int l = 0; l < L.nlevels; ++l) {
    const LevelInfo& li = file.levels[std::size_t(l)];
    const std::string lname = "level " + std::to_string(l);
    if (!plausible_zip(li.header_size, std::uint64_t(li.face_count) * 4)) {
      return ctx.corrupt(lname + ": face-data header too small for its faces");
    }
    std::vector<std::uint8_t> fdh(std::size_t(li.face_count) * 4);
    if (!inflate_exact(ctx.bytes.subspan(std::size_t(level_pos), li.header_size), fdh)) {
      return ctx.corrupt(lname + ": face-data header zlib data corrupt or wrong size");
    }
    std::uint64_t p = level_pos + li.header_size;
    const std::uint64_t end = level_pos + li.data_size;
    for (std::uint32_t f = 0; f < li.face_count; ++f) {
      const std::uint32_t d = rd32(&fdh[std::size_t(f) * 4]);
      const std::uint32_t size = d & 0x3FFFFFFFu;
      if (size > end - p)
        return ctx.corrupt(lname + " face " + std::to_string(f) + ": data runs past the level");
      if (l == 0) {
        Status s = read_level0_face(ctx, fmt, f, d, ctx.bytes.subspan(std::size_t(p), size), file);
        if (!s.ok()) return s;
      }
      p += size;
    }
    level_pos += li.data_size;
  }
  return Status::success();
}

}  // namespace

Result<PtexFile> parse_ptex(std::span<const std::uint8_t> bytes, const std::string& name,
                            const ParseOptions& options) {
  const Ctx ctx{bytes, name};
  PtexFile file;
  Result<Layout> layout = read_header(ctx, file);
  if (!layout) return layout.status();
  const Format fmt{file.data_type, file.channels, data_size(file.data_type) * file.channels};
  if (Status s = read_face_info(ctx, *layout, file); !s.ok()) return s;
  if (Status s = read_constant_data(ctx, *layout, fmt, file); !s.ok()) return s;
  if (Status s = read_level_info(ctx, *layout, options, file); !s.ok()) return s;
  if (Status s = read_levels(ctx, *layout, fmt, file); !s.ok()) return s;
  return file;
}

Result<PtexFile> read_ptex(const std::string& path, const ParseOptions& options) {
  Result<std::vector<std::uint8_t>> bytes = io::read_file(path);
  if (!bytes) return bytes.status();
  return parse_ptex(*bytes, path, options);
}

}  // namespace tessera::ptex
