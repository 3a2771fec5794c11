// Per-face textures for the GPU: the layout (one texture array per face resolution, one
// std430 record per face mirroring the CPU FaceTextureSet's adjacency and corner links) and
// its upload (every mip level from the CPU chains, so GL and CPU filter the same texels).
#include <algorithm>
#include <map>
#include <string_view>
#include <utility>

#include "core/check.h"
#include "gl/gl_api.h"
#include "tessera/faces.h"
#include "tessera/gl_ptex.h"
#include "tessera/ptex.h"

namespace tessera::gl {

using namespace api;  // NOLINT(google-build-using-namespace): the loaded GL entry points

namespace {
// GL 4.6 core, or ARB/EXT_texture_filter_anisotropic.
bool anisotropy_supported() {
  GLint major = 0, minor = 0, count = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major * 10 + minor >= 46) return true;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i) {
    const auto* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
    if (e == nullptr) continue;
    const std::string_view name(e);
    if (name == "GL_ARB_texture_filter_anisotropic" ||
        name == "GL_EXT_texture_filter_anisotropic") {
      return true;
    }
  }
  return false;
}
}  // namespace

Result<PackedFaces> pack_faces(const faces::FaceTextureSet& set, const PackLimits& limits) {
  const int n = set.face_count();
  if (n == 0) return Status::error(ErrorCode::invalid_argument, "pack_faces: no faces");
  // Classes ordered by (height, width).
  std::map<std::pair<int, int>, int> class_of;
  for (int f = 0; f < n; ++f) {
    const texture::Texture& t = set.texture(f);
    if (limits.max_texture_size > 0 &&
        (t.width() > limits.max_texture_size || t.height() > limits.max_texture_size)) {
      return Status::error(ErrorCode::too_large,
                           "face " + std::to_string(f) + " is " + std::to_string(t.width()) +
                               "x" + std::to_string(t.height()) +
                               ", above GL_MAX_TEXTURE_SIZE = " +
                               std::to_string(limits.max_texture_size));
    }
    class_of.emplace(std::make_pair(t.height(), t.width()), 0);
  }
  PackedFaces p;
  for (auto& [size, index] : class_of) {
    index = int(p.classes.size());
    FaceClass c;
    c.width = size.second;
    c.height = size.first;
    p.classes.push_back(c);
  }
  if (limits.max_classes > 0 && int(p.classes.size()) > limits.max_classes) {
    return Status::error(ErrorCode::too_large,
                         std::to_string(p.classes.size()) +
                             " face resolutions need as many texture arrays, above the limit " +
                             std::to_string(limits.max_classes));
  }
  const std::int64_t bytes = std::int64_t(n) * std::int64_t(sizeof(FaceRecord));
  if (limits.max_ssbo_bytes > 0 && bytes > limits.max_ssbo_bytes) {
    return Status::error(ErrorCode::too_large,
                         std::to_string(n) + " face records (" + std::to_string(bytes) +
                             " bytes) exceed GL_MAX_SHADER_STORAGE_BLOCK_SIZE = " +
                             std::to_string(limits.max_ssbo_bytes));
  }
  p.records.resize(std::size_t(n));
  for (int f = 0; f < n; ++f) {
    const texture::Texture& t = set.texture(f);
    const int cls = class_of.at({t.height(), t.width()});
    FaceClass& c = p.classes[std::size_t(cls)];
    if (c.faces.empty()) {
      c.levels = t.level_count();
    } else if (c.levels != t.level_count()) {
      return Status::error(ErrorCode::invalid_argument,
                           "face " + std::to_string(f) + " has " +
                               std::to_string(t.level_count()) + " mip levels, other " +
                               std::to_string(t.width()) + "x" + std::to_string(t.height()) +
                               " faces " + std::to_string(c.levels));
    }
    FaceRecord& r = p.records[std::size_t(f)];
    r.info = {cls, int(c.faces.size()), t.width(), t.height()};
    c.faces.push_back(f);
    const faces::FaceAdjacency& a = set.adjacency(f);
    for (int e = 0; e < 4; ++e) {
      const std::size_t ei = std::size_t(e);
      if (a.face[ei] < 0) continue;
      r.neighbour[ei] = a.face[ei];
      r.mapping[ei] = e * 4 + a.edge[ei];
    }
    // Corner c: across my edge c into face f1 (entered by its edge e1), then across f1's next
    // edge (e1 + 1) & 3 — the walk faces::corner_links composes.
    for (int c4 = 0; c4 < 4; ++c4) {
      const faces::CornerLink& link = set.corner(f, c4);
      if (link.face < 0) continue;
      const int f1 = a.face[std::size_t(c4)];
      const int e1 = a.edge[std::size_t(c4)];
      const int out1 = (e1 + 1) & 3;
      const int e2 = set.adjacency(f1).edge[std::size_t(out1)];
      r.corner[std::size_t(c4)] = link.face;
      r.corner_mapping[std::size_t(c4)] = (c4 * 4 + e1) * 16 + out1 * 4 + e2;
    }
    // The record as seams.glsl reads it: a class and layer that exist, neighbours that are
    // faces, mappings into the 16 edge transforms (corners: two of them).
    TESSERA_DCHECK(r.info[0] >= 0 && r.info[0] < int(p.classes.size()) && r.info[1] >= 0);
    for (std::size_t e = 0; e < 4; ++e) {
      TESSERA_DCHECK(r.neighbour[e] < n && (r.neighbour[e] < 0) == (r.mapping[e] < 0));
      TESSERA_DCHECK(r.mapping[e] < 16 && r.corner[e] < n && r.corner_mapping[e] < 256);
    }
  }
  for (const FaceClass& c : p.classes) {
    if (limits.max_array_layers > 0 && int(c.faces.size()) > limits.max_array_layers) {
      return Status::error(ErrorCode::too_large,
                           std::to_string(c.faces.size()) + " faces of " +
                               std::to_string(c.width) + "x" + std::to_string(c.height) +
                               " exceed GL_MAX_ARRAY_TEXTURE_LAYERS = " +
                               std::to_string(limits.max_array_layers));
    }
  }
  return p;
}

