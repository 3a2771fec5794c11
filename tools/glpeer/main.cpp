// tessera-glpeer — renders a scene with OpenGL 4.5 core through tessera's EGL runtime
// (tessera/gl.h: an EGL device or the surfaceless platform, Mesa llvmpipe on a machine without
// a GPU; --egl-device / TESSERA_EGL_DEVICE choose), as the peer of tessera's software
// rasteriser.
//
// Same inputs and conventions as `tessera render`: the scene loaders of tessera/scene.h, the
// camera of --camera / --orbit, an unlit shader (base colour factor x base-colour texture,
// sampled trilinear or 16x anisotropic with GL_REPEAT), sRGB textures decoded by the hardware
// path (GL_SRGB8_ALPHA8, glGenerateMipmap), colour accumulated in a multisampled RGBA32F
// buffer, resolved by glBlitFramebuffer (box filter in linear light) and encoded to sRGB on the
// CPU exactly as tessera encodes its own images. Timing covers clear, draw and resolve of each
// frame, ended by glFinish; the read-back is excluded. The JSON also reports GL_TIME_ELAPSED per
// frame (gpu_frame_ms).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "gl/gl_api.h"
#include "tessera/gl.h"
#include "tessera/io.h"
#include "tessera/render.h"
#include "tessera/scene.h"
#include "tessera/texture.h"

namespace {

using namespace tessera;
using namespace tessera::gl::api;  // NOLINT(google-build-using-namespace): GL entry points

int fail(const std::string& msg) {
  std::fprintf(stderr, "tessera-glpeer: %s\n", msg.c_str());
  return 1;
}

const char* kVertex = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec2 uv;
uniform mat4 view_projection;
out vec2 v_uv;
void main() {
  v_uv = uv;
  gl_Position = view_projection * vec4(position, 1.0);
})";

const char* kFragment = R"(#version 450 core
in vec2 v_uv;
uniform sampler2D base_texture;
uniform vec4 base_color;
uniform int has_texture;
layout(location = 0) out vec4 colour;
void main() {
  vec4 c = base_color;
  if (has_texture != 0) c *= texture(base_texture, v_uv);
  colour = vec4(c.rgb, 1.0);
})";

struct GpuMesh {
  gl::Object vao, vbo, ibo;
  GLsizei count = 0;
  int material = 0;
};

/// The command line.
struct Options {
  std::string scene_path, out_path, camera_text, orbit_text, json_path, filter = "trilinear",
                                                                        shading = "textured";
  std::string egl_device;
  int width = 1024, height = 768, msaa = 1, frames = 1;
};

/// Parses argv into `o`; returns -1 to go on, else the exit code (help, usage error).
int parse_args(int argc, char** argv, Options& o) {
  CLI::App app{"Render a scene with OpenGL (Mesa llvmpipe) as the peer of `tessera render`",
               "tessera-glpeer"};
  app.add_option("SCENE", o.scene_path, "Scene file (.obj, .gltf, .glb) or 'builtin'")->required();
  app.add_option("--width", o.width)->check(CLI::Range(1, 8192));
  app.add_option("--height", o.height)->check(CLI::Range(1, 8192));
  app.add_option("--camera", o.camera_text, "eye,target,up,fov (10 numbers)");
  app.add_option("--orbit", o.orbit_text, "FRAME/N: camera on the scene's orbit");
  app.add_option("--msaa", o.msaa, "Samples per pixel (1, 2, 4, 8)")
      ->check(CLI::IsMember({1, 2, 4, 8, 16}));
  app.add_option("--filter", o.filter)->check(CLI::IsMember({"trilinear", "aniso16"}));
  app.add_option("--shading", o.shading, "textured, or flat white (coverage only)")
      ->check(CLI::IsMember({"textured", "flat"}));
  app.add_option("--frames", o.frames, "Frames to time (same camera); the image is the last")
      ->check(CLI::Range(1, 10000));
  app.add_option("-o,--out", o.out_path, "Output PNG")->required();
  app.add_option("--json", o.json_path, "Write timings and details as JSON here ('-' = stdout)");
  app.add_option("--egl-device", o.egl_device,
                 "EGL device: auto, hardware, software, surfaceless or an index (default: "
                 "$TESSERA_EGL_DEVICE, else auto)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return e.get_exit_code() == 0 ? 0 : 2;
  }
  return -1;
}

