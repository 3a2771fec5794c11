// tessera/gl_ptex.h — per-face (Ptex-style) textures packed for the GPU: the layout of a
// faces::FaceTextureSet as one GL_TEXTURE_2D_ARRAY per face-resolution class and one std430
// face-record buffer (neighbours, edge mappings, valence-4 corners), which
// share/tessera/glsl/seams.glsl reads (the GL twin of the CPU's adjacency and corner links).
// Part of the optional `tessera::gl` library (src/gl/ptex_pack.cpp).
//
// `pack_faces` is pure (no GL); `FaceTextures::upload` and `bind` need a current tessera
// context on the calling thread (tessera/gl.h), and the objects should be destroyed while it is
// current and alive.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "tessera/core.h"
#include "tessera/gl.h"

namespace tessera::faces {
class FaceTextureSet;
}

namespace tessera::gl {

// Per-face textures for the GPU (Toth 2013 / McDonald 2013 layout).

/// One face's record in the face-record buffer: std430, 80 bytes, five ivec4:
///
///   struct FaceRecord {          // GLSL, std430 (share/tessera/glsl/seams.glsl)
///     ivec4 info;                // x: class (the texture array), y: layer in it,
///                                // z, w: level-0 width and height in texels
///     ivec4 neighbour;           // face across edge e (0..3), -1 on a border
///     ivec4 mapping;             // e * 4 + the neighbour's shared edge: the index of the
///                                // transform my UV -> neighbour UV in the 16-entry table
///                                // (faces::edge_transform_table); -1 on a border
///     ivec4 corner;              // diagonal face at corner c (valence-4 vertex), -1 none
///     ivec4 corner_mapping;      // m1 * 16 + m2: corner transform = table[m2] after
///                                // table[m1] (across edge c, then across the next edge)
///   };
///   layout(std430) readonly buffer Faces { FaceRecord faces[]; };
///
/// Exactly the CPU `FaceTextureSet`'s adjacency (`adjacency(f)`) and corner links
/// (`corner(f, c)`), so GL and CPU traverse the same faces through the same transforms.
struct FaceRecord {
  std::array<std::int32_t, 4> info{0, 0, 0, 0};
  std::array<std::int32_t, 4> neighbour{-1, -1, -1, -1};
  std::array<std::int32_t, 4> mapping{-1, -1, -1, -1};
  std::array<std::int32_t, 4> corner{-1, -1, -1, -1};
  std::array<std::int32_t, 4> corner_mapping{-1, -1, -1, -1};
};
static_assert(sizeof(FaceRecord) == 80, "FaceRecord must match the std430 layout");

/// One texture array: the faces of one level-0 resolution.
struct FaceClass {
  int width = 0, height = 0;  ///< Level-0 texels.
  int levels = 0;             ///< The full chain (as the CPU textures have).
  std::vector<int> faces;     ///< Layer l holds face faces[l].
};

/// The GPU layout of a face set: classes ordered by (height, width), faces in index order
/// within a class.
struct PackedFaces {
  std::vector<FaceClass> classes;
  std::vector<FaceRecord> records;  ///< One per face, index = face id.
};

/// Limits the packing must respect (from `Context::limits()`; 0 = unchecked).
struct PackLimits {
  int max_texture_size = 0;
  int max_array_layers = 0;
  int max_classes = 0;  ///< E.g. the texture units a shader can bind.
  std::int64_t max_ssbo_bytes = 0;
};

/// The layout of `set` for the GPU. Fails with too_large naming the limit ("97 faces of 64x64
/// exceed GL_MAX_ARRAY_TEXTURE_LAYERS = 64") or invalid_argument on an empty set. Pure (no GL).
Result<PackedFaces> pack_faces(const faces::FaceTextureSet& set, const PackLimits& limits = {});

enum class TexelFormat {
  rgba32f,  ///< Exactly the CPU texels (default): GL samples the same values as tessera.
  rgba16f,  ///< Half the memory; texels rounded to binary16 by the driver on upload.
};

struct FaceTexturesOptions {
  TexelFormat format = TexelFormat::rgba32f;
  /// Upper bound of the GL_TEXTURE_MAX_ANISOTROPY of the samplers (1..16; clamped to the
  /// implementation's maximum).
  float max_anisotropy = 16.0f;
};

/// The GL objects of a packed face set: one GL_TEXTURE_2D_ARRAY per class with every mip
/// level uploaded from the CPU chains (no glGenerateMipmap: GL and CPU filter the same
/// texels), a GL_SHADER_STORAGE_BUFFER of `FaceRecord`s, and two sampler objects: clamp-to-
/// border (0,0,0,0) and clamp-to-edge, both trilinear with anisotropy.
class FaceTextures {
 public:
  /// Packs and uploads `set` (checking the current context's limits). Needs a current context.
  static Result<FaceTextures> upload(const faces::FaceTextureSet& set,
                                     const FaceTexturesOptions& options = {});

  const PackedFaces& layout() const { return layout_; }
  int class_count() const { return int(arrays_.size()); }
  std::uint32_t array_texture(int cls) const { return arrays_[std::size_t(cls)].get(); }
  std::uint32_t record_buffer() const { return records_.get(); }
  std::uint32_t border_sampler() const { return border_sampler_.get(); }
  std::uint32_t clamp_sampler() const { return clamp_sampler_.get(); }
  /// Bytes of texture storage (all levels of all arrays).
  std::uint64_t texture_bytes() const { return texture_bytes_; }

  /// Binds class c's array to texture units first_unit + c (border sampler) and, when
  /// `clamp_units` is true, also to first_unit + classes + c (clamp sampler, for the Clamp
  /// method and Discard's zero-coverage fallback); binds the record buffer to
  /// GL_SHADER_STORAGE_BUFFER binding `ssbo_binding`.
  /// Fails (invalid_argument) when the units needed exceed GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS.
  Status bind(int first_unit, int ssbo_binding, bool clamp_units = true) const;

 private:
  PackedFaces layout_;
  std::vector<Object> arrays_;
  Object records_, border_sampler_, clamp_sampler_;
  std::uint64_t texture_bytes_ = 0;
};

}  // namespace tessera::gl
