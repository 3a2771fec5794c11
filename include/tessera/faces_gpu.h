// tessera/faces_gpu.h — the GPU layout of per-face (Ptex-style) textures, shared by every GPU
// backend (gl::FaceTextureSet in gl_faces.h, vk::FaceTextureSet in vk_faces.h): which faces go
// into which texture array (one per level-0 resolution, the "class"), at which layer, and the
// std430 face-record buffer seams.glsl reads (adjacency and corner links of the CPU
// faces::FaceTextureSet). Pure CPU data: no GL, no Vulkan; the backends upload exactly these
// bytes, so GL and Vulkan traverse the same faces through the same transforms as the CPU.
// Contract: every function here is pure and thread-safe. `ptex_quad_mesh` maps a Ptex file's
// polygon mesh to the quad mesh of its faces (the mesh an engine draws with these textures);
// `class_grouped_indices` is the class-grouped index list the GPU face renderers draw.
// Tests: tests/gl/gl_faces_test.cpp (layout vs CPU adjacency), tests/vk/vk_faces_test.cpp.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "tessera/core.h"

namespace tessera::ptex {
struct PtexFile;
}

namespace tessera::faces {

class FaceTextureSet;
struct PolygonMesh;
struct QuadMesh;

/// One face's record in the face-record buffer: std430, 80 bytes, five ivec4:
///
///   struct TesseraFaceRecord {   // GLSL, std430 (share/tessera/glsl/seams.glsl)
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
///   layout(std430) readonly buffer Faces { TesseraFaceRecord faces[]; };
///
/// Exactly the CPU `FaceTextureSet`'s adjacency (`adjacency(f)`) and corner links
/// (`corner(f, c)`), so the GPU and the CPU traverse the same faces through the same transforms.
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

/// Limits the packing must respect (the backend's device limits; 0 = unchecked).
struct PackLimits {
  int max_texture_size = 0;
  int max_array_layers = 0;
  int max_classes = 0;  ///< E.g. the texture units a shader can bind.
  std::int64_t max_ssbo_bytes = 0;
};

/// The backend's names of the limits, for the error messages ("GL_MAX_TEXTURE_SIZE",
/// "maxImageDimension2D", ...).
struct PackLimitNames {
  std::string texture_size = "the maximum texture size";
  std::string array_layers = "the maximum array layers";
  std::string ssbo_bytes = "the maximum storage-buffer size";
};

/// The layout of `set` for the GPU. Fails with too_large naming the limit ("97 faces of 64x64
/// exceed GL_MAX_ARRAY_TEXTURE_LAYERS = 64", the name from `names`), or invalid_argument on an
/// empty set or faces of one resolution with different mip counts.
Result<PackedFaces> pack_faces(const FaceTextureSet& set, const PackLimits& limits,
                               const PackLimitNames& names);

/// How the backends store the texels of the face arrays (gl:: and vk::FaceTextureSetOptions).
enum class TexelFormat {
  rgba32f,      ///< Exactly the CPU texels (default): the GPU samples tessera's values.
  rgba16f,      ///< binary16, half the memory (rounded to nearest even).
  rgba8_unorm,  ///< 8 bits per channel of the linear values (round(255 * clamp(v, 0, 1))).
  rgba8_srgb,   ///< 8-bit sRGB-encoded colour (exact curve, rounded), linear alpha; the GPU
                ///< decodes to linear when it samples: a quarter of the memory.
};
/// Bytes per texel of `format` (16, 8, 4, 4).
std::size_t texel_bytes(TexelFormat format);
/// Converts `texels` RGBA float texels to `format` into `out` (texel_bytes(format) each),
/// little-endian as the GPU formats store them. The same bytes on every CPU. Pure.
void convert_texels(const float* rgba, std::size_t texels, TexelFormat format, std::uint8_t* out);

/// One draw call of a class-grouped index list: face class `cls` (the texture array every face
/// of the draw samples) and its `count` indices from index `first`.
struct FaceClassDraw {
  int cls = 0;
  std::size_t first = 0, count = 0;
};

/// The index list every GPU face renderer draws (gl::FaceRenderer, the Vulkan seam backend):
/// face f owns vertices 4f .. 4f+3, the faces grouped by `layout`'s classes (in face order
/// within a class), two triangles per face on the CPU renderer's diagonal, (0,1,2) and (0,2,3)
/// — or each reversed, (0,2,1) and (0,3,2), where `reversed` (OpenGL: the shaders' y flip
/// mirrors the winding there). Appends to `indices`; one draw per class with faces, in class
/// order.
std::vector<FaceClassDraw> class_grouped_indices(const PackedFaces& layout, bool reversed,
                                                 std::vector<std::uint32_t>& indices);

/// The quad mesh of a Ptex file's faces from the polygon mesh it was painted on: face f of the
/// result is Ptex face f. A quad of `mesh` is one face; an n-gon (n = 3 or n >= 5) must have
/// been split by the file into n subfaces (FaceInfo::subface) and becomes the n quads of
/// faces::ptex_face_layout. Fails with unsupported naming the polygon ("teapot: polygon 12 has
/// 3 vertices, but Ptex face 12 is not a subface: only quads, and n-gons the Ptex file split
/// into subfaces, are supported") when an n-gon was not split, with size_mismatch when the
/// counts of faces differ or a quad meets a subface, and with unsupported on a triangle-mesh
/// file. `name` prefixes the messages.
Result<QuadMesh> ptex_quad_mesh(const PolygonMesh& mesh, const ptex::PtexFile& file,
                                const std::string& name);

}  // namespace tessera::faces
