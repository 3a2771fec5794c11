// engine_aa — a minimal deferred renderer that anti-aliases with tessera::gl::AdaptiveSupersampler.
//
// The engine side is all here and all its own: an OpenGL 4.5 core context it makes itself (a GLFW
// window through GLX, or with --headless a surfaceless EGL context: examples/common/
// engine_context.h, which also hands the context's GetProcAddress to tessera), GL entry points
// from libOpenGL, a scene of boxes and spheres generated in code, a G-buffer of
//   RT0 RGBA16F  (world normal xyz, linear view depth)
//   RT1 RGBA8    (albedo rgb, (material id + 1) / 255; 0 = sky)
// rasterised m x m enlarged, six point lights in the engine's own uniform block, and a
// Blinn-Phong shader with a sharp specular lobe and a procedural checker floor (both alias at
// one sample per pixel). The integration with tessera is the block marked "tessera" below.
//
// Usage: engine_aa [--headless] [--size WxH] [--m M] [--budget B]
//                  [--schedule frame_list|tile_list|loop] [--glsl DIR] [--json] [-o DIR]
//   --headless  a surfaceless EGL context instead of the window (the image is the same)
//   --json  one JSON object: samples %, PSNR of the adaptive and the 1 spp image against the
//           component's own full supersampling (tonemapped, sRGB8), pass times (host time to a
//           glFinish after each pass: llvmpipe's GL_TIME_ELAPSED reads 0 for compute)
//   -o DIR  writes adaptive.png, reference.png, first.png, samples.png (k + 1, grey)
//   --frame-loop N  N frames with dynamic resolution: the render scale cycles 100 % -> 70 % ->
//           85 %, the G-buffer drawn into the top-left of the full-size targets, one component
//           dispatched at each frame's render size (no re-create); --json reports per frame the
//           render size, the extra samples and tessera's time
// In the window the adaptive image is drawn to the default framebuffer and shown; --json then
// also reports "window_max_diff", the largest byte difference between the back buffer read back
// and adaptive.png. Exit 1 with one line when there is no OpenGL 4.5 device or on bad arguments.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "aa_report.h"  // examples/common: the flags, measures and report both AA engines share
#include "aa_scene.h"   // examples/common: the scene, camera, lights and shading of both
#include "engine_context.h"  // first: the engine's GL and window headers
#include "tessera/core.h"
#include "tessera/gl.h"
#include "tessera/gl_adaptive.h"

namespace {

// The flags of engine_aa_vk too (aa_report.h), and the GL engine's own.
struct Args : engine::AaArgs {
  std::string glsl;
  bool headless = false;
  int frame_loop = 0;
};

int fail(const std::string& msg) {
  std::fprintf(stderr, "engine_aa: %s\n", msg.c_str());
  return 1;
}

// ---- the engine's scene (examples/common/aa_scene.h) -----------------------------------------

using engine::Camera;
using engine::make_scene;
using engine::Vertex;

// ---- small GL helpers (the engine's own) ----------------------------------------------------

const char* kGeometryVs = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 albedo;
layout(location = 3) in float id;
uniform mat4 view, proj;
out vec3 v_normal, v_albedo;
out float v_depth, v_id;
void main() {
  vec4 view_pos = view * vec4(position, 1.0);
  v_normal = normal; v_albedo = albedo; v_id = id; v_depth = -view_pos.z;
  gl_Position = proj * view_pos;
  gl_Position.y = -gl_Position.y;  // G-buffer row 0 = the top row (the component's convention)
})";
const char* kGeometryFs = R"(#version 450 core
in vec3 v_normal, v_albedo;
in float v_depth, v_id;
layout(location = 0) out vec4 rt0;
layout(location = 1) out vec4 rt1;
void main() {
  rt0 = vec4(normalize(v_normal), v_depth);
  rt1 = vec4(v_albedo, (v_id + 1.0) / 255.0);
})";

// The engine's shading, handed to tessera as the hook (aa_scene.h): its own frame block
// (binding 0) and albedo texture (unit 0), positions from the linear depth.
const std::string kShadingHook = engine::shading_hook("std140, binding = 0", "binding = 0");

using engine::ms_since;

tessera::ImageRGBAF read_rgba(GLuint tex, int w, int h) {
  tessera::ImageRGBAF img(w, h);
  glGetTextureImage(tex, 0, GL_RGBA, GL_FLOAT, GLsizei(img.pixels.size() * 4), img.pixels.data());
  return img;
}