namespace {

// The pixel-unpack state an upload needs (tight rows, no unpack buffer), set for the upload and
// put back afterwards: the engine's own settings survive it.
class UnpackStateGuard {
 public:
  UnpackStateGuard() {
    for (std::size_t i = 0; i < kNames.size(); ++i) glGetIntegerv(kNames[i], &saved_[i]);
    glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &buffer_);
    for (std::size_t i = 0; i < kNames.size(); ++i) glPixelStorei(kNames[i], kUpload[i]);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  }
  ~UnpackStateGuard() {
    for (std::size_t i = 0; i < kNames.size(); ++i) glPixelStorei(kNames[i], saved_[i]);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, GLuint(buffer_));
  }
  UnpackStateGuard(const UnpackStateGuard&) = delete;
  UnpackStateGuard& operator=(const UnpackStateGuard&) = delete;

 private:
  static constexpr std::array<GLenum, 8> kNames = {
      GL_UNPACK_ALIGNMENT,   GL_UNPACK_ROW_LENGTH,  GL_UNPACK_IMAGE_HEIGHT, GL_UNPACK_SKIP_PIXELS,
      GL_UNPACK_SKIP_ROWS,   GL_UNPACK_SKIP_IMAGES, GL_UNPACK_SWAP_BYTES,   GL_UNPACK_LSB_FIRST};
  static constexpr std::array<GLint, 8> kUpload = {4, 0, 0, 0, 0, 0, 0, 0};
  std::array<GLint, 8> saved_{};
  GLint buffer_ = 0;
};

}  // namespace

