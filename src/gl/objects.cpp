// GL object ownership, timer queries, render targets and read-back into tessera images.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>

#include "gl/gl_api.h"
#include "tessera/gl.h"

namespace tessera::gl {

using namespace api;  // NOLINT(google-build-using-namespace): the loaded GL entry points

// ---- Objects --------------------------------------------------------------------------------

Object& Object::operator=(Object&& o) noexcept {
  if (this != &o) {
    reset();
    type_ = o.type_;
    name_ = o.name_;
    o.name_ = 0;
  }
  return *this;
}

void Object::reset() {
  if (name_ == 0) return;
  // Without the loaded entry points (no context was ever created) there is nothing to delete.
  if (glDeleteBuffers != nullptr) {
    const GLuint n = name_;
    switch (type_) {
      case ObjectType::buffer:
        glDeleteBuffers(1, &n);
        break;
      case ObjectType::texture:
        glDeleteTextures(1, &n);
        break;
      case ObjectType::framebuffer:
        glDeleteFramebuffers(1, &n);
        break;
      case ObjectType::renderbuffer:
        glDeleteRenderbuffers(1, &n);
        break;
      case ObjectType::vertex_array:
        glDeleteVertexArrays(1, &n);
        break;
      case ObjectType::query:
        glDeleteQueries(1, &n);
        break;
      case ObjectType::sampler:
        glDeleteSamplers(1, &n);
        break;
      case ObjectType::program:
        glDeleteProgram(n);
        break;
      case ObjectType::shader:
        glDeleteShader(n);
        break;
    }
  }
  name_ = 0;
}

Object create_object(ObjectType type, std::uint32_t target) {
  GLuint n = 0;
  if (!ensure_loaded()) return Object();  // name 0: the caller's check_errors says why
  switch (type) {
    case ObjectType::buffer:
      glCreateBuffers(1, &n);
      break;
    case ObjectType::texture:
      glCreateTextures(target, 1, &n);
      break;
    case ObjectType::framebuffer:
      glCreateFramebuffers(1, &n);
      break;
    case ObjectType::renderbuffer:
      glCreateRenderbuffers(1, &n);
      break;
    case ObjectType::vertex_array:
      glCreateVertexArrays(1, &n);
      break;
    case ObjectType::query:
      glCreateQueries(target, 1, &n);
      break;
    case ObjectType::sampler:
      glCreateSamplers(1, &n);
      break;
    case ObjectType::program:
      n = glCreateProgram();
      break;
    case ObjectType::shader:
      n = glCreateShader(target);
      break;
  }
  return Object(type, n);
}

// ---- Timer queries --------------------------------------------------------------------------

Status GpuTimer::begin(std::string pass) {
  if (Status s = check_current_context("GpuTimer::begin(" + pass + ")"); !s.ok()) return s;
  if (open_) {
    return Status::error(ErrorCode::invalid_argument,
                         "GpuTimer: pass '" + pass + "' begun while '" + pending_.back().pass +
                             "' is open (GL_TIME_ELAPSED queries cannot nest)");
  }
  Object q = create_object(ObjectType::query, GL_TIME_ELAPSED);
  glBeginQuery(GL_TIME_ELAPSED, q.get());
  pending_.push_back({std::move(pass), std::move(q), std::chrono::steady_clock::now()});
  open_ = true;
  return check_errors("GpuTimer::begin(" + pending_.back().pass + ")");
}

Status GpuTimer::end() {
  if (!open_) return Status::error(ErrorCode::invalid_argument, "GpuTimer: end without begin");
  glEndQuery(GL_TIME_ELAPSED);
  open_ = false;
  return check_errors("GpuTimer::end(" + pending_.back().pass + ")");
}

Result<std::vector<PassTime>> GpuTimer::collect() {
  if (open_) {
    return Status::error(ErrorCode::invalid_argument,
                         "GpuTimer: pass '" + pending_.back().pass + "' is still open");
  }
  std::vector<PassTime> out;
  std::vector<Pending> pending;
  pending.swap(pending_);
  for (const Pending& p : pending) {
    GLuint64 ns = 0;
    glGetQueryObjectui64v(p.query.get(), GL_QUERY_RESULT, &ns);  // waits for the result
    const double ms = double(ns) * 1e-6;
    // The GPU cannot have worked on the pass before begin() or after the result arrived.
    const double wall_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - p.begun)
            .count();
    if (ms > wall_ms + 1.0) {
      return Status::error(ErrorCode::unsupported,
                           "GpuTimer: pass '" + p.pass + "' reports " + std::to_string(ms) +
                               " ms, more than the " + std::to_string(wall_ms) +
                               " ms since it began (driver timer query bug)");
    }
    PassTime t;
    t.pass = p.pass;
    t.gpu_ms = ms;
    out.push_back(std::move(t));
  }
  if (Status s = check_errors("GpuTimer::collect"); !s.ok()) return s;
  return out;
}

// ---- Render targets -------------------------------------------------------------------------

