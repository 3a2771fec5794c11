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
// In the window the adaptive image is drawn to the default framebuffer and shown; --json then
// also reports "window_max_diff", the largest byte difference between the back buffer read back
// and adaptive.png. Exit 1 with one line when there is no OpenGL 4.5 device or on bad arguments.
#include "engine_context.h"  // first: the engine's GL and window headers

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "aa_scene.h"
#include "tessera/core.h"
#include "tessera/gl.h"
#include "tessera/gl_adaptive.h"
#include "tessera/io.h"
#include "tessera/metrics.h"

namespace {

struct Args {
  int w = 320, h = 240, m = 4;
  long long budget = -1;  // -1: none
  std::string schedule = "frame_list", glsl, out;
  bool json = false, headless = false;
};

int fail(const std::string& msg) {
  std::fprintf(stderr, "engine_aa: %s\n", msg.c_str());
  return 1;
}

// ---- the engine's scene ---------------------------------------------------------------------

using engine::make_scene;
using engine::Vertex;

// ---- small GL helpers (the engine's own) ----------------------------------------------------

GLuint compile(GLenum stage, const char* src) {
  const GLuint s = glCreateShader(stage);
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[1024] = {};
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    std::fprintf(stderr, "engine_aa: geometry shader: %s\n", log);
    std::exit(1);
  }
  return s;
}

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

// The engine's shading, handed to tessera as the hook: its own lights block (binding 0), its
// own albedo texture (unit 0), positions from the linear depth.
const char* kShadingHook = R"(
layout(std140, binding = 0) uniform EngineFrame {
  mat4 inv_view;      // camera to world
  vec4 eye_tan;       // eye xyz, tan(fov_y / 2)
  vec4 grid_aspect;   // grid width, height, aspect
  vec4 light_pos[6];  // xyz, radius
  vec4 light_col[6];  // rgb intensity
};
layout(binding = 0) uniform sampler2D engine_albedo;  // RT1

vec3 engine_position(ivec2 g, float depth) {
  float nx = 2.0 * (float(g.x) + 0.5) / grid_aspect.x - 1.0;
  float ny = 1.0 - 2.0 * (float(g.y) + 0.5) / grid_aspect.y;
  float t = eye_tan.w;
  return (inv_view * vec4(nx * t * grid_aspect.z * depth, ny * t * depth, -depth, 1.0)).xyz;
}

vec4 tessera_shade_sample(ivec2 g, float footprint) {
  int id = tessera_adaptive_id(g);  // the component's accessor of the layout's id channel
  if (id < 0) return vec4(0.25, 0.35, 0.55, 1.0) * (1.0 - float(g.y) / grid_aspect.y * 0.6);
  vec3 n = normalize(tessera_adaptive_normal(g));
  vec3 p = engine_position(g, tessera_adaptive_depth(g));
  vec3 albedo = texelFetch(engine_albedo, g, 0).rgb;
  float shininess = id == 2 ? 600.0 : (id == 1 ? 24.0 : 120.0);
  float spec = id == 2 ? 6.0 : (id == 1 ? 0.3 : 1.5);
  if (id == 0) {  // checker floor: a texture term that aliases in the distance
    vec2 c = floor(p.xz * 4.0);
    albedo *= mod(c.x + c.y, 2.0) < 1.0 ? 1.0 : 0.15;
  }
  vec3 v = normalize(eye_tan.xyz - p);
  vec3 colour = 0.04 * albedo;
  for (int i = 0; i < 6; ++i) {
    vec3 to = light_pos[i].xyz - p;
    float d2 = dot(to, to);
    vec3 l = to * inversesqrt(d2);
    float ndl = max(dot(n, l), 0.0);
    if (ndl <= 0.0) continue;
    float fall = light_col[i].w / d2;
    float ndh = max(dot(n, normalize(l + v)), 0.0);
    colour += light_col[i].rgb * fall * ndl * (albedo + spec * pow(ndh, shininess));
  }
  return vec4(colour, 1.0);
}
)";