Result<FaceTextures> FaceTextures::upload(const faces::FaceTextureSet& set,
                                          const FaceTexturesOptions& options) {
  if (Status s = check_current_context("FaceTextures::upload"); !s.ok()) return s;
  if (Status s = check_errors("FaceTextures::upload (errors before it)"); !s.ok()) return s;
  const UnpackStateGuard unpack;
  PackLimits limits;
  GLint v = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &v);
  limits.max_texture_size = v;
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &v);
  limits.max_array_layers = v;
  GLint64 ssbo = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &ssbo);
  limits.max_ssbo_bytes = ssbo;
  Result<PackedFaces> packed = pack_faces(set, limits);
  if (!packed) return packed.status();

  FaceTextures out;
  out.layout_ = std::move(*packed);
  const bool half = options.format == TexelFormat::rgba16f;
  const std::uint64_t texel_bytes = half ? 8 : 16;
  for (const FaceClass& c : out.layout_.classes) {
    Object tex = create_object(ObjectType::texture, GL_TEXTURE_2D_ARRAY);
    const int layers = int(c.faces.size());
    glTextureStorage3D(tex.get(), c.levels, half ? GL_RGBA16F : GL_RGBA32F, c.width, c.height,
                       layers);
    const std::string what = "FaceTextures::upload: " + std::to_string(layers) + " faces of " +
                             std::to_string(c.width) + "x" + std::to_string(c.height);
    if (Status s = check_errors(what); !s.ok()) return s;
    for (int layer = 0; layer < layers; ++layer) {
      const texture::Texture& t = set.texture(c.faces[std::size_t(layer)]);
      for (int level = 0; level < c.levels; ++level) {
        const texture::TextureLevelView view = t.level(0, level);
        glTextureSubImage3D(tex.get(), level, 0, 0, layer, view.width, view.height, 1, GL_RGBA,
                            GL_FLOAT, view.texels);
        if (layer == 0) {
          out.texture_bytes_ += std::uint64_t(view.width) * std::uint64_t(view.height) *
                                std::uint64_t(layers) * texel_bytes;
        }
      }
    }
    if (Status s = check_errors(what); !s.ok()) return s;
    out.arrays_.push_back(std::move(tex));
  }
  GLfloat max_aniso = 1.0f;
  if (anisotropy_supported()) glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY, &max_aniso);
  const float aniso = std::clamp(options.max_anisotropy, 1.0f, std::max(1.0f, max_aniso));
  const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  for (Object* s : {&out.border_sampler_, &out.clamp_sampler_}) {
    *s = create_object(ObjectType::sampler);
    const GLint wrap = s == &out.border_sampler_ ? GL_CLAMP_TO_BORDER : GL_CLAMP_TO_EDGE;
    glSamplerParameteri(s->get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glSamplerParameteri(s->get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glSamplerParameteri(s->get(), GL_TEXTURE_WRAP_S, wrap);
    glSamplerParameteri(s->get(), GL_TEXTURE_WRAP_T, wrap);
    glSamplerParameterfv(s->get(), GL_TEXTURE_BORDER_COLOR, zero);
    if (max_aniso > 1.0f) glSamplerParameterf(s->get(), GL_TEXTURE_MAX_ANISOTROPY, aniso);
  }
  out.records_ = create_object(ObjectType::buffer);
  glNamedBufferStorage(out.records_.get(),
                       GLsizeiptr(out.layout_.records.size() * sizeof(FaceRecord)),
                       out.layout_.records.data(), 0);
  if (Status s = check_errors("FaceTextures::upload: samplers and face records"); !s.ok()) {
    return s;
  }
  return out;
}

Status FaceTextures::bind(const FaceTexturesBindings& b) const {
  if (Status s = check_current_context("FaceTextures::bind"); !s.ok()) return s;
  GLint units = 0, ssbo_bindings = 0;
  glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &units);
  glGetIntegerv(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &ssbo_bindings);
  const int classes = class_count();
  const int clamp_unit = b.clamp_unit >= 0 ? b.clamp_unit : b.border_unit + classes;
  auto range = [](int first, int n) {
    return std::to_string(first) + ".." + std::to_string(first + n - 1);
  };
  auto fail = [](const std::string& msg) {
    return Status::error(ErrorCode::invalid_argument, "FaceTextures::bind: " + msg);
  };
  if (b.border_unit < 0 || b.clamp_unit < -1 || b.records_binding < 0) {
    return fail("negative binding point (border_unit " + std::to_string(b.border_unit) +
                ", clamp_unit " + std::to_string(b.clamp_unit) + ", records_binding " +
                std::to_string(b.records_binding) + ")");
  }
  const int last = std::max(b.border_unit, b.clamp ? clamp_unit : 0) + classes - 1;
  if (last >= units) {
    return fail(std::to_string(classes) + " face classes need texture units " +
                range(b.border_unit, classes) +
                (b.clamp ? " and " + range(clamp_unit, classes) : std::string()) +
                ", the implementation has " + std::to_string(units));
  }
  if (b.clamp && clamp_unit < b.border_unit + classes && b.border_unit < clamp_unit + classes) {
    return fail("border units " + range(b.border_unit, classes) + " overlap clamp units " +
                range(clamp_unit, classes));
  }
  if (b.records_binding >= ssbo_bindings) {
    return fail("records_binding " + std::to_string(b.records_binding) +
                " exceeds GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS = " +
                std::to_string(ssbo_bindings));
  }
  for (int c = 0; c < classes; ++c) {
    glBindTextureUnit(GLuint(b.border_unit + c), array_texture(c));
    glBindSampler(GLuint(b.border_unit + c), border_sampler());
    if (b.clamp) {
      glBindTextureUnit(GLuint(clamp_unit + c), array_texture(c));
      glBindSampler(GLuint(clamp_unit + c), clamp_sampler());
    }
  }
  // The multi-bind form leaves the generic GL_SHADER_STORAGE_BUFFER binding alone.
  const GLuint buffer = record_buffer();
  glBindBuffersBase(GL_SHADER_STORAGE_BUFFER, GLuint(b.records_binding), 1, &buffer);
  return check_errors("FaceTextures::bind");
}

