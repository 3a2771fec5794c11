// tessera/gl_ptex.h — per-face (Ptex-style) textures packed for the GPU: the layout of a
// faces::FaceTextureSet as one GL_TEXTURE_2D_ARRAY per face-resolution class and one std430
// face-record buffer (neighbours, edge mappings, valence-4 corners), which
// share/tessera/glsl/seams.glsl reads (the GL twin of the CPU's adjacency and corner links).
// Part of the optional `tessera::gl` library (src/gl/ptex_pack.cpp).
//
// `pack_faces` and `ptex_quad_mesh` are pure (no GL); `FaceTextures::upload` and `bind` need a
// current tessera context on the calling thread (tessera/gl.h), and the objects should be
// destroyed while it is current and alive.
//
// Recipe: per-face textures in an engine's own shader (examples/engine_ptex/main.cpp does all
// of this in one file)
// -------------------------------------------------------------------------------------------
// What is supported: Ptex files of quad meshes (mesh type 1), including quad-mesh files whose
// non-quad polygons were split into subfaces by the Ptex convention (the Disney samples
// nonquad.ptx and pentagon.ptx: an n-gon becomes n quads, see faces::ptex_face_layout). Not
// supported: Ptex triangle-mesh files (mesh type 0, e.g. triangle.ptx: `ptex_quad_mesh` and
// faces::FaceTextureSet::from_ptex fail with unsupported), and any non-quad polygon of the mesh
// that the Ptex file did not split (`ptex_quad_mesh` fails naming the polygon). A triangle mesh
// can be used after splitting each triangle into three quads (corner, edge midpoint, centre,
// edge midpoint; again faces::ptex_face_layout) and authoring the Ptex file on that layout.
//
//   1. Mesh and textures (pure):
//        faces::PolygonMesh obj = faces::load_obj_polygons("teapot.obj")
//        ptex::PtexFile file = ptex::read_ptex("teapot.ptx")
//        faces::QuadMesh mesh = gl::ptex_quad_mesh(obj, file, "teapot")  // face f = Ptex face f
//        faces::FaceTextureSet set = faces::FaceTextureSet::from_ptex(file, "teapot.ptx")
//   2. Upload once, with the engine's context current:
//        gl::FaceTextures tex = gl::FaceTextures::upload(set)
//   3. Vertex stage (the engine's own): draw each quad face f as two triangles of its four
//      corners 0..3 in mesh order, and pass to the fragment stage
//        flat int face   = f                      (the Ptex face id = the face-record index)
//        vec2 uv         = (0,0), (1,0), (1,1), (0,1) at corners 0, 1, 2, 3
//      interpolated perspective-correctly (the default). Corners must not be shared between
//      faces (each face has its own UV square), so a mesh of F faces draws 4F vertices.
//      Triangles (0,1,2) and (0,2,3) are the split tessera's renderers use (the other diagonal
//      works too, but draws a non-planar face differently).
//   4. Fragment stage (the engine's own): the preamble `tex.glsl_defines(bindings)` (the
//      class count and the binding points) after #version, `#include "seams.glsl"` (installed
//      in tessera_GLSL_DIR; gl::link_program resolves it, or paste the file after the
//      defines), then
//        vec4 s = tessera_seams_sample_discard(face, uv, dFdx(uv), dFdy(uv), true);
//      with the gradients taken in uniform control flow (the lookups use them explicitly, so
//      the per-face class switch inside is safe). s.rgb is the filtered linear colour without
//      seams (Toth 2013), s.a the coverage; light it as the engine likes.
//   5. Per frame, before the draw: `tex.bind(bindings)` with the binding points the engine
//      chose (FaceTexturesBindings). It binds exactly the units and the storage-buffer index
//      named there and nothing else (see `bind`); the engine's own textures go on other
//      units.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "tessera/core.h"
#include "tessera/gl.h"

namespace tessera::faces {
class FaceTextureSet;
struct PolygonMesh;
struct QuadMesh;
}  // namespace tessera::faces

namespace tessera::ptex {
struct PtexFile;
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

/// The binding points `FaceTextures::bind` uses, chosen by the caller (seams.glsl's macros of
/// the same meaning: TESSERA_SEAMS_FIRST_UNIT, TESSERA_SEAMS_CLAMP_UNIT,
/// TESSERA_SEAMS_FACES_BINDING; `FaceTextures::glsl_defines` writes them).
struct FaceTexturesBindings {
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
  Status bind(const FaceTexturesBindings& b) const;

  /// `bind({first_unit, -1, ssbo_binding, clamp_units})`: border units first_unit + c, clamp
  /// units first_unit + class_count() + c (the defaults of seams.glsl).
  Status bind(int first_unit, int ssbo_binding, bool clamp_units = true) const;

  /// The lines a shader that includes seams.glsl needs before the include for `b`:
  /// "#define TESSERA_SEAMS_CLASSES N", "#define TESSERA_SEAMS_FIRST_UNIT U",
  /// "#define TESSERA_SEAMS_CLAMP_UNIT V" and "#define TESSERA_SEAMS_FACES_BINDING B" (for
  /// glsl::ExpandOptions::preamble, or pasted after #version).
  std::vector<std::string> glsl_defines(const FaceTexturesBindings& b) const;

 private:
  PackedFaces layout_;
  std::vector<Object> arrays_;
  Object records_, border_sampler_, clamp_sampler_;
  std::uint64_t texture_bytes_ = 0;
};

/// The quad mesh of a Ptex file's faces from the polygon mesh it was painted on (step 1 of the
/// recipe above): face f of the result is Ptex face f. A quad of `mesh` is one face; an n-gon
/// (n = 3 or n >= 5) must have been split by the file into n subfaces (FaceInfo::subface) and
/// becomes the n quads of faces::ptex_face_layout. Fails with unsupported naming the polygon
/// ("teapot: polygon 12 has 3 vertices, but Ptex face 12 is not a subface: only quads, and
/// n-gons the Ptex file split into subfaces, are supported") when an n-gon was not split, with
/// size_mismatch when the counts of faces differ or a quad meets a subface, and with
/// unsupported on a triangle-mesh file. `name` prefixes the messages. Pure (no GL).
Result<faces::QuadMesh> ptex_quad_mesh(const faces::PolygonMesh& mesh, const ptex::PtexFile& file,
                                       const std::string& name);

}  // namespace tessera::gl
