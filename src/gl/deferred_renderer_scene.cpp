// DeferredRenderer: scene upload (the CPU's texture chains as RGBA32F arrays, meshes), the
// size check against the framebuffer limits, the geometry pass into the enlarged G-buffer, and
// its read-back into the CPU layout.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <tuple>

#include "gl/deferred_renderer_internal.h"
#include "gl/gl_api.h"
#include "tessera/glsl.h"
#include "tessera/render.h"

namespace tessera::gl {

using namespace api;

namespace {

/// The base-colour textures' size classes (deferred::gpu_texture_classes), one RGBA32F array
/// per class into `arrays` (a 1x1 dummy when there is none, so that unit 3 holds a complete
/// array).
void upload_texture_classes(const deferred::GpuTextureClasses& classes,
                            const std::vector<texture::Texture>& textures,
                            std::vector<Object>& arrays) {
  for (const deferred::GpuTextureClasses::Class& c : classes.classes) {
    Object arr = create_object(ObjectType::texture, GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(arr.get(), c.levels, GL_RGBA32F, c.width, c.height,
                       GLsizei(c.textures.size()));
    for (std::size_t layer = 0; layer < c.textures.size(); ++layer) {
      const texture::Texture& tex = textures[std::size_t(c.textures[layer])];
      for (int l = 0; l < c.levels; ++l) {
        const texture::TextureLevelView v = tex.level(0, l);
        glTextureSubImage3D(arr.get(), l, 0, 0, GLint(layer), v.width, v.height, 1, GL_RGBA,
                            GL_FLOAT, v.texels);
      }
    }
    glTextureParameteri(arr.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(arr.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(arr.get(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(arr.get(), GL_TEXTURE_WRAP_T, GL_REPEAT);
    arrays.push_back(std::move(arr));
  }
  if (arrays.empty()) {  // a 1x1 dummy so that unit 3 holds a complete array
    Object arr = create_object(ObjectType::texture, GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(arr.get(), 1, GL_RGBA32F, 1, 1, 1);
    const float one[4] = {1, 1, 1, 1};
    glTextureSubImage3D(arr.get(), 0, 0, 0, 0, 1, 1, 1, GL_RGBA, GL_FLOAT, one);
    arrays.push_back(std::move(arr));
  }
}

/// The materials as an SSBO (deferred::gpu_materials).
Object upload_materials(const std::vector<deferred::GpuMaterial>& mats) {
  Object ssbo = create_object(ObjectType::buffer);
  glNamedBufferStorage(ssbo.get(), GLsizeiptr(mats.size() * sizeof(deferred::GpuMaterial)),
                       mats.data(), 0);
  return ssbo;
}

/// Per mesh: a dynamic buffer (clip xyzw, linear depth) per frame, a static one (normal, uv).
void upload_meshes(const std::vector<scene::Mesh>& scene_meshes, std::vector<GlMesh>& meshes) {
  for (const scene::Mesh& mesh : scene_meshes) {
    GlMesh g;
    g.vertices = mesh.positions.size();
    g.indices = mesh.indices.size();
    g.material = mesh.material;
    g.vao = create_object(ObjectType::vertex_array);
    g.dynamic_vbo = create_object(ObjectType::buffer);
    g.static_vbo = create_object(ObjectType::buffer);
    g.ebo = create_object(ObjectType::buffer);
    const std::vector<float> st_data = deferred::gpu_static_vertices(mesh);
    glNamedBufferStorage(g.static_vbo.get(),
                         GLsizeiptr(std::max<std::size_t>(1, st_data.size()) * sizeof(float)),
                         st_data.empty() ? nullptr : st_data.data(), 0);
    glNamedBufferStorage(g.ebo.get(),
                         GLsizeiptr(std::max<std::size_t>(1, g.indices) * sizeof(std::uint32_t)),
                         mesh.indices.empty() ? nullptr : mesh.indices.data(), 0);
    glBindVertexArray(g.vao.get());
    glBindBuffer(GL_ARRAY_BUFFER, g.dynamic_vbo.get());
    glNamedBufferData(g.dynamic_vbo.get(), GLsizeiptr(std::max<std::size_t>(1, g.vertices) * 20),
                      nullptr, GL_STREAM_DRAW);
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 20, reinterpret_cast<const void*>(0));
    glVertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, 20, reinterpret_cast<const void*>(16));
    glBindBuffer(GL_ARRAY_BUFFER, g.static_vbo.get());
    glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, 20, reinterpret_cast<const void*>(0));
    glVertexAttribPointer(3, 2, GL_FLOAT, GL_FALSE, 20, reinterpret_cast<const void*>(12));
    for (GLuint a = 0; a < 4; ++a) glEnableVertexAttribArray(a);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.ebo.get());
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    meshes.push_back(std::move(g));
  }
}

}  // namespace

DeferredRenderer::~DeferredRenderer() = default;

const std::filesystem::path& DeferredRenderer::glsl_dir() const { return state_->options.glsl_dir; }
double DeferredRenderer::last_gbuffer_ms() const { return state_->gbuffer_ms; }
double DeferredRenderer::last_gbuffer_wall_ms() const { return state_->gbuffer_wall_ms; }
int DeferredRenderer::width() const { return state_->w; }
int DeferredRenderer::height() const { return state_->h; }
int DeferredRenderer::m() const { return state_->m; }

Result<std::unique_ptr<DeferredRenderer>> DeferredRenderer::create(
    const scene::Scene& scene, const DeferredRendererOptions& options) {
  std::unique_ptr<DeferredRenderer> r(new DeferredRenderer());
  r->state_ = std::make_unique<State>();
  State& st = *r->state_;
  st.scene = &scene;
  st.options = options;

  Result<std::vector<texture::Texture>> textures =
      render::build_scene_textures(scene, {options.threads});
  if (!textures) return textures.status();
  st.cpu_textures = std::move(*textures);
  Result<deferred::GpuTextureClasses> classes =
      deferred::gpu_texture_classes(scene.materials, st.cpu_textures, "deferred GL");
  if (!classes) return classes.status();
  upload_texture_classes(*classes, st.cpu_textures, st.class_arrays);
  st.materials_ssbo =
      upload_materials(deferred::gpu_materials(scene.materials, st.cpu_textures, *classes));
  upload_meshes(scene.meshes, st.meshes);
  const std::filesystem::path& d = st.options.glsl_dir;
  Result<glsl::Source> vs = glsl::shipped_shader(glsl::Stage::vertex, "deferred_gbuffer.vert", d);
  if (!vs) return vs.status();
  Result<glsl::Source> fs = glsl::shipped_shader(glsl::Stage::fragment, "deferred_gbuffer.frag", d);
  if (!fs) return fs.status();
  glsl::ExpandOptions so;
  so.shipped_dir = d;
  Result<Program> prog = link_program({*vs, *fs}, so);
  if (!prog) return prog.status();
  st.gbuffer_program = std::move(*prog);
  st.material_location = st.gbuffer_program.uniform("tessera_material");
  if (Status s = check_errors("deferred GL: scene upload"); !s.ok()) return s;
  return r;
}

Status DeferredRenderer::check_size(int width, int height, int m) const {
  if (m < 1 || m > 8) {
    return Status::error(ErrorCode::invalid_argument,
                         "deferred GL: window size m must be in [1, 8], got " + std::to_string(m));
  }
  if (width < 1 || height < 1) {
    return Status::error(
        ErrorCode::invalid_argument,
        "deferred GL: bad output size " + std::to_string(width) + "x" + std::to_string(height));
  }
  GLint fw = 0, fh = 0, tex = 0, rb = 0;
  glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &fw);
  glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &fh);
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &tex);
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &rb);
  const std::int64_t gw = std::int64_t(width) * m, gh = std::int64_t(height) * m;
  const std::string what = "deferred GL: G-buffer " + std::to_string(gw) + "x" +
                           std::to_string(gh) + " (" + std::to_string(width) + "x" +
                           std::to_string(height) + ", m = " + std::to_string(m) + ") exceeds ";
  const std::pair<std::int64_t, std::pair<GLint, const char*>> checks[] = {
      {gw, {fw, "GL_MAX_FRAMEBUFFER_WIDTH"}},
      {gh, {fh, "GL_MAX_FRAMEBUFFER_HEIGHT"}},
      {std::max(gw, gh), {tex, "GL_MAX_TEXTURE_SIZE"}},
      {std::max(gw, gh), {rb, "GL_MAX_RENDERBUFFER_SIZE"}}};
  for (const auto& [value, limit] : checks) {
    if (value > limit.first) {
      return Status::error(ErrorCode::too_large,
                           what + limit.second + " = " + std::to_string(limit.first));
    }
  }
  return Status::success();
}