// The engine's camera (aa_scene.h) with GL's perspective projection (depth -1..1).
Camera make_camera(const Args& a) {
  Camera cam = engine::make_camera(a.w, a.h);
  const float zn = 0.1f, zf = 50.0f;
  cam.proj[0] = 1.0f / (cam.tan_half * cam.aspect);
  cam.proj[5] = 1.0f / cam.tan_half;
  cam.proj[10] = -(zf + zn) / (zf - zn);
  cam.proj[11] = -1.0f;
  cam.proj[14] = -2.0f * zf * zn / (zf - zn);
  return cam;
}

// The engine's per-frame shading data (aa_scene.h), bound where its hook declares it.
GLuint make_frame_ubo(const Camera& cam, int gw, int gh) {
  const engine::FrameBlock frame_ubo = engine::frame_block(cam, gw, gh);
  GLuint ubo;
  glCreateBuffers(1, &ubo);
  glNamedBufferStorage(ubo, sizeof frame_ubo, &frame_ubo, GL_DYNAMIC_STORAGE_BIT);
  return ubo;
}

// The report (aa_report.h) with the GL engine's own keys: its context, the window's difference.
void print_report(const Args& a, const engine::Platform& platform, const engine::AaReport& r,
                  int window_diff) {
  if (!a.json) {
    engine::print_aa_summary("engine_aa", "", a, r);
    return;
  }
  std::string context = "\"context\": \"" + std::string(platform.kind()) + "\", ";
  if (window_diff >= 0) context += "\"window_max_diff\": " + std::to_string(window_diff) + ", ";
  engine::print_aa_json(platform.renderer(), a, r, "", context, "");
}

// The engine's G-buffer (RT0 RGBA16F normal + linear depth, RT1 RGBA8 albedo + (id + 1) / 255,
// a depth buffer), its geometry and program.
struct GBuffer {
  GLuint rt[2] = {0, 0}, depth_rb = 0, fbo = 0, vao = 0, vbo = 0, prog = 0;
  GLsizei count = 0;
  double ms = 0;  // the geometry pass, to a glFinish
  ~GBuffer() {
    glDeleteProgram(prog);
    glDeleteBuffers(1, &vbo);
    glDeleteVertexArrays(1, &vao);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(1, &depth_rb);
    glDeleteTextures(2, rt);
  }
};

// Rasterises the scene into the top-left gw x gh texels of the G-buffer (the rest cleared).
void draw_gbuffer(const GBuffer& g, const Camera& cam, int gw, int gh) {
  glBindFramebuffer(GL_FRAMEBUFFER, g.fbo);
  glViewport(0, 0, gw, gh);
  glEnable(GL_DEPTH_TEST);
  const float zero[4] = {0, 0, 0, 0}, far_depth = 1.0f;
  glClearNamedFramebufferfv(g.fbo, GL_COLOR, 0, zero);
  glClearNamedFramebufferfv(g.fbo, GL_COLOR, 1, zero);
  glClearNamedFramebufferfv(g.fbo, GL_DEPTH, 0, &far_depth);
  glUseProgram(g.prog);
  glUniformMatrix4fv(glGetUniformLocation(g.prog, "view"), 1, GL_FALSE, cam.view);
  glUniformMatrix4fv(glGetUniformLocation(g.prog, "proj"), 1, GL_FALSE, cam.proj);
  glBindVertexArray(g.vao);
  glDrawArrays(GL_TRIANGLES, 0, g.count);
}