/// Textures: hardware sRGB decoding, glGenerateMipmap chains, repeat addressing.
std::vector<gl::Object> upload_textures(const scene::Scene& sc, const std::string& filter) {
  std::vector<gl::Object> textures;
  for (const scene::Texture& t : sc.textures) {
    gl::Object tex = gl::create_object(gl::ObjectType::texture, GL_TEXTURE_2D);
    const int levels = mip_level_count(t.image.width, t.image.height);
    glTextureStorage2D(tex.get(), levels, t.srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, t.image.width,
                       t.image.height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(tex.get(), 0, 0, 0, t.image.width, t.image.height, GL_RGBA,
                        GL_UNSIGNED_BYTE, t.image.pixels.data());
    glGenerateTextureMipmap(tex.get());
    glTextureParameteri(tex.get(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(tex.get(), GL_TEXTURE_WRAP_T, GL_REPEAT);
    glTextureParameteri(tex.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(tex.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameterf(tex.get(), GL_TEXTURE_MAX_ANISOTROPY, filter == "aniso16" ? 16.0f : 1.0f);
    textures.push_back(std::move(tex));
  }
  return textures;
}

/// Meshes: interleaved position + uv.
std::vector<GpuMesh> upload_meshes(const scene::Scene& sc) {
  std::vector<GpuMesh> meshes;
  for (const scene::Mesh& m : sc.meshes) {
    GpuMesh g;
    std::vector<float> v;
    v.reserve(m.positions.size() * 5);
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
      v.insert(v.end(),
               {m.positions[i].x, m.positions[i].y, m.positions[i].z, m.uvs[i].x, m.uvs[i].y});
    }
    g.vao = gl::create_object(gl::ObjectType::vertex_array);
    g.vbo = gl::create_object(gl::ObjectType::buffer);
    g.ibo = gl::create_object(gl::ObjectType::buffer);
    glBindVertexArray(g.vao.get());
    glBindBuffer(GL_ARRAY_BUFFER, g.vbo.get());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(v.size() * sizeof(float)), v.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.ibo.get());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(m.indices.size() * 4), m.indices.data(),
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 20, nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, 20, reinterpret_cast<void*>(12));
    g.count = GLsizei(m.indices.size());
    g.material = m.material;
    meshes.push_back(std::move(g));
  }
  return meshes;
}

/// What one frame draws with: the scene's GPU objects, the uniforms, the framebuffers.
struct FrameSetup {
  const scene::Scene& sc;
  const std::vector<GpuMesh>& meshes;
  const std::vector<gl::Object>& textures;
  GLint loc_base_color, loc_has;
  GLuint ms_fbo, fbo;
  int width, height;
  bool flat;
};

/// Clears, draws every mesh and resolves the multisampled target into `fbo`.
void draw_frame(const FrameSetup& f) {
  glBindFramebuffer(GL_FRAMEBUFFER, f.ms_fbo);
  glViewport(0, 0, f.width, f.height);
  glClearColor(render::kBackground[0], render::kBackground[1], render::kBackground[2], 1.0f);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glActiveTexture(GL_TEXTURE0);
  for (const GpuMesh& g : f.meshes) {
    const scene::Material& m = f.sc.materials[std::size_t(g.material)];
    const float white[4] = {1, 1, 1, 1};
    glUniform4fv(f.loc_base_color, 1, f.flat ? white : m.base_color);
    const bool has = !f.flat && m.base_color_texture >= 0;
    glUniform1i(f.loc_has, has ? 1 : 0);
    if (has) glBindTexture(GL_TEXTURE_2D, f.textures[std::size_t(m.base_color_texture)].get());
    glBindVertexArray(g.vao.get());
    glDrawElements(GL_TRIANGLES, g.count, GL_UNSIGNED_INT, nullptr);
  }
  glBindFramebuffer(GL_READ_FRAMEBUFFER, f.ms_fbo);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, f.fbo);
  glBlitFramebuffer(0, 0, f.width, f.height, 0, 0, f.width, f.height, GL_COLOR_BUFFER_BIT,
                    GL_NEAREST);
}

/// The JSON report to stdout ('-') or atomically to o.json_path (none when empty).
Status write_report(const Options& o, const gl::Context& context, const scene::Scene& sc,
                    int samples, const std::vector<double>& times,
                    const std::vector<double>& gpu_times) {
  std::vector<double> sorted = times, gpu_sorted = gpu_times;
  std::sort(sorted.begin(), sorted.end());
  std::sort(gpu_sorted.begin(), gpu_sorted.end());
  nlohmann::json j = {{"renderer", context.renderer()},
                      {"device", context.device_description()},
                      {"width", o.width},
                      {"height", o.height},
                      {"msaa", o.msaa},
                      {"samples", samples},
                      {"filter", o.filter},
                      {"triangles", sc.triangle_count()},
                      {"frames", o.frames},
                      {"frame_ms", times},
                      {"median_ms", sorted[sorted.size() / 2]},
                      {"gpu_frame_ms", gpu_times},
                      {"gpu_median_ms", gpu_sorted[gpu_sorted.size() / 2]}};
  if (o.json_path == "-") {
    std::printf("%s\n", j.dump(2).c_str());
  } else if (!o.json_path.empty()) {
    const std::string text = j.dump(2) + "\n";
    return io::write_file_atomic(o.json_path,
                                 {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
  }
  return Status::success();
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (int rc = parse_args(argc, argv, o); rc >= 0) return rc;
  const int width = o.width, height = o.height, msaa = o.msaa;

  Result<scene::Scene> loaded = o.scene_path == "builtin"
                                    ? Result<scene::Scene>(scene::builtin_scene())
                                    : scene::load_scene(o.scene_path);
  if (!loaded) return fail(loaded.status().message);
  const scene::Scene& sc = *loaded;
  Result<scene::Camera> cam = scene::camera_from_text(sc, o.camera_text, o.orbit_text);
  if (!cam) {
    std::fprintf(stderr, "tessera-glpeer: %s\n", cam.status().message.c_str());
    return 2;
  }
  const scene::Camera camera = *cam;

  // OpenGL 4.5 core through tessera's EGL runtime (surfaceless context, FBO rendering).
  gl::ContextOptions context_options;
  context_options.device = o.egl_device;
  Result<std::unique_ptr<gl::Context>> context = gl::Context::create(context_options);
  if (!context) return fail(context.status().message);

  Result<gl::Program> program =
      gl::link_program({{glsl::Stage::vertex, kVertex, "glpeer.vert"},
                        {glsl::Stage::fragment, kFragment, "glpeer.frag"}});
  if (!program) return fail("shader: " + program.status().message);
  const GLuint prog = program->get();
  glUseProgram(prog);

  std::vector<gl::Object> textures = upload_textures(sc, o.filter);
  std::vector<GpuMesh> meshes = upload_meshes(sc);
  if (Status s = gl::check_errors("scene upload"); !s.ok()) return fail(s.message);

  // Framebuffers: multisampled RGBA32F + depth, resolved into single-sampled RGBA32F.
  gl::RenderTargetOptions target_options;
  target_options.width = width;
  target_options.height = height;
  target_options.samples = msaa;
  target_options.colour = gl::ColourFormat::rgba32f;
  Result<gl::RenderTarget> ms_target = gl::create_render_target(target_options);
  if (!ms_target) return fail(ms_target.status().message);
  target_options.samples = 1;
  target_options.depth = false;
  Result<gl::RenderTarget> target = gl::create_render_target(target_options);
  if (!target) return fail(target.status().message);
  const GLuint ms_fbo = ms_target->framebuffer.get(), fbo = target->framebuffer.get();
  GLint samples = 0;
  glBindFramebuffer(GL_FRAMEBUFFER, ms_fbo);
  glGetIntegerv(GL_SAMPLES, &samples);

  const Mat4 vp = camera.view_projection(float(width) / float(height));
  glUniformMatrix4fv(program->uniform("view_projection"), 1, GL_FALSE, &vp.m[0][0]);
  glUniform1i(program->uniform("base_texture"), 0);
  const FrameSetup frame{sc,
                         meshes,
                         textures,
                         program->uniform("base_color"),
                         program->uniform("has_texture"),
                         ms_fbo,
                         fbo,
                         width,
                         height,
                         o.shading == "flat"};
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  if (msaa > 1) glEnable(GL_MULTISAMPLE);

  // Wall time per frame (clear, draw, resolve, glFinish) and GPU time (GL_TIME_ELAPSED).
  std::vector<double> times, gpu_times;
  gl::GpuTimer timer;
  for (int f = 0; f < o.frames; ++f) {
    const auto t0 = std::chrono::steady_clock::now();
    if (Status s = timer.begin("frame"); !s.ok()) return fail(s.message);
    draw_frame(frame);
    if (Status s = timer.end(); !s.ok()) return fail(s.message);
    glFinish();
    times.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  Result<std::vector<PassTime>> passes = timer.collect();
  if (!passes) return fail(passes.status().message);
  for (const PassTime& p : *passes) gpu_times.push_back(p.gpu_ms);
  // Read back (flipped to top-down) and encode like tessera does.
  Result<ImageRGBAF> lin = gl::read_framebuffer_rgbaf(fbo, 0, width, height);
  if (!lin) return fail(lin.status().message);
  if (Status s = gl::check_errors("render"); !s.ok()) return fail(s.message);
  if (Status s = io::write_png(o.out_path, to_srgb8(*lin)); !s.ok()) return fail(s.message);
  if (Status s = write_report(o, **context, sc, samples, times, gpu_times); !s.ok()) {
    return fail(s.message);
  }
  // GL objects go before the context does.
  meshes.clear();
  textures.clear();
  *ms_target = {};
  *target = {};
  *program = {};
  return 0;
}