Status DeferredRenderer::render_gbuffer(const scene::Camera& camera, int width, int height, int m) {
  if (Status s = check_size(width, height, m); !s.ok()) return s;
  State& st = *state_;
  const int gw = width * m, gh = height * m;
  if (st.w != width || st.h != height || st.m != m || !st.fbo) {
    st.fbo = create_object(ObjectType::framebuffer);
    Object* targets[3] = {&st.g0, &st.g1, &st.g2};
    GLenum bufs[3];
    for (int i = 0; i < 3; ++i) {
      *targets[i] = create_object(ObjectType::texture, GL_TEXTURE_2D);
      glTextureStorage2D(targets[i]->get(), 1, GL_RGBA32F, gw, gh);
      glTextureParameteri(targets[i]->get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTextureParameteri(targets[i]->get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      glNamedFramebufferTexture(st.fbo.get(), GLenum(GL_COLOR_ATTACHMENT0 + i), targets[i]->get(),
                                0);
      bufs[i] = GLenum(GL_COLOR_ATTACHMENT0 + i);
    }
    st.depth = create_object(ObjectType::renderbuffer);
    glNamedRenderbufferStorage(st.depth.get(), GL_DEPTH_COMPONENT32F, gw, gh);
    glNamedFramebufferRenderbuffer(st.fbo.get(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                   st.depth.get());
    glNamedFramebufferDrawBuffers(st.fbo.get(), 3, bufs);
    const GLenum status = glCheckNamedFramebufferStatus(st.fbo.get(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
      st.fbo.reset();
      return Status::error(
          ErrorCode::unsupported, "deferred GL: G-buffer framebuffer " + std::to_string(gw) + "x" +
                                      std::to_string(gh) +
                                      " (3 x RGBA32F + D32F) is incomplete (0x" +
                                      [&] {
                                        char b[16];
                                        std::snprintf(b, sizeof b, "%04X", status);
                                        return std::string(b);
                                      }() +
                                      ")");
    }
    st.w = width;
    st.h = height;
    st.m = m;
  }
  // Camera data and vertices, exactly as DeferredRenderer::render_gbuffer.
  const deferred::GBufferCamera cam = deferred::gbuffer_camera(camera, width, height);
  st.camera = deferred::gpu_camera(cam, camera.far_z);
  const scene::Scene& sc = *st.scene;
  for (std::size_t mi = 0; mi < sc.meshes.size(); ++mi) {
    const scene::Mesh& mesh = sc.meshes[mi];
    st.scratch.resize(mesh.positions.size() * 5);
    // Interleaved: clip x, y, z, w and the linear view depth per vertex.
    deferred::transform_gbuffer_vertices(cam, mesh.positions, st.scratch.data(), 5,
                                         st.scratch.data() + 4, 5, {st.options.threads});
    if (!st.scratch.empty()) {
      glNamedBufferData(st.meshes[mi].dynamic_vbo.get(), GLsizeiptr(st.scratch.size() * 4),
                        st.scratch.data(), GL_STREAM_DRAW);
    }
  }
  GpuTimer timer;
  glFinish();
  const auto wall0 = std::chrono::steady_clock::now();
  if (Status s = timer.begin("gbuffer"); !s.ok()) return s;
  const float clear0[4] = {camera.far_z, 0, 0, 0}, clear1[4] = {-1, 0, 0, 0},
              clear2[4] = {0, 0, 0, 0};
  glClearNamedFramebufferfv(st.fbo.get(), GL_COLOR, 0, clear0);
  glClearNamedFramebufferfv(st.fbo.get(), GL_COLOR, 1, clear1);
  glClearNamedFramebufferfv(st.fbo.get(), GL_COLOR, 2, clear2);
  const float one = 1.0f;
  glClearNamedFramebufferfv(st.fbo.get(), GL_DEPTH, 0, &one);
  glBindFramebuffer(GL_FRAMEBUFFER, st.fbo.get());
  glViewport(0, 0, gw, gh);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glUseProgram(st.gbuffer_program.get());
  for (const GlMesh& g : st.meshes) {
    if (g.indices == 0) continue;
    glUniform1i(st.material_location, g.material);
    glBindVertexArray(g.vao.get());
    glDrawElements(GL_TRIANGLES, GLsizei(g.indices), GL_UNSIGNED_INT, nullptr);
  }
  glBindVertexArray(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glFinish();  // see deferred_renderer.cpp run_pass: the query must cover the deferred work
  st.gbuffer_wall_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall0).count();
  if (Status s = timer.end(); !s.ok()) return s;
  // Mesa 22.3 llvmpipe sometimes reports an impossible GL_TIME_ELAPSED for the first pass
  // after a framebuffer is (re)allocated (GpuTimer::collect detects it): the frame is fine,
  // only its time is unknown (NaN).
  Result<std::vector<PassTime>> times = timer.collect();
  st.gbuffer_ms = times && !times->empty() ? times->front().gpu_ms : std::nan("");
  return check_errors("deferred GL: geometry pass");
}

Result<deferred::GBuffer> DeferredRenderer::read_gbuffer() const {
  const State& st = *state_;
  if (!st.fbo) return Status::error(ErrorCode::invalid_argument, "deferred GL: no G-buffer yet");
  deferred::GBuffer gb;
  raster::FrameBufferDesc desc;
  desc.width = st.w;
  desc.height = st.h;
  desc.ssaa = st.m;
  desc.msaa = 1;
  desc.channels = deferred::kGBufferChannels;
  Result<raster::FrameBuffer> fb = raster::FrameBuffer::create(desc);
  if (!fb) return fb.status();
  gb.fb = std::move(*fb);
  gb.m = st.m;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) gb.inv_view.m[c][r] = st.camera.inv_view[c * 4 + r];
  gb.eye = {st.camera.eye[0], st.camera.eye[1], st.camera.eye[2]};
  gb.tan_half_fov_y = st.camera.tan_half_fov;
  gb.aspect = st.camera.aspect;
  const Object* tex[3] = {&st.g0, &st.g1, &st.g2};
  // Channel of each texture component (-1 = not stored).
  const int map[3][4] = {
      {deferred::kChDepth, deferred::kChNormal, deferred::kChNormal + 1, deferred::kChNormal + 2},
      {deferred::kChMaterial, deferred::kChUv, deferred::kChUv + 1, -1},
      {deferred::kChDuvDx, deferred::kChDuvDx + 1, deferred::kChDuvDy, deferred::kChDuvDy + 1}};
  for (int t = 0; t < 3; ++t) {
    Result<ImageRGBAF> img = read_texture_rgbaf(tex[t]->get(), 0, 0);
    if (!img) return img.status();
    for (int gy = 0; gy < img->height; ++gy) {
      for (int gx = 0; gx < img->width; ++gx) {
        const float* s = img->at(gx, gy);
        float* o = gb.fb.data(gx, gy, 0);
        for (int c = 0; c < 4; ++c)
          if (map[t][c] >= 0) o[map[t][c]] = s[c];
      }
    }
  }
  return gb;
}

}  // namespace tessera::gl
