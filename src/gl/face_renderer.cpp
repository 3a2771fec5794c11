// The seams experiment on the GPU (tessera/gl_face_renderer.h): class-grouped draws of a per-face-
// textured quad mesh through seams_render.{vert,frag}, a multisampled RGBA32F target, the box
// resolve (glBlitFramebuffer, linear light), GL_TIME_ELAPSED per pass and read-back.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <map>
#include <span>
#include <string>
#include <system_error>
#include <vector>

#include "gl/gl_api.h"
#include "tessera/gl_face_renderer.h"
#include "tessera/glsl.h"
#include "tessera/raster.h"

namespace tessera::gl {

using namespace api;  // NOLINT(google-build-using-namespace)

struct FaceRenderer::State {
  const faces::FaceScene* scene = nullptr;
  const faces::FaceTextureSet* set = nullptr;
  FaceTextureSet textures;
  std::filesystem::path glsl_dir;
  Object vao, clip_buffer, normal_buffer, index_buffer;
  std::vector<float> clip;                   // 4 floats per vertex, 4 vertices per face
  std::vector<faces::FaceClassDraw> ranges;  // one draw per face class
  std::map<int, Program> programs;
  std::map<int, bool> msaa_ok;
  std::map<int, SamplePattern> patterns;  // by requested rate
  RenderTarget target, resolved;  // target: drawn (multisampled or not); resolved: MSAA only
  float max_anisotropy = 1.0f;

  Result<const Program*> program(const FaceFrameOptions& o);
  Status ensure_targets(int width, int height, int samples);
};

Result<const Program*> FaceRenderer::State::program(const FaceFrameOptions& o) {
  const int method = int(o.method);
  const int fallback = o.method == faces::SeamMethod::discard ? int(o.clamp_fallback) : 1;
  const int output = int(o.output);
  const int key = method * 4 + fallback * 2 + output;
  if (auto it = programs.find(key); it != programs.end()) return &it->second;
  Result<glsl::Source> vs =
      glsl::shipped_shader(glsl::Stage::vertex, "seams_render.vert", glsl_dir);
  if (!vs) return vs.status();
  Result<glsl::Source> fs =
      glsl::shipped_shader(glsl::Stage::fragment, "seams_render.frag", glsl_dir);
  if (!fs) return fs.status();
  glsl::ExpandOptions so;
  so.shipped_dir = glsl_dir;
  so.preamble = {"#define TESSERA_SEAMS_CLASSES " + std::to_string(textures.class_count()),
                 "#define TESSERA_RENDER_METHOD " + std::to_string(method),
                 "#define TESSERA_RENDER_FALLBACK " + std::to_string(fallback),
                 "#define TESSERA_RENDER_OUTPUT " + std::to_string(output)};
  Result<Program> p = link_program({*vs, *fs}, so);
  if (!p) return p.status();
  return &programs.emplace(key, std::move(*p)).first->second;
}

Status FaceRenderer::State::ensure_targets(int width, int height, int samples) {
  if (target.framebuffer && target.width == width && target.height == height &&
      target.samples == samples) {
    return Status::success();
  }
  target = {};
  resolved = {};
  RenderTargetOptions to;
  to.width = width;
  to.height = height;
  to.samples = samples;
  to.colour = ColourFormat::rgba32f;
  to.depth = true;
  Result<RenderTarget> t = create_render_target(to);
  if (!t) return t.status();
  target = std::move(*t);
  if (samples > 1) {
    to.samples = 1;
    to.depth = false;
    Result<RenderTarget> r = create_render_target(to);
    if (!r) return r.status();
    resolved = std::move(*r);
  }
  return Status::success();
}

FaceRenderer::~FaceRenderer() = default;

const FaceTextureSet& FaceRenderer::textures() const { return state_->textures; }
const std::filesystem::path& FaceRenderer::glsl_dir() const { return state_->glsl_dir; }

Result<std::unique_ptr<FaceRenderer>> FaceRenderer::create(const faces::FaceScene& scene,
                                                           const faces::FaceTextureSet& set,
                                                           const FaceRendererOptions& options) {
  const faces::QuadMesh& m = scene.mesh;
  if (m.face_count() != set.face_count()) {
    return Status::error(ErrorCode::size_mismatch,
                         scene.name + ": " + std::to_string(m.face_count()) + " faces but " +
                             std::to_string(set.face_count()) + " face textures");
  }
  std::unique_ptr<FaceRenderer> r(new FaceRenderer());
  r->state_ = std::make_unique<State>();
  State& s = *r->state_;
  s.scene = &scene;
  s.set = &set;
  s.glsl_dir = options.glsl_dir;
  FaceTextureSetOptions fo;
  fo.format = options.texels;
  fo.max_anisotropy = 16.0f;
  Result<FaceTextureSet> tex = FaceTextureSet::upload(set, fo);
  if (!tex) return tex.status();
  s.textures = std::move(*tex);
  GLint units = 0;
  glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &units);
  const int classes = s.textures.class_count();
  if (classes > 16 || 2 * classes > units) {
    return Status::error(ErrorCode::unsupported,
                         scene.name + ": " + std::to_string(classes) + " face classes need " +
                             std::to_string(2 * classes) +
                             " fragment texture units (seams.glsl: at most 16 classes; "
                             "GL_MAX_TEXTURE_IMAGE_UNITS = " +
                             std::to_string(units) + ")");
  }
  glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY, &s.max_anisotropy);
  s.max_anisotropy = std::max(1.0f, s.max_anisotropy);

  // Smooth normals exactly as faces::FaceRenderer (faces::smooth_face_normals).
  std::vector<float> vertex_normals;
  vertex_normals.reserve(std::size_t(m.face_count()) * 4 * 3);
  for (const Vec3& n : faces::smooth_face_normals(m)) {
    vertex_normals.insert(vertex_normals.end(), {n.x, n.y, n.z});
  }
  // Indices grouped by class; each triangle reversed (the vertex shader's y flip mirrors the
  // winding), same diagonal as the CPU: (0, 2, 1) and (0, 3, 2) for the CPU's (0,1,2), (0,2,3).
  std::vector<std::uint32_t> indices;
  indices.reserve(std::size_t(m.face_count()) * 6);
  s.ranges = faces::class_grouped_indices(s.textures.layout(), true, indices);
  s.clip.assign(std::size_t(m.face_count()) * 4 * 4, 0.0f);
  s.vao = create_object(ObjectType::vertex_array);
  s.clip_buffer = create_object(ObjectType::buffer);
  s.normal_buffer = create_object(ObjectType::buffer);
  s.index_buffer = create_object(ObjectType::buffer);
  glNamedBufferData(s.clip_buffer.get(), GLsizeiptr(s.clip.size() * 4), nullptr, GL_STREAM_DRAW);
  glNamedBufferData(s.normal_buffer.get(), GLsizeiptr(vertex_normals.size() * 4),
                    vertex_normals.data(), GL_STATIC_DRAW);
  glNamedBufferData(s.index_buffer.get(), GLsizeiptr(indices.size() * 4), indices.data(),
                    GL_STATIC_DRAW);
  glBindVertexArray(s.vao.get());
  glBindBuffer(GL_ARRAY_BUFFER, s.clip_buffer.get());
  glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 16, nullptr);
  glEnableVertexAttribArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, s.normal_buffer.get());
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 12, nullptr);
  glEnableVertexAttribArray(1);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, s.index_buffer.get());
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  if (Status st = check_errors("face renderer: mesh upload"); !st.ok()) return st;
  return r;
}