Status FaceTextures::bind(int first_unit, int ssbo_binding, bool clamp_units) const {
  FaceTexturesBindings b;
  b.border_unit = first_unit;
  b.records_binding = ssbo_binding;
  b.clamp = clamp_units;
  return bind(b);
}

std::vector<std::string> FaceTextures::glsl_defines(const FaceTexturesBindings& b) const {
  const int clamp_unit = b.clamp_unit >= 0 ? b.clamp_unit : b.border_unit + class_count();
  return {"#define TESSERA_SEAMS_CLASSES " + std::to_string(class_count()),
          "#define TESSERA_SEAMS_FIRST_UNIT " + std::to_string(b.border_unit),
          "#define TESSERA_SEAMS_CLAMP_UNIT " + std::to_string(clamp_unit),
          "#define TESSERA_SEAMS_FACES_BINDING " + std::to_string(b.records_binding)};
}

Result<faces::QuadMesh> ptex_quad_mesh(const faces::PolygonMesh& mesh, const ptex::PtexFile& file,
                                       const std::string& name) {
  if (file.mesh_type != ptex::MeshType::quad) {
    return Status::error(ErrorCode::unsupported,
                         name + ": a triangle-mesh Ptex file: only quad-mesh files are supported");
  }
  const int count = file.face_count();
  int next = 0;  // the Ptex face of the polygon's first quad
  for (std::size_t p = 0; p < mesh.faces.size(); ++p) {
    const int n = int(mesh.faces[p].size());
    const int quads = n == 4 ? 1 : n;
    const bool split = n != 4;
    if (next + quads > count) {
      return Status::error(ErrorCode::size_mismatch,
                           name + ": the mesh's polygons make more than the Ptex file's " +
                               std::to_string(count) + " faces (polygon " + std::to_string(p) +
                               ")");
    }
    for (int k = 0; k < quads; ++k) {
      const bool sub = file.faces[std::size_t(next + k)].subface;
      if (split && !sub) {
        return Status::error(
            ErrorCode::unsupported,
            name + ": polygon " + std::to_string(p) + " has " + std::to_string(n) +
                " vertices, but Ptex face " + std::to_string(next + k) +
                " is not a subface: only quads, and n-gons the Ptex file split into subfaces, "
                "are supported");
      }
      if (!split && sub) {
        return Status::error(ErrorCode::size_mismatch,
                             name + ": polygon " + std::to_string(p) +
                                 " is a quad, but Ptex face " + std::to_string(next) +
                                 " is a subface of a split polygon");
      }
    }
    next += quads;
  }
  if (next != count) {
    return Status::error(ErrorCode::size_mismatch,
                         name + ": the mesh's polygons make " + std::to_string(next) +
                             " Ptex faces, the file has " + std::to_string(count));
  }
  return faces::ptex_face_layout(mesh);
}

}  // namespace tessera::gl
