// Per-face textures for OpenGL: the shared GPU layout (tessera/faces_gpu.h) uploaded, every
// mip level from the CPU chains, so GL and CPU filter the same texels.
#include <algorithm>
#include <string_view>
#include <utility>

#include "gl/gl_api.h"
#include "tessera/faces.h"
#include "tessera/gl_faces.h"
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

Result<faces::PackedFaces> pack_faces(const faces::FaceTextureSet& set,
                                      const faces::PackLimits& limits) {
  faces::PackLimitNames names;
  names.texture_size = "GL_MAX_TEXTURE_SIZE";
  names.array_layers = "GL_MAX_ARRAY_TEXTURE_LAYERS";
  names.ssbo_bytes = "GL_MAX_SHADER_STORAGE_BLOCK_SIZE";
  return faces::pack_faces(set, limits, names);
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
      GL_UNPACK_ALIGNMENT, GL_UNPACK_ROW_LENGTH,  GL_UNPACK_IMAGE_HEIGHT, GL_UNPACK_SKIP_PIXELS,
      GL_UNPACK_SKIP_ROWS, GL_UNPACK_SKIP_IMAGES, GL_UNPACK_SWAP_BYTES,   GL_UNPACK_LSB_FIRST};
  static constexpr std::array<GLint, 8> kUpload = {4, 0, 0, 0, 0, 0, 0, 0};
  std::array<GLint, 8> saved_{};
  GLint buffer_ = 0;
};

}  // namespace

Result<FaceTextureSet> FaceTextureSet::upload(const faces::FaceTextureSet& set,
                                              const FaceTextureSetOptions& options) {
  if (Status s = check_current_context("FaceTextureSet::upload"); !s.ok()) return s;
  if (Status s = check_errors("FaceTextureSet::upload (errors before it)"); !s.ok()) return s;
  const UnpackStateGuard unpack;
  faces::PackLimits limits;
  GLint v = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &v);
  limits.max_texture_size = v;
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &v);
  limits.max_array_layers = v;
  GLint64 ssbo = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &ssbo);
  limits.max_ssbo_bytes = ssbo;
  Result<faces::PackedFaces> packed = pack_faces(set, limits);
  if (!packed) return packed.status();

  FaceTextureSet out;
  out.layout_ = std::move(*packed);
  const faces::TexelFormat format = options.format;
  const std::uint64_t texel_bytes = faces::texel_bytes(format);
  // Every format but RGBA32F from faces::convert_texels (the driver's own float-to-half
  // conversion rounds differently: Mesa's is not round-to-nearest-even everywhere).
  const bool converted_upload = format != faces::TexelFormat::rgba32f;
  const GLenum upload_type =
      format == faces::TexelFormat::rgba16f ? GL_HALF_FLOAT : GL_UNSIGNED_BYTE;
  const GLenum internal = format == faces::TexelFormat::rgba32f       ? GL_RGBA32F
                          : format == faces::TexelFormat::rgba16f     ? GL_RGBA16F
                          : format == faces::TexelFormat::rgba8_unorm ? GL_RGBA8
                                                                      : GL_SRGB8_ALPHA8;
  std::vector<std::uint8_t> converted;  // faces::convert_texels's bytes
  for (const faces::FaceClass& c : out.layout_.classes) {
    Object tex = create_object(ObjectType::texture, GL_TEXTURE_2D_ARRAY);
    const int layers = int(c.faces.size());
    glTextureStorage3D(tex.get(), c.levels, internal, c.width, c.height, layers);
    const std::string what = "FaceTextureSet::upload: " + std::to_string(layers) + " faces of " +
                             std::to_string(c.width) + "x" + std::to_string(c.height);
    if (Status s = check_errors(what); !s.ok()) return s;
    for (int layer = 0; layer < layers; ++layer) {
      const texture::Texture& t = set.texture(c.faces[std::size_t(layer)]);
      for (int level = 0; level < c.levels; ++level) {
        const texture::TextureLevelView view = t.level(0, level);
        if (converted_upload) {
          const std::size_t texels = std::size_t(view.width) * std::size_t(view.height);
          converted.resize(texels * texel_bytes);
          faces::convert_texels(view.texels, texels, format, converted.data());
          glTextureSubImage3D(tex.get(), level, 0, 0, layer, view.width, view.height, 1, GL_RGBA,
                              upload_type, converted.data());
        } else {
          glTextureSubImage3D(tex.get(), level, 0, 0, layer, view.width, view.height, 1, GL_RGBA,
                              GL_FLOAT, view.texels);
        }
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
                       GLsizeiptr(out.layout_.records.size() * sizeof(faces::FaceRecord)),
                       out.layout_.records.data(), 0);
  if (Status s = check_errors("FaceTextureSet::upload: samplers and face records"); !s.ok()) {
    return s;
  }
  return out;
}

Status FaceTextureSet::bind(const FaceTextureSetBindings& b) const {
  if (Status s = check_current_context("FaceTextureSet::bind"); !s.ok()) return s;
  GLint units = 0, ssbo_bindings = 0;
  glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &units);
  glGetIntegerv(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &ssbo_bindings);
  const int classes = class_count();
  const int clamp_unit = b.clamp_unit >= 0 ? b.clamp_unit : b.border_unit + classes;
  auto range = [](int first, int n) {
    return std::to_string(first) + ".." + std::to_string(first + n - 1);
  };
  auto fail = [](const std::string& msg) {
    return Status::error(ErrorCode::invalid_argument, "FaceTextureSet::bind: " + msg);
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
    return fail(
        "records_binding " + std::to_string(b.records_binding) +
        " exceeds GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS = " + std::to_string(ssbo_bindings));
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
  return check_errors("FaceTextureSet::bind");
}

Status FaceTextureSet::bind(int first_unit, int ssbo_binding, bool clamp_units) const {
  FaceTextureSetBindings b;
  b.border_unit = first_unit;
  b.records_binding = ssbo_binding;
  b.clamp = clamp_units;
  return bind(b);
}

std::vector<std::string> FaceTextureSet::glsl_defines(const FaceTextureSetBindings& b) const {
  const int clamp_unit = b.clamp_unit >= 0 ? b.clamp_unit : b.border_unit + class_count();
  return {"#define TESSERA_SEAMS_CLASSES " + std::to_string(class_count()),
          "#define TESSERA_SEAMS_FIRST_UNIT " + std::to_string(b.border_unit),
          "#define TESSERA_SEAMS_CLAMP_UNIT " + std::to_string(clamp_unit),
          "#define TESSERA_SEAMS_FACES_BINDING " + std::to_string(b.records_binding)};
}

}  // namespace tessera::gl