// Creates the G-buffer of gw x gh texels and rasterises the scene into it; "" or the problem.
std::string geometry_pass(GBuffer& g, const Camera& cam, int gw, int gh) {
  glCreateTextures(GL_TEXTURE_2D, 2, g.rt);
  glTextureStorage2D(g.rt[0], 1, GL_RGBA16F, gw, gh);
  glTextureStorage2D(g.rt[1], 1, GL_RGBA8, gw, gh);
  glCreateRenderbuffers(1, &g.depth_rb);
  glNamedRenderbufferStorage(g.depth_rb, GL_DEPTH_COMPONENT32F, gw, gh);
  glCreateFramebuffers(1, &g.fbo);
  glNamedFramebufferTexture(g.fbo, GL_COLOR_ATTACHMENT0, g.rt[0], 0);
  glNamedFramebufferTexture(g.fbo, GL_COLOR_ATTACHMENT1, g.rt[1], 0);
  glNamedFramebufferRenderbuffer(g.fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, g.depth_rb);
  const GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(g.fbo, 2, bufs);
  if (glCheckNamedFramebufferStatus(g.fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    return "G-buffer " + std::to_string(gw) + "x" + std::to_string(gh) + " incomplete";
  const std::vector<Vertex> verts = make_scene();
  glCreateBuffers(1, &g.vbo);
  glNamedBufferStorage(g.vbo, GLsizeiptr(verts.size() * sizeof(Vertex)), verts.data(), 0);
  glCreateVertexArrays(1, &g.vao);
  glVertexArrayVertexBuffer(g.vao, 0, g.vbo, 0, sizeof(Vertex));
  const GLuint sizes[4] = {3, 3, 3, 1}, offsets[4] = {0, 12, 24, 36};
  for (GLuint i = 0; i < 4; ++i) {
    glEnableVertexArrayAttrib(g.vao, i);
    glVertexArrayAttribFormat(g.vao, i, GLint(sizes[i]), GL_FLOAT, GL_FALSE, offsets[i]);
    glVertexArrayAttribBinding(g.vao, i, 0);
  }
  std::string log;
  g.prog = engine::compile_program(kGeometryVs, kGeometryFs, log);  // engine_context.h
  if (g.prog == 0) return "geometry shader: " + log;
  g.count = GLsizei(verts.size());
  glFinish();
  auto t0 = std::chrono::steady_clock::now();
  draw_gbuffer(g, cam, gw, gh);
  glFinish();
  g.ms = ms_since(t0);
  return "";
}

// The command line; "" or the problem.
std::string parse_args(int argc, char** argv, Args& a) {
  engine::CommandLine cl;
  engine::add_aa_flags(cl, a);
  cl.option("--glsl", [&a](const std::string& v) -> std::string {
    a.glsl = v;
    return "";
  });
  cl.flag("--headless", &a.headless);
  cl.option("--frame-loop", [&a](const std::string& v) -> std::string {
    a.frame_loop = std::atoi(v.c_str());
    return a.frame_loop < 1 ? "--frame-loop " + v + ": expected a frame count >= 1" : "";
  });
  return cl.parse(argc, argv);
}

// --frame-loop: a new render size every frame (100 % -> 70 % -> 85 %) on one component: the
// G-buffer drawn into the top-left of the full-size targets, the frame block's grid updated,
// one dispatch at that render size. Prints per frame the size, extra samples and time.
int frame_loop(const Args& a, const GBuffer& g, const Camera& cam, GLuint ubo,
               tessera::gl::AdaptiveSupersampler& aa) {
  static const int kScales[3] = {100, 70, 85};
  std::string frames;
  for (int i = 0; i < a.frame_loop; ++i) {
    const int scale = kScales[i % 3];
    const int w = (a.w * scale + 50) / 100, h = (a.h * scale + 50) / 100;
    draw_gbuffer(g, cam, w * a.m, h * a.m);
    const engine::FrameBlock block = engine::frame_block(cam, w * a.m, h * a.m);
    glNamedBufferSubData(ubo, 0, sizeof block, &block);
    // ---- tessera: this frame's render size, the same component ----
    tessera::gl::AdaptiveFrame frame;
    frame.gbuffer = {g.rt[0], g.rt[1], 0, 0};
    frame.render_size = {w, h};
    if (a.budget >= 0) frame.budget = a.budget;
    auto r = aa.dispatch(frame);
    if (!r) return fail(r.status().message);
    char line[256];
    std::snprintf(line, sizeof line,
                  "%s{\"frame\": %d, \"scale_percent\": %d, \"render_size\": [%d, %d], "
                  "\"extra_samples\": %llu, \"tessera_ms\": %.3f}",
                  i ? ", " : "", i + 1, scale, r->render_size.width, r->render_size.height,
                  static_cast<unsigned long long>(r->extra_samples), r->total_wall_ms());
    frames += line;
    if (!a.json) {
      std::printf("frame %d: %dx%d (%d %%), %llu extra samples, %.2f ms\n", i + 1, w, h, scale,
                  static_cast<unsigned long long>(r->extra_samples), r->total_wall_ms());
    }
  }
  if (a.json) std::printf("{\"backend\": \"gl\", \"frames\": [%s]}\n", frames.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  if (std::string why = parse_args(argc, argv, a); !why.empty()) return fail(why);
  // The engine's context, current from here on; tessera's entry points loaded from it.
  engine::Platform platform;
  if (std::string why = platform.open(a.headless, a.w, a.h, "engine_aa"); !why.empty())
    return fail("no OpenGL 4.5 device: " + why);
  const int gw = a.w * a.m, gh = a.h * a.m;

  // ---- the engine's G-buffer and geometry pass ----
  const Camera cam = make_camera(a);
  GBuffer gbuf;
  if (std::string why = geometry_pass(gbuf, cam, gw, gh); !why.empty()) return fail(why);
  const GLuint* rt = gbuf.rt;
  const double gbuffer_ms = gbuf.ms;

  const GLuint ubo = make_frame_ubo(cam, gw, gh);
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, ubo);
  glBindTextureUnit(0, rt[1]);

  // ---- tessera: create once per (size, m, options), dispatch per frame ----
  tessera::gl::AdaptiveSupersamplerOptions o;
  // The G-buffer layout, the hook, the resolve: as engine_aa_vk's (aa_report.h). Its pass
  // times are a stall per pass here: for --json, not for shipping frames.
  engine::set_aa_options(o, a, kShadingHook);
  o.glsl_dir = a.glsl;
  auto aa = tessera::gl::AdaptiveSupersampler::create(o);
  if (!aa) return fail(aa.status().message);
  if (a.frame_loop > 0) {
    const int rc = frame_loop(a, gbuf, cam, ubo, **aa);
    glDeleteBuffers(1, &ubo);
    aa->reset();
    return rc;
  }
  tessera::gl::AdaptiveFrame frame;
  frame.gbuffer = {rt[0], rt[1], 0, 0};
  if (a.budget >= 0) frame.budget = a.budget;
  tessera::Result<tessera::gl::AdaptiveOutput> adaptive = (*aa)->dispatch(frame);
  if (!adaptive) return fail(adaptive.status().message);
  // ---- end of the integration: adaptive->colour is the anti-aliased HDR image ----

  // Timed frames: the first dispatch of each kind also pays the driver's shader compilation
  // (llvmpipe compiles at first use), so every kind runs twice and the second is reported.
  adaptive = (*aa)->dispatch(frame);
  if (!adaptive) return fail(adaptive.status().message);
  const tessera::ImageRGBAF img = read_rgba(adaptive->colour, a.w, a.h);
  // The frame on screen: the output texture drawn to the window (Reinhard, then sRGB).
  std::vector<std::uint8_t> shown;
  if (platform.windowed()) platform.present(adaptive->colour, a.w, a.h, true, true, shown);
  std::vector<std::uint8_t> counts(std::size_t(a.w) * std::size_t(a.h));
  glGetTextureImage(adaptive->sample_counts, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE,
                    GLsizei(counts.size()), counts.data());
  const auto extra = adaptive->extra_samples;
  const auto adaptive_passes = adaptive->passes;
  auto reference = (*aa)->dispatch_reference(frame);
  if (reference) reference = (*aa)->dispatch_reference(frame);
  if (!reference) return fail(reference.status().message);
  const tessera::ImageRGBAF ref = read_rgba(reference->colour, a.w, a.h);
  const double reference_ms = reference->total_wall_ms();
  auto first = (*aa)->dispatch_first_sample(frame);
  if (first) first = (*aa)->dispatch_first_sample(frame);
  if (!first) return fail(first.status().message);
  const tessera::ImageRGBAF one = read_rgba(first->colour, a.w, a.h);
  const double first_ms = first->total_wall_ms();

  engine::AaReport rep;
  const engine::AaImages images =
      engine::measure(a, img, ref, one, static_cast<unsigned long long>(extra), rep);
  const int window_diff =
      platform.windowed() ? engine::max_rgb_difference(shown, images.adaptive.pixels.data()) : -1;
  if (!a.out.empty()) {
    if (std::string why = engine::write_aa_outputs(a, images, counts); !why.empty())
      return fail(why);
  }
  rep.gbuffer_ms = gbuffer_ms;
  rep.first_ms = first_ms;
  rep.reference_ms = reference_ms;
  rep.set_passes(adaptive_passes, &tessera::PassTime::wall_ms);
  for (const auto& pass : rep.passes) rep.adaptive_ms += pass.second;
  print_report(a, platform, rep, window_diff);
  glDeleteBuffers(1, &ubo);
  aa->reset();
  return 0;
}