bool FaceRenderer::msaa_supported(int samples) {
  if (samples < 1) return false;
  if (samples == 1) return true;
  if (auto it = state_->msaa_ok.find(samples); it != state_->msaa_ok.end()) return it->second;
  RenderTargetOptions to;
  to.width = to.height = 8;
  to.samples = samples;
  const bool ok = create_render_target(to).ok();
  (void)check_errors("msaa probe");  // a refused rate may leave a GL error behind
  state_->msaa_ok[samples] = ok;
  return ok;
}

Result<SamplePattern> FaceRenderer::sample_pattern(int msaa) {
  if (msaa < 1) {
    return Status::error(ErrorCode::invalid_argument,
                         "face renderer: MSAA " + std::to_string(msaa) + " is below 1");
  }
  if (auto it = state_->patterns.find(msaa); it != state_->patterns.end()) return it->second;
  if (!msaa_supported(msaa)) {
    return Status::error(
        ErrorCode::unsupported,
        "face renderer: the driver refuses " + std::to_string(msaa) + "x MSAA for RGBA32F + depth");
  }
  SamplePattern p;
  p.requested = msaa;
  if (msaa == 1) {
    p.positions = {SamplePosition{}};  // the pixel centre (no sample buffers to query)
  } else {
    // A target like `render`'s: what the driver allocates depends on the formats.
    RenderTargetOptions to;
    to.width = to.height = 8;
    to.samples = msaa;
    to.colour = ColourFormat::rgba32f;
    to.depth = true;
    Result<RenderTarget> t = create_render_target(to);
    if (!t) return t.status();
    GLint previous = 0, samples = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, t->framebuffer.get());
    glGetIntegerv(GL_SAMPLES, &samples);
    for (GLint i = 0; i < samples; ++i) {
      GLfloat xy[2] = {0.5f, 0.5f};
      glGetMultisamplefv(GL_SAMPLE_POSITION, GLuint(i), xy);
      // Window y runs with the image rows (the vertex shader's flip): y down in the image.
      p.positions.push_back(SamplePosition{xy[0] - 0.5f, xy[1] - 0.5f});
    }
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(previous));
    if (Status st = check_errors("face renderer: sample positions"); !st.ok()) return st;
    if (samples < msaa) {
      return Status::error(ErrorCode::unsupported, "face renderer: the driver gave " +
                                                       std::to_string(samples) + " samples for " +
                                                       std::to_string(msaa) + "x MSAA");
    }
    p.samples = int(samples);
  }
  p.cpu_msaa = matching_cpu_msaa(p.positions);
  return state_->patterns.emplace(msaa, std::move(p)).first->second;
}