using engine::look_at;

tessera::ImageRGBAF read_rgba(GLuint tex, int w, int h) {
  tessera::ImageRGBAF img(w, h);
  glGetTextureImage(tex, 0, GL_RGBA, GL_FLOAT, GLsizei(img.pixels.size() * 4), img.pixels.data());
  return img;
}

/// Display encoding: Reinhard c / (1 + c), then sRGB8.
tessera::ImageRGBA8 display(const tessera::ImageRGBAF& hdr) {
  tessera::ImageRGBAF ldr = hdr;
  for (std::size_t i = 0; i < ldr.pixel_count(); ++i) {
    for (int c = 0; c < 3; ++c) {
      float& x = ldr.pixels[i * 4 + std::size_t(c)];
      x = x / (1.0f + x);
    }
    ldr.pixels[i * 4 + 3] = 1.0f;
  }
  return tessera::to_srgb8(ldr);
}

double psnr(const tessera::ImageRGBA8& a, const tessera::ImageRGBA8& b) {
  tessera::metrics::CompareOptions o;
  o.compute_ssim = false;
  auto r = tessera::metrics::compare_images(a, b, o);
  return r ? r->psnr_rgb : 0.0;
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// The engine's camera: look-at view (and its inverse) and a perspective projection.
struct Camera {
  float eye[3] = {3.2f, 2.2f, 4.2f};
  float tan_half = 0, aspect = 1;
  float view[16], inv_view[16], proj[16] = {};
};

Camera make_camera(const Args& a) {
  Camera cam;
  const float at[3] = {0.0f, 0.4f, 0.0f};
  const float fov = 0.8f;
  cam.tan_half = std::tan(fov / 2);
  cam.aspect = float(a.w) / float(a.h);
  look_at(cam.eye, at, cam.view, cam.inv_view);
  const float zn = 0.1f, zf = 50.0f;
  cam.proj[0] = 1.0f / (cam.tan_half * cam.aspect);
  cam.proj[5] = 1.0f / cam.tan_half;
  cam.proj[10] = -(zf + zn) / (zf - zn);
  cam.proj[11] = -1.0f;
  cam.proj[14] = -2.0f * zf * zn / (zf - zn);
  return cam;
}

// The engine's per-frame shading data (bound where its hook declares it): camera, grid size,
// six point lights.
GLuint make_frame_ubo(const Camera& cam, int gw, int gh) {
  struct {
    float inv_view[16], eye_tan[4], grid_aspect[4], light_pos[6][4], light_col[6][4];
  } frame_ubo{};
  std::copy(cam.inv_view, cam.inv_view + 16, frame_ubo.inv_view);
  std::copy(cam.eye, cam.eye + 3, frame_ubo.eye_tan);
  frame_ubo.eye_tan[3] = cam.tan_half;
  frame_ubo.grid_aspect[0] = float(gw), frame_ubo.grid_aspect[1] = float(gh);
  frame_ubo.grid_aspect[2] = cam.aspect;
  const float lights[6][8] = {{2.5f, 3.0f, 2.0f, 0, 1.0f, 0.9f, 0.8f, 14.0f},
                              {-3.0f, 2.5f, 1.5f, 0, 0.5f, 0.6f, 1.0f, 10.0f},
                              {0.5f, 1.2f, 2.5f, 0, 1.0f, 0.5f, 0.3f, 4.0f},
                              {-1.0f, 4.0f, -2.5f, 0, 0.9f, 0.9f, 1.0f, 12.0f},
                              {3.0f, 0.6f, -1.0f, 0, 0.3f, 1.0f, 0.4f, 3.0f},
                              {0.0f, 6.0f, 0.0f, 0, 1.0f, 1.0f, 1.0f, 16.0f}};
  for (int i = 0; i < 6; ++i)
    for (int c = 0; c < 4; ++c) {
      frame_ubo.light_pos[i][c] = lights[i][c];
      frame_ubo.light_col[i][c] = lights[i][4 + c];
    }
  GLuint ubo;
  glCreateBuffers(1, &ubo);
  glNamedBufferStorage(ubo, sizeof frame_ubo, &frame_ubo, 0);
  return ubo;
}

// What one run measured, for the report.
struct Report {
  double samples_pct = 0, psnr_adaptive = 0, psnr_one = 0;
  double gbuffer_ms = 0, first_ms = 0, reference_ms = 0;
  unsigned long long extra = 0;
  int window_diff = -1;  // -1: headless
  std::vector<tessera::gl::PassTime> passes;
};

void print_report(const Args& a, const engine::Platform& platform, const Report& r) {
  if (a.json) {
    std::printf(
        "{\"device\": \"%s\", \"width\": %d, \"height\": %d, \"m\": %d, \"schedule\": \"%s\", ",
        platform.renderer().c_str(), a.w, a.h, a.m, a.schedule.c_str());
    std::printf("\"context\": \"%s\", ", platform.kind());
    if (r.window_diff >= 0) std::printf("\"window_max_diff\": %d, ", r.window_diff);
    if (a.budget >= 0) {
      std::printf("\"budget\": %lld, ", a.budget);
    } else {
      std::printf("\"budget\": null, ");
    }
    std::printf(
        "\"extra_samples\": %llu, \"samples_percent\": %.3f, \"psnr_db\": %.3f, "
        "\"psnr_1spp_db\": %.3f, \"gbuffer_ms\": %.3f, \"passes_ms\": {",
        r.extra, r.samples_pct, r.psnr_adaptive, r.psnr_one, r.gbuffer_ms);
    double total = 0;
    for (std::size_t i = 0; i < r.passes.size(); ++i) {
      std::printf("%s\"%s\": %.3f", i ? ", " : "", r.passes[i].pass.c_str(),
                  r.passes[i].ms);
      total += r.passes[i].ms;
    }
    std::printf("}, \"adaptive_ms\": %.3f, \"first_ms\": %.3f, \"reference_ms\": %.3f}\n", total,
                r.first_ms, r.reference_ms);
  } else {
    std::printf(
        "engine_aa %dx%d m=%d: %.1f %% samples, PSNR %.2f dB (1 spp %.2f dB) against "
        "full supersampling\n",
        a.w, a.h, a.m, r.samples_pct, r.psnr_adaptive, r.psnr_one);
  }
}

// The engine's G-buffer (RT0 RGBA16F normal + linear depth, RT1 RGBA8 albedo + (id + 1) / 255,
// a depth buffer), its geometry and program.
struct GBuffer {
  GLuint rt[2] = {0, 0}, depth_rb = 0, fbo = 0, vao = 0, vbo = 0, prog = 0;
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
  g.prog = glCreateProgram();
  glAttachShader(g.prog, compile(GL_VERTEX_SHADER, kGeometryVs));
  glAttachShader(g.prog, compile(GL_FRAGMENT_SHADER, kGeometryFs));
  glLinkProgram(g.prog);
  glFinish();
  auto t0 = std::chrono::steady_clock::now();
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
  glDrawArrays(GL_TRIANGLES, 0, GLsizei(verts.size()));
  glFinish();
  g.ms = ms_since(t0);
  return "";
}

// The command line; "" or the problem.
std::string parse_args(int argc, char** argv, Args& a) {
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "engine_aa: %s needs a value\n", k.c_str());
        std::exit(1);
      }
      return argv[++i];
    };
    if (k == "--size") {
      const std::string v = next();
      if (std::sscanf(v.c_str(), "%dx%d", &a.w, &a.h) != 2 || a.w <= 0 || a.h <= 0)
        return "--size " + v + ": expected WxH";
    } else if (k == "--m") {
      a.m = std::atoi(next().c_str());
    } else if (k == "--budget") {
      a.budget = std::atoll(next().c_str());
      if (a.budget < 0) return "--budget must be >= 0";
    } else if (k == "--schedule") {
      a.schedule = next();
    } else if (k == "--glsl") {
      a.glsl = next();
    } else if (k == "--json") {
      a.json = true;
    } else if (k == "--headless") {
      a.headless = true;
    } else if (k == "-o") {
      a.out = next();
    } else {
      return "unknown argument " + k;
    }
  }
  return "";
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
  o.width = a.w;
  o.height = a.h;
  o.m = a.m;
  o.layout.normal = {0, "rgb"};
  o.layout.depth = {0, "a"};
  o.layout.id = {1, "a", 255.0f, -1.0f};  // (id + 1) / 255 in unorm8; sky = -1
  o.hook = {kShadingHook, "engine_shading.glsl", {}};
  o.resolve = tessera::AdaptiveResolve::tonemap_weighted;  // HDR lights
  o.output = tessera::AdaptiveOutputFormat::rgba16f;
  o.sample_count_texture = true;
  o.glsl_dir = a.glsl;
  o.profile = true;  // pass times for --json (a stall per pass: not for shipping frames)
  if (a.schedule == "tile_list") {
    o.schedule = tessera::AdaptiveSchedule::tile_list;
  } else if (a.schedule == "loop") {
    o.schedule = tessera::AdaptiveSchedule::loop;
  } else if (a.schedule != "frame_list") {
    return fail("--schedule " + a.schedule + ": frame_list, tile_list or loop");
  }
  auto aa = tessera::gl::AdaptiveSupersampler::create(o);
  if (!aa) return fail(aa.status().message);
  tessera::gl::AdaptiveFrame frame;
  frame.gbuffer = {rt[0], rt[1], 0, 0};
  if (a.budget >= 0) frame.budget = a.budget;
  tessera::Result<tessera::gl::AdaptiveFrameResult> adaptive = (*aa)->dispatch(frame);
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
  const auto adaptive_passes = adaptive->wall_passes;
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

  const tessera::ImageRGBA8 d_img = display(img), d_ref = display(ref), d_one = display(one);
  const int window_diff =
      platform.windowed() ? engine::max_rgb_difference(shown, d_img.pixels.data()) : -1;
  const double pixels = double(a.w) * a.h;
  const double samples_pct = 100.0 * (pixels + double(extra)) / (pixels * a.m * a.m);
  const double p_adaptive = psnr(d_img, d_ref), p_one = psnr(d_one, d_ref);
  if (!a.out.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(a.out, ec);
    tessera::ImageRGBA8 k(a.w, a.h);
    for (std::size_t i = 0; i < counts.size(); ++i) {
      const auto g = std::uint8_t(255 * (counts[i] - 1) / (a.m * a.m - 1));
      k.pixels[i * 4] = k.pixels[i * 4 + 1] = k.pixels[i * 4 + 2] = g;
      k.pixels[i * 4 + 3] = 255;
    }
    for (const auto& [name, im] : {std::pair{"adaptive.png", &d_img},
                                   {"reference.png", &d_ref},
                                   {"first.png", &d_one},
                                   {"samples.png", &k}}) {
      const std::string path = (std::filesystem::path(a.out) / name).string();
      if (auto s = tessera::io::write_png(path, *im); !s.ok()) return fail(s.message);
    }
  }
  Report rep;
  rep.samples_pct = samples_pct;
  rep.psnr_adaptive = p_adaptive;
  rep.psnr_one = p_one;
  rep.gbuffer_ms = gbuffer_ms;
  rep.first_ms = first_ms;
  rep.reference_ms = reference_ms;
  rep.extra = static_cast<unsigned long long>(extra);
  rep.window_diff = window_diff;
  rep.passes = adaptive_passes;
  print_report(a, platform, rep);
  glDeleteBuffers(1, &ubo);
  aa->reset();
  return 0;
}