Result<RenderTarget> create_render_target(const RenderTargetOptions& o) {
  const std::string what = "render target " + std::to_string(o.width) + "x" +
                           std::to_string(o.height) + " " +
                           (o.colour == ColourFormat::rgba8 ? "RGBA8" : "RGBA32F") + " with " +
                           std::to_string(o.samples) + " sample" + (o.samples == 1 ? "" : "s");
  if (Status s = check_current_context(what); !s.ok()) return s;
  GLint max_size = 0, max_samples = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  if (o.width < 1 || o.height < 1 || o.width > max_size || o.height > max_size) {
    return Status::error(ErrorCode::invalid_argument,
                         what + ": size outside 1.." + std::to_string(max_size));
  }
  if (o.samples < 1 || o.samples > std::max(1, max_samples)) {
    return Status::error(ErrorCode::unsupported, what + ": the implementation supports at most " +
                                                     std::to_string(max_samples) +
                                                     " samples (GL_MAX_SAMPLES)");
  }
  RenderTarget t;
  t.width = o.width;
  t.height = o.height;
  t.samples = o.samples;
  const GLsizei samples = o.samples > 1 ? o.samples : 0;
  t.framebuffer = create_object(ObjectType::framebuffer);
  t.colour = create_object(ObjectType::renderbuffer);
  glNamedRenderbufferStorageMultisample(t.colour.get(), samples,
                                        o.colour == ColourFormat::rgba8 ? GL_RGBA8 : GL_RGBA32F,
                                        o.width, o.height);
  glNamedFramebufferRenderbuffer(t.framebuffer.get(), GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                 t.colour.get());
  if (o.depth) {
    t.depth = create_object(ObjectType::renderbuffer);
    glNamedRenderbufferStorageMultisample(t.depth.get(), samples, GL_DEPTH_COMPONENT32F, o.width,
                                          o.height);
    glNamedFramebufferRenderbuffer(t.framebuffer.get(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                   t.depth.get());
  }
  if (Status s = check_errors(what); !s.ok()) return s;
  const GLenum status = glCheckNamedFramebufferStatus(t.framebuffer.get(), GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%04X", unsigned(status));
    return Status::error(ErrorCode::unsupported,
                         what + ": framebuffer incomplete (status " + buf + ")");
  }
  return t;
}

// ---- Read-back ------------------------------------------------------------------------------

namespace {

template <class Image, class T>
Result<Image> read_framebuffer(std::uint32_t framebuffer, int attachment, int width, int height,
                               GLenum type, const char* what) {
  if (framebuffer == 0 || attachment < 0 || attachment > 7 || width < 1 || height < 1) {
    return Status::error(ErrorCode::invalid_argument,
                         std::string(what) + ": needs a framebuffer, attachment 0..7 and a size");
  }
  if (Status s = check_errors(std::string(what) + " (errors before it)"); !s.ok()) return s;
  GLint previous = 0;
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous);
  glNamedFramebufferReadBuffer(framebuffer, GL_COLOR_ATTACHMENT0 + GLenum(attachment));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  std::vector<T> px(std::size_t(width) * std::size_t(height) * 4);
  glReadPixels(0, 0, width, height, GL_RGBA, type, px.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(previous));
  if (Status s = check_errors(what); !s.ok()) return s;
  Image img(width, height);
  const std::size_t row = std::size_t(width) * 4;
  for (int y = 0; y < height; ++y) {  // GL rows go up; tessera images go down
    std::memcpy(img.at(0, y), &px[std::size_t(height - 1 - y) * row], row * sizeof(T));
  }
  return img;
}

template <class Image, class T>
Result<Image> read_texture(std::uint32_t texture, int level, int layer, GLenum type,
                           const char* what) {
  if (Status s = check_errors(std::string(what) + " (errors before it)"); !s.ok()) return s;
  GLint target = 0, w = 0, h = 0, depth = 0;
  glGetTextureParameteriv(texture, GL_TEXTURE_TARGET, &target);
  glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_WIDTH, &w);
  glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_HEIGHT, &h);
  glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_DEPTH, &depth);
  if (Status s = check_errors(what); !s.ok()) return s;
  if (target != GL_TEXTURE_2D && target != GL_TEXTURE_2D_ARRAY) {
    return Status::error(ErrorCode::unsupported,
                         std::string(what) + ": only 2D textures and 2D arrays are supported");
  }
  if (w < 1 || h < 1) {
    return Status::error(ErrorCode::invalid_argument, std::string(what) + ": texture level " +
                                                          std::to_string(level) + " is empty");
  }
  const int layers = target == GL_TEXTURE_2D_ARRAY ? depth : 1;
  if (layer < 0 || layer >= layers) {
    return Status::error(ErrorCode::invalid_argument, std::string(what) + ": layer " +
                                                          std::to_string(layer) + " outside 0.." +
                                                          std::to_string(layers - 1));
  }
  Image img(w, h);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureSubImage(texture, level, 0, 0, layer, w, h, 1, GL_RGBA, type,
                       GLsizei(img.pixels.size() * sizeof(T)), img.pixels.data());
  if (Status s = check_errors(what); !s.ok()) return s;
  return img;
}

}  // namespace

Result<ImageRGBAF> read_framebuffer_rgbaf(std::uint32_t framebuffer, int attachment, int width,
                                          int height) {
  return read_framebuffer<ImageRGBAF, float>(framebuffer, attachment, width, height, GL_FLOAT,
                                             "read_framebuffer_rgbaf");
}

Result<ImageRGBA8> read_framebuffer_rgba8(std::uint32_t framebuffer, int attachment, int width,
                                          int height) {
  Result<ImageRGBA8> r = read_framebuffer<ImageRGBA8, std::uint8_t>(
      framebuffer, attachment, width, height, GL_UNSIGNED_BYTE, "read_framebuffer_rgba8");
  if (r) r->has_alpha = true;
  return r;
}

Result<ImageRGBAF> read_texture_rgbaf(std::uint32_t texture, int level, int layer) {
  return read_texture<ImageRGBAF, float>(texture, level, layer, GL_FLOAT, "read_texture_rgbaf");
}

Result<ImageRGBA8> read_texture_rgba8(std::uint32_t texture, int level, int layer) {
  Result<ImageRGBA8> r = read_texture<ImageRGBA8, std::uint8_t>(
      texture, level, layer, GL_UNSIGNED_BYTE, "read_texture_rgba8");
  if (r) r->has_alpha = true;
  return r;
}

}  // namespace tessera::gl