int matching_cpu_msaa(const std::vector<SamplePosition>& positions) {
  for (int n : {1, 2, 4, 8, 16}) {
    const std::span<const raster::SampleOffset> table = raster::sample_positions(n);
    if (table.size() != positions.size()) continue;
    std::vector<bool> used(positions.size(), false);
    bool all = true;
    for (const raster::SampleOffset& t : table) {
      bool found = false;
      for (std::size_t i = 0; i < positions.size() && !found; ++i) {
        if (!used[i] && std::abs(positions[i].x - float(t.x) / 16.0f) < 1e-4f &&
            std::abs(positions[i].y - float(t.y) / 16.0f) < 1e-4f) {
          used[i] = found = true;
        }
      }
      all = all && found;
    }
    if (all) return n;
  }
  return 0;
}

std::vector<raster::SampleOffset> cpu_sample_offsets(const std::vector<SamplePosition>& positions) {
  if (positions.empty() || positions.size() > std::size_t(raster::kMaxSamples)) return {};
  std::vector<raster::SampleOffset> out;
  out.reserve(positions.size());
  // Within 1e-3 pixel of the 1/16 grid: a driver's float positions of grid points are exact
  // or nearly so, while a finer pattern (e.g. 1/256) is not on the grid and cannot be drawn.
  const auto to_grid = [](float v, int& out_v) {
    const double sixteenths = double(v) * 16.0;
    const double k = std::round(sixteenths);
    if (!(std::abs(sixteenths - k) <= 16.0 * 1e-3) || k < -8.0 || k > 7.0) return false;
    out_v = int(k);
    return true;
  };
  for (const SamplePosition& p : positions) {
    raster::SampleOffset o;
    if (!to_grid(p.x, o.x) || !to_grid(p.y, o.y)) return {};
    out.push_back(o);
  }
  return out;
}

std::vector<int> FaceRenderer::refused_msaa(const std::vector<int>& rates) {
  std::vector<int> out;
  for (int r : rates) {
    if (!msaa_supported(r)) out.push_back(r);
  }
  return out;
}

