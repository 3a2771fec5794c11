// tessera/ptex.h — a reader for Ptex (.ptx) per-face texture files.
//
// What: `parse_ptex` turns the bytes of a .ptx file into level 0 of every face as normalised
//   floats (u8 / 255, u16 / 65535, half and float as stored), with the adjacency the file
//   stores; all four encodings and data types, quad meshes (split non-quad faces as subfaces).
// Format: Burley & Lacewell 2008 and the Ptex file-format documentation; the layout, block by
//   block, is in src/ptex/ptex_reader.cpp. Stored reduction levels are checked, not decoded
//   (`faces::FaceTextureSet` builds its own mip chains).
// Refused (`unsupported`): triangle meshes, face-data edits, faces beyond 2^15 texels a side.
// Conventions: face f's texel (x, y) covers u in [x/w, (x+1)/w], v in [y/h, (y+1)/h], with
//   (u, v) = (0,0), (1,0), (1,1), (0,1) at vertices 0..3 and edge e joining vertices e, e+1.
// Errors: one line naming the file ("teapot.ptx: level 0 face 12: zlib data corrupt"); every
//   size is checked before allocating, no read outside the bytes (fuzz/fuzz_ptex.cpp).
// Threads: pure functions, thread-safe.
// Tests: tests/unit/ptex_test.cpp (reader, bad files), tests/gl/gl_faces_test.cpp (the Disney
// samples).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "tessera/core.h"

namespace tessera::ptex {

enum class MeshType { triangle = 0, quad = 1 };
enum class DataType { u8 = 0, u16 = 1, half = 2, f32 = 3 };

/// Largest log2 resolution of a face side tessera accepts (32768 texels).
inline constexpr int kMaxFaceLog2 = 15;

/// One face's header entry.
struct FaceInfo {
  int ulog2 = 0;                                 ///< log2 of the width in texels (0..kMaxFaceLog2).
  int vlog2 = 0;                                 ///< log2 of the height.
  std::array<int, 4> adj_faces{-1, -1, -1, -1};  ///< Neighbour across edge e, -1 on a border.
  std::array<int, 4> adj_edges{0, 0, 0, 0};      ///< The neighbour's edge that is shared.
  bool constant = false;  ///< The face is a single colour (its constant-data pixel).
  bool subface = false;   ///< Part of a non-quad face split into quads.
  int width() const { return 1 << ulog2; }
  int height() const { return 1 << vlog2; }
};

/// Size and encoding of one stored level (as found in the file).
struct LevelInfo {
  std::uint64_t data_size = 0;    ///< Bytes of the level including its header.
  std::uint32_t header_size = 0;  ///< Zipped size of the face-data-header array.
  std::uint32_t face_count = 0;   ///< Faces stored at this level.
};

/// Counts of the face encodings met at level 0 (for tests and `ptex info`-like output).
struct EncodingCounts {
  int constant = 0, zipped = 0, diff_zipped = 0, tiled = 0;
};

/// A decoded .ptx file: per-face level-0 texels as normalised floats.
struct PtexFile {
  MeshType mesh_type = MeshType::quad;
  DataType data_type = DataType::u8;
  int channels = 0;        ///< 1..64 channels per texel.
  int alpha_channel = -1;  ///< Index of alpha, -1 = none.
  int minor_version = 0;
  int border_mode_u = 0, border_mode_v = 0;  ///< 0 clamp, 1 black, 2 periodic (unused here).
  std::vector<FaceInfo> faces;
  std::vector<LevelInfo> levels;  ///< Stored levels (level 0 first).
  EncodingCounts encodings;       ///< Level-0 face encodings (tiles counted once per face).
  /// Constant (average) colour of each face: `channels` floats per face.
  std::vector<float> constant_data;
  /// Level-0 texels of face f: width * height * channels floats, row-major (rows of
  /// increasing v, u fastest), channels interleaved.
  std::vector<std::vector<float>> texels;

  int face_count() const { return int(faces.size()); }
};

/// Limits of `parse_ptex` (a hostile file cannot make it allocate more).
struct ParseOptions {
  /// Largest number of decoded floats over all faces (texels x channels); too_large beyond.
  std::uint64_t max_floats = std::uint64_t{1} << 27;
};

/// Parses a whole .ptx file from memory. `name` (usually the path) prefixes every error.
Result<PtexFile> parse_ptex(std::span<const std::uint8_t> bytes, const std::string& name,
                            const ParseOptions& options = {});

/// Reads and parses a .ptx file.
Result<PtexFile> read_ptex(const std::string& path, const ParseOptions& options = {});

/// Converts an IEEE 754 binary16 value to float (all cases: zero, subnormal, inf, NaN).
float half_to_float(std::uint16_t h);

}  // namespace tessera::ptex
