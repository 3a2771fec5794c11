// tessera/gl_faces.h — per-face (Ptex-style) textures for the GPU: a faces::FaceTextureSet packed
// as one GL_TEXTURE_2D_ARRAY per face-resolution class plus a std430 face-record buffer, which
// the shipped seams.glsl reads in the engine's own shaders (tessera_seams_sample_discard, ...).
// Contract: `pack_faces` (the layout of tessera/faces_gpu.h) is pure;
// `FaceTextureSet::upload` and `bind` work on the OpenGL 4.5 core context current on the
// calling thread, whoever made it (entry points as tessera/gl.h says: `load_entry_points` or
// first-use resolution; no tessera `Context` needed), and fail with one line without one.
// `upload` leaves the engine's GL state as it found it (it sets and restores the pixel-unpack
// state); `bind` changes exactly the binding points it is given. Destroy the objects while
// their context is current. The recipe (mesh, upload, vertex
// and fragment stages, per-frame bind) is docs/engine_integration.md; examples/engine_ptex does
// it in one file; Tests: tests/gl/gl_faces_bind_test.cpp, gl_engine_context*.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "tessera/core.h"
#include "tessera/faces_gpu.h"
#include "tessera/gl.h"

namespace tessera::gl {

// Per-face textures for the GPU (Toth 2013 / McDonald 2013 layout): the layout is the
// backends' shared one (tessera/faces_gpu.h: faces::PackedFaces, faces::FaceRecord, ...).

/// faces::pack_faces with GL's names of the limits in its messages ("97 faces of 64x64 exceed
/// GL_MAX_ARRAY_TEXTURE_LAYERS = 64", "above GL_MAX_TEXTURE_SIZE", "exceed
/// GL_MAX_SHADER_STORAGE_BLOCK_SIZE"); invalid_argument on an empty set. Pure (no GL).
Result<faces::PackedFaces> pack_faces(const faces::FaceTextureSet& set,
                                      const faces::PackLimits& limits = {});

struct FaceTextureSetOptions {
  /// The arrays' texel format (tessera/faces_gpu.h): GL_RGBA32F (the CPU texels, default),
  /// GL_RGBA16F, GL_RGBA8, GL_SRGB8_ALPHA8 (converted by faces::convert_texels: the bytes
  /// Vulkan uploads).
  faces::TexelFormat format = faces::TexelFormat::rgba32f;
  /// Upper bound of the GL_TEXTURE_MAX_ANISOTROPY of the samplers (1..16; clamped to the
  /// implementation's maximum).
  float max_anisotropy = 16.0f;
};

/// The binding points `FaceTextureSet::bind` uses, chosen by the caller (seams.glsl's macros of
/// the same meaning: TESSERA_SEAMS_FIRST_UNIT, TESSERA_SEAMS_CLAMP_UNIT,
/// TESSERA_SEAMS_FACES_BINDING; `FaceTextureSet::glsl_defines` writes them).
struct FaceTextureSetBindings {
  int border_unit = 0;      ///< First texture unit of the clamp-to-border arrays (one per class).
  int clamp_unit = -1;      ///< First unit of the clamp-to-edge arrays; -1 = right after the
                            ///< border units (border_unit + class_count()).
  int records_binding = 0;  ///< Indexed GL_SHADER_STORAGE_BUFFER binding of the face records.
  /// Bind the clamp-to-edge units too. They are read by Clamp, Traverse and Discard's
  /// zero-coverage fallback (`clamp_fallback` true); without them only
  /// tessera_seams_sample_discard(..., false) gives defined results.
  bool clamp = true;
};

/// The GL objects of a packed face set: one GL_TEXTURE_2D_ARRAY per class with every mip
/// level uploaded from the CPU chains (no glGenerateMipmap: GL and CPU filter the same
/// texels), a GL_SHADER_STORAGE_BUFFER of `faces::FaceRecord`s, and two sampler objects: clamp-to-
/// border (0,0,0,0) and clamp-to-edge, both trilinear with anisotropy.
class FaceTextureSet {
 public:
  /// Packs and uploads `set` (checking the current context's limits); the pixel-unpack state
  /// (alignment, row length, skips, GL_PIXEL_UNPACK_BUFFER) is set for the upload and restored.
  static Result<FaceTextureSet> upload(const faces::FaceTextureSet& set,
                                       const FaceTextureSetOptions& options = {});

  const faces::PackedFaces& layout() const { return layout_; }
  int class_count() const { return int(arrays_.size()); }
  std::uint32_t array_texture(int cls) const { return arrays_[std::size_t(cls)].get(); }
  std::uint32_t record_buffer() const { return records_.get(); }
  std::uint32_t border_sampler() const { return border_sampler_.get(); }
  std::uint32_t clamp_sampler() const { return clamp_sampler_.get(); }
  /// Bytes of texture storage (all levels of all arrays).
  std::uint64_t texture_bytes() const { return texture_bytes_; }

  /// Binds the objects to the caller's binding points. For each class c = 0 .. class_count()-1:
  /// texture unit `b.border_unit + c` gets array_texture(c) (on its GL_TEXTURE_2D_ARRAY target)
  /// and border_sampler(); when `b.clamp` is true, unit `b.clamp_unit + c` (or
  /// border_unit + class_count() + c when clamp_unit is -1) gets array_texture(c) and
  /// clamp_sampler(). The record buffer goes to the indexed GL_SHADER_STORAGE_BUFFER binding
  /// `b.records_binding`.
  ///
  /// GL state touched: exactly those units' GL_TEXTURE_2D_ARRAY and sampler bindings and that
  /// one indexed storage-buffer binding (its whole range). Nothing else: not the active texture
  /// unit, not the generic GL_SHADER_STORAGE_BUFFER binding (glBindBuffersBase leaves it), no
  /// program, framebuffer, vertex array or other unit. Nothing is restored afterwards: to
  /// restore, the caller re-binds its own objects on those points. GL errors pending before
  /// the call are reported as its failure (glGetError).
  /// Fails (invalid_argument, before any GL call that binds) when a unit or binding is
  /// negative, the border and clamp unit ranges overlap, or a unit exceeds
  /// GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS or the binding GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS.
  Status bind(const FaceTextureSetBindings& b) const;

  /// `bind({first_unit, -1, ssbo_binding, clamp_units})`: border units first_unit + c, clamp
  /// units first_unit + class_count() + c (the defaults of seams.glsl).
  Status bind(int first_unit, int ssbo_binding, bool clamp_units = true) const;

  /// The lines a shader that includes seams.glsl needs before the include for `b`:
  /// "#define TESSERA_SEAMS_CLASSES N", "#define TESSERA_SEAMS_FIRST_UNIT U",
  /// "#define TESSERA_SEAMS_CLAMP_UNIT V" and "#define TESSERA_SEAMS_FACES_BINDING B" (for
  /// glsl::ExpandOptions::preamble, or pasted after #version).
  std::vector<std::string> glsl_defines(const FaceTextureSetBindings& b) const;

 private:
  faces::PackedFaces layout_;
  std::vector<Object> arrays_;
  Object records_, border_sampler_, clamp_sampler_;
  std::uint64_t texture_bytes_ = 0;
};

}  // namespace tessera::gl