Result<FaceFrame> FaceRenderer::render(const scene::Camera& camera, const FaceFrameOptions& o) {
  State& s = *state_;
  if (o.width < 1 || o.height < 1 || o.width > 16384 || o.height > 16384) {
    return Status::error(ErrorCode::invalid_argument, "face renderer: bad frame size");
  }
  if (o.msaa != 1 && o.msaa != 2 && o.msaa != 4 && o.msaa != 8 && o.msaa != 16) {
    return Status::error(ErrorCode::invalid_argument,
                         "face renderer: MSAA " + std::to_string(o.msaa) + " not in 1,2,4,8,16");
  }
  if (o.filter != texture::TextureFilter::trilinear &&
      o.filter != texture::TextureFilter::anisotropic) {
    return Status::error(ErrorCode::invalid_argument,
                         "face renderer: the filter must be trilinear or anisotropic");
  }
  if (!msaa_supported(o.msaa)) {
    return Status::error(ErrorCode::unsupported, "face renderer: the driver refuses " +
                                                     std::to_string(o.msaa) +
                                                     "x MSAA for RGBA32F + depth");
  }
  Result<SamplePattern> pattern = sample_pattern(o.msaa);
  if (!pattern) return pattern.status();
  Result<const Program*> prog = s.program(o);
  if (!prog) return prog.status();
  if (Status st = s.ensure_targets(o.width, o.height, o.msaa); !st.ok()) return st;

  FaceFrame frame;
  frame.samples = pattern->samples;
  const auto t0 = std::chrono::steady_clock::now();
  // Clip-space positions with the CPU renderer's arithmetic (faces::FaceRenderer::render).
  faces::face_clip_positions(s.scene->mesh, camera, faces::frame_window(o), s.clip);
  glNamedBufferData(s.clip_buffer.get(), GLsizeiptr(s.clip.size() * 4), s.clip.data(),
                    GL_STREAM_DRAW);

  const float aniso = o.filter == texture::TextureFilter::anisotropic
                          ? std::clamp(float(o.max_aniso), 1.0f, s.max_anisotropy)
                          : 1.0f;
  glSamplerParameterf(s.textures.border_sampler(), GL_TEXTURE_MAX_ANISOTROPY, aniso);
  glSamplerParameterf(s.textures.clamp_sampler(), GL_TEXTURE_MAX_ANISOTROPY, aniso);
  if (Status st = s.textures.bind(0, 0, true); !st.ok()) return st;

  const Program& p = **prog;
  const int class_loc = p.uniform("tessera_render_class");
  glUseProgram(p.get());
  glBindVertexArray(s.vao.get());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, s.target.framebuffer.get());
  glViewport(0, 0, o.width, o.height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glEnable(GL_MULTISAMPLE);
  if (Status st = check_errors("face renderer: state"); !st.ok()) return st;

  const bool flags = o.output == SeamsOutput::zero_coverage;  // background 0: nothing flagged
  const float background[4] = {flags ? 0.0f : faces::kFaceBackground[0],
                               flags ? 0.0f : faces::kFaceBackground[1],
                               flags ? 0.0f : faces::kFaceBackground[2], 0.0f};
  const float far_depth = 1.0f;
  glClearNamedFramebufferfv(s.target.framebuffer.get(), GL_COLOR, 0, background);
  glClearNamedFramebufferfv(s.target.framebuffer.get(), GL_DEPTH, 0, &far_depth);
  // The draw pass begins after the clears: Mesa 22.3 llvmpipe loses the start of a
  // GL_TIME_ELAPSED query begun before a clear that opens a frame (it then reports an
  // absolute timestamp); llvmpipe defers full clears into the first binned command anyway.
  GpuTimer timer;
  if (Status st = timer.begin("draw"); !st.ok()) return st;
  for (const faces::FaceClassDraw& r : s.ranges) {
    glProgramUniform1i(p.get(), class_loc, r.cls);
    glDrawElements(GL_TRIANGLES, GLsizei(r.count), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(r.first * sizeof(std::uint32_t)));
    ++frame.draw_calls;
  }
  if (Status st = timer.end(); !st.ok()) return st;
  std::uint32_t read_fb = s.target.framebuffer.get();
  if (o.msaa > 1) {
    if (Status st = timer.begin("resolve"); !st.ok()) return st;
    glBlitNamedFramebuffer(s.target.framebuffer.get(), s.resolved.framebuffer.get(), 0, 0, o.width,
                           o.height, 0, 0, o.width, o.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    if (Status st = timer.end(); !st.ok()) return st;
    read_fb = s.resolved.framebuffer.get();
  }
  glFinish();
  frame.wall_ms = ms_since(t0);
  glBindVertexArray(0);
  glUseProgram(0);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  if (Status st = check_errors("face renderer: draw"); !st.ok()) return st;
  Result<std::vector<PassTime>> times = timer.collect();
  if (!times) return times.status();
  for (const PassTime& t : *times) {
    (t.pass == "draw" ? frame.gpu_ms_draw : frame.gpu_ms_resolve) += t.gpu_ms;
  }

  if (o.read_back) {
    // Row 0 of the framebuffer is the image's top row (the vertex shader's y flip).
    frame.image = ImageRGBAF(o.width, o.height);
    GLint previous = 0;
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous);
    glNamedFramebufferReadBuffer(read_fb, GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, read_fb);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, o.width, o.height, GL_RGBA, GL_FLOAT, frame.image.pixels.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(previous));
    if (Status st = check_errors("face renderer: read-back"); !st.ok()) return st;
  }
  return frame;
}

Result<ImageRGBAF> FaceRenderer::render_reference(const scene::Camera& camera, int width,
                                                  int height,
                                                  const faces::ReferenceOptions& options) {
  return faces::render_reference_with<FaceFrameOptions>(*this, camera, width, height, options);
}

}  // namespace tessera::gl
