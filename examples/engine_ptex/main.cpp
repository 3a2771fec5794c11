// engine_ptex — a small forward renderer that draws a Ptex mesh with its own shader and
// tessera's seamless per-face lookup (seams.glsl, tessera_seams_sample_discard: Toth 2013).
//
// The engine side is all here and all its own: an OpenGL 4.5 core context it makes itself (a GLFW
// window through GLX, or with --headless a surfaceless EGL context: examples/common/
// engine_context.h, which also hands the context's GetProcAddress to tessera), GL entry points
// from libOpenGL, an interleaved
// vertex layout (position, normal, per-face UV, integer face id), a per-frame uniform block at
// binding 0 (view-projection, light), its own framebuffer, and a vertex and fragment shader
// written below. The integration with tessera follows the recipe of tessera/gl_faces.h and is the
// blocks marked "tessera": mesh and textures from the .obj and .ptx, one upload, the binding
// points the engine chose (FaceTextureSetBindings) as shader defines and as one bind per frame.
//
// Usage: engine_ptex MESH.obj FILE.ptx [--headless] [--size WxH] [--orbit K/N] [--fov DEG]
// [--shader-method
//                    discard|clamp] [--shift-px X] [--glsl DIR] [--check] [--json] [-o FILE.png]
//   --headless        a surfaceless EGL context instead of the window (the image is the same;
//                     in the window the frame is shown, and --json reports "window_max_diff",
//                     the largest byte difference between the back buffer and the -o image)
//   -o FILE.png       the GL image (8-bit sRGB)
//   --orbit K/N       the camera: frame K of N of faces::face_orbit_camera (default 1/8)
//   --fov DEG         its vertical field of view (default the orbit's 60; smaller zooms in)
//   --check           also renders the same frame with tessera's CPU renderer
//                     (faces::FaceRenderer: Discard, trilinear, same camera, resolution and
//                     lighting) and prints the agreement: PSNR of the 8-bit sRGB images and the
//                     fraction of pixels whose linear-RGB 2-norm difference is >= 0.01
//   --json            one JSON object (with the agreement: --json implies --check; psnr_db
//                     is null when the 8-bit images are identical)
//   --shader-method   the engine shader's lookup (clamp: the seam-artefact baseline); the CPU
//                     frame stays Discard, so clamp measures how much the seams matter
//   --shift-px X      moves the GL camera's image X pixels to the right (the CPU frame stays)
// The last two are negative controls for the agreement bounds (tests/gl/engine_ptex_test.py).
// Exit 1 with one line when there is no OpenGL 4.5 device, on bad arguments or input (a mesh
// polygon the Ptex file did not split into quads is named).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "engine_context.h"  // first: the engine's GL and window headers
#include "ptex_report.h"  // examples/common: the flags, vertex, frame block and CPU check of both
#include "tessera/core.h"
#include "tessera/faces.h"
#include "tessera/gl.h"
#include "tessera/gl_faces.h"
#include "tessera/glsl.h"
#include "tessera/io.h"
#include "tessera/ptex.h"

namespace {

// The flags of engine_ptex_vk too (ptex_report.h), and the GL engine's own.
struct Args : engine::PtexArgs {
  std::string glsl, method = "discard";
  float fov = 0.0f;  // 0: the orbit camera's
  bool check = false, headless = false;
};

int fail(const std::string& msg) {
  std::fprintf(stderr, "engine_ptex: %s\n", msg.c_str());
  return 1;
}

// The engine's vertex (ptex_report.h): 4 per Ptex face (corners are not shared: each face has
// its own UVs); its per-frame block (std140, binding 0).
using Vertex = engine::FaceVertex;
using FrameBlock = engine::ForwardFrameBlock;

const char* kVertexShader = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec2 face_uv;
layout(location = 3) in int face_id;
layout(std140, binding = 0) uniform Frame {
  mat4 view_proj;
  vec4 light_dir;
  vec4 shade;
};
out vec3 v_normal;
out vec2 v_uv;
flat out int v_face;
void main() {
  v_normal = normal;
  v_uv = face_uv;
  v_face = face_id;
  gl_Position = view_proj * vec4(position, 1.0);
}
)";

// The defines of FaceTextureSet::glsl_defines go after #version (glsl::ExpandOptions::preamble).
const char* kFragmentShader = R"(#version 450 core
#include "seams.glsl"
layout(std140, binding = 0) uniform Frame {
  mat4 view_proj;
  vec4 light_dir;
  vec4 shade;
};
in vec3 v_normal;
in vec2 v_uv;
flat in int v_face;
layout(location = 0) out vec4 colour;
void main() {
  // Explicit fine gradients: the lookups sit in non-uniform control flow (a class per face).
  vec2 dx = dFdxFine(v_uv), dy = dFdyFine(v_uv);
#if ENGINE_CLAMP
  vec4 tex = tessera_seams_sample_clamp(v_face, v_uv, dx, dy);
#else
  vec4 tex = tessera_seams_sample_discard(v_face, v_uv, dx, dy, true);
#endif
  float nl = dot(v_normal, light_dir.xyz) / sqrt(dot(v_normal, v_normal) + 1e-20);
  colour = vec4(tex.rgb * (shade.x + shade.y * max(nl, 0.0)), 1.0);
}
)";

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// The engine's GPU objects: vertex, index and frame buffers, vertex array, an RGBA32F colour
// target with depth.
struct EngineObjects {
  GLuint vbo = 0, ibo = 0, ubo = 0, vao = 0, fbo = 0, colour_tex = 0, depth_rb = 0;
  ~EngineObjects() {
    glDeleteBuffers(1, &vbo);
    glDeleteBuffers(1, &ibo);
    glDeleteBuffers(1, &ubo);
    glDeleteVertexArrays(1, &vao);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(1, &depth_rb);
    glDeleteTextures(1, &colour_tex);
  }
};

// Creates them for a w x h frame; "" or the problem.
std::string create_objects(EngineObjects& o, const std::vector<Vertex>& verts,
                           const std::vector<std::uint32_t>& indices, const FrameBlock& frame,
                           int w, int h) {
  glCreateBuffers(1, &o.vbo);
  glNamedBufferStorage(o.vbo, GLsizeiptr(verts.size() * sizeof(Vertex)), verts.data(), 0);
  glCreateBuffers(1, &o.ibo);
  glNamedBufferStorage(o.ibo, GLsizeiptr(indices.size() * 4), indices.data(), 0);
  glCreateBuffers(1, &o.ubo);
  glNamedBufferStorage(o.ubo, sizeof frame, &frame, 0);
  glCreateVertexArrays(1, &o.vao);
  glVertexArrayVertexBuffer(o.vao, 0, o.vbo, 0, sizeof(Vertex));
  glVertexArrayElementBuffer(o.vao, o.ibo);
  const GLuint sizes[3] = {3, 3, 2}, offsets[3] = {0, 12, 24};
  for (GLuint i = 0; i < 3; ++i) {
    glEnableVertexArrayAttrib(o.vao, i);
    glVertexArrayAttribFormat(o.vao, i, GLint(sizes[i]), GL_FLOAT, GL_FALSE, offsets[i]);
    glVertexArrayAttribBinding(o.vao, i, 0);
  }
  glEnableVertexArrayAttrib(o.vao, 3);
  glVertexArrayAttribIFormat(o.vao, 3, 1, GL_INT, offsetof(Vertex, face));
  glVertexArrayAttribBinding(o.vao, 3, 0);
  glCreateTextures(GL_TEXTURE_2D, 1, &o.colour_tex);
  glTextureStorage2D(o.colour_tex, 1, GL_RGBA32F, w, h);
  glCreateRenderbuffers(1, &o.depth_rb);
  glNamedRenderbufferStorage(o.depth_rb, GL_DEPTH_COMPONENT32F, w, h);
  glCreateFramebuffers(1, &o.fbo);
  glNamedFramebufferTexture(o.fbo, GL_COLOR_ATTACHMENT0, o.colour_tex, 0);
  glNamedFramebufferRenderbuffer(o.fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, o.depth_rb);
  if (glCheckNamedFramebufferStatus(o.fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    return "framebuffer " + std::to_string(w) + "x" + std::to_string(h) + " incomplete";

  return "";
}

// The report; with --check the same frame through tessera's CPU renderer (Discard, trilinear)
// and the agreement of the two. 0, or 1 with the problem on stderr.
int report(const Args& a, const engine::Platform& platform, const tessera::faces::FaceScene& scene,
           const tessera::faces::FaceTextureSet& set, const tessera::scene::Camera& camera,
           const tessera::ImageRGBAF& img, int classes, double gl_ms, int window_diff) {
  if (a.check) {
    auto agree = engine::cpu_agreement(scene, set, camera, img);
    if (!agree) return fail(agree.status().message);
    if (a.json) {
      const std::string psnr_json = engine::psnr_text(agree->psnr, true);
      std::printf(
          "{\"device\": \"%s\", \"mesh\": \"%s\", \"faces\": %d, \"classes\": %d, "
          "\"width\": %d, \"height\": %d, \"orbit\": \"%d/%d\", \"shader_method\": \"%s\", "
          "\"shift_px\": %.3f, \"psnr_db\": %s, \"frac_001\": %.6f, \"max_norm\": %.4f, "
          "\"non_finite\": %d, \"gl_ms\": %.3f, \"cpu_ms\": %.3f, \"context\": \"%s\"%s}\n",
          platform.renderer().c_str(), scene.name.c_str(), scene.mesh.face_count(), classes, a.w,
          a.h, a.orbit_k, a.orbit_n, a.method.c_str(), double(a.shift_px), psnr_json.c_str(),
          agree->frac_001, agree->max_norm, agree->non_finite, gl_ms, agree->cpu_ms,
          platform.kind(),
          window_diff >= 0 ? (", \"window_max_diff\": " + std::to_string(window_diff)).c_str()
                           : "");
    } else {
      std::printf(
          "engine_ptex %dx%d, %d faces in %d classes: GL (%s) vs CPU Discard: PSNR %.2f dB, "
          "%.3f %% of the pixels >= 0.01 apart\n",
          a.w, a.h, scene.mesh.face_count(), classes, a.method.c_str(), agree->psnr,
          100.0 * agree->frac_001);
    }
  } else {
    std::printf("engine_ptex %dx%d, %d faces in %d classes: drawn in %.1f ms\n", a.w, a.h,
                scene.mesh.face_count(), classes, gl_ms);
  }

  return 0;
}

// The command line; "" or the problem.
std::string parse_args(int argc, char** argv, Args& a) {
  engine::CommandLine cl;
  engine::add_ptex_flags(cl, a);
  cl.option("--shader-method", [&a](const std::string& v) -> std::string {
    a.method = v;
    return v == "discard" || v == "clamp" ? "" : "--shader-method " + v + ": discard or clamp";
  });
  cl.option("--fov", [&a](const std::string& v) -> std::string {
    a.fov = std::strtof(v.c_str(), nullptr);
    return a.fov > 0.0f && a.fov < 180.0f ? "" : "--fov: degrees in (0, 180)";
  });
  cl.option("--glsl", [&a](const std::string& v) -> std::string {
    a.glsl = v;
    return "";
  });
  cl.flag("--headless", &a.headless);
  cl.flag("--check", &a.check);
  std::string why = engine::parse_ptex_args(cl, argc, argv, a, "engine_ptex");
  a.check = a.check || a.json;  // --json implies --check
  return why;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  if (std::string why = parse_args(argc, argv, a); !why.empty()) return fail(why);

  // ---- tessera, step 1 (pure; ptex_report.h, as engine_ptex_vk): the quad faces of the Ptex
  // file and their textures ----
  auto loaded = engine::load_ptex_scene(a);
  if (!loaded) return fail(loaded.status().message);
  const tessera::faces::FaceScene& scene = loaded->scene;
  const tessera::faces::FaceTextureSet& set = loaded->set;
  // ---- end of step 1 ----

  // The engine's context, current from here on; tessera's entry points loaded from it.
  engine::Platform platform;
  if (std::string why = platform.open(a.headless, a.w, a.h, "engine_ptex"); !why.empty())
    return fail("no OpenGL 4.5 device: " + why);

  // The engine's scene data: a camera on an orbit, smooth normals, 4 vertices and 2 triangles
  // per face (tessera's helpers for both, so the CPU check sees the same geometry).
  tessera::scene::Camera camera = tessera::faces::face_orbit_camera(scene, a.orbit_k, a.orbit_n);
  if (a.fov > 0.0f) camera.fov_y_degrees = a.fov;
  std::vector<Vertex> verts;
  std::vector<std::uint32_t> indices;
  engine::face_vertices(scene.mesh, verts, indices);
  // The camera moved `shift_px` pixels right, the light.
  const FrameBlock frame = engine::forward_frame_block(camera, a.w, a.h, a.shift_px);

  // ---- tessera, step 2: upload once; the binding points are the engine's choice ----
  tessera::gl::FaceTextureSetOptions to;
  to.max_anisotropy = 1.0f;  // trilinear: the filter the CPU check uses
  auto tex = tessera::gl::FaceTextureSet::upload(set, to);
  if (!tex) return fail(tex.status().message);
  tessera::gl::FaceTextureSetBindings bindings;
  bindings.border_unit = 1;  // unit 0 stays free for the engine's own textures
  bindings.clamp_unit = 17;  // after at most 16 classes
  bindings.records_binding = 3;
  // The engine compiles its own program; tessera gives the full fragment source: the defines
  // after #version and seams.glsl in place of the #include (from the copy embedded in the
  // library; --glsl DIR reads a development folder instead).
  tessera::glsl::ExpandOptions so;
  if (!a.glsl.empty()) so.shipped_dir = a.glsl;
  so.preamble = tex->glsl_defines(bindings);
  so.preamble.push_back(std::string("#define ENGINE_CLAMP ") + (a.method == "clamp" ? "1" : "0"));
  auto fragment = tessera::glsl::expand_includes(
      {tessera::glsl::Stage::fragment, kFragmentShader, "engine_ptex.frag"}, so);
  if (!fragment) return fail(fragment.status().message);
  std::string log;
  const GLuint program = engine::compile_program(kVertexShader, fragment->text.c_str(), log);
  if (program == 0) return fail(tessera::glsl::format_log(log, fragment->files));
  // ---- end of step 2 ----

  EngineObjects obj;
  if (std::string why = create_objects(obj, verts, indices, frame, a.w, a.h); !why.empty())
    return fail(why);
  const GLuint fbo = obj.fbo, ubo = obj.ubo, vao = obj.vao, colour_tex = obj.colour_tex;

  // ---- the frame ----
  const auto t0 = std::chrono::steady_clock::now();
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glViewport(0, 0, a.w, a.h);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_CULL_FACE);  // counter-clockwise front faces, back faces culled (as the CPU)
  const float background[4] = {tessera::faces::kFaceBackground[0],
                               tessera::faces::kFaceBackground[1],
                               tessera::faces::kFaceBackground[2], 0.0f};
  const float far_depth = 1.0f;
  glClearNamedFramebufferfv(fbo, GL_COLOR, 0, background);
  glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &far_depth);
  glUseProgram(program);
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, ubo);
  if (auto s = tex->bind(bindings); !s.ok()) return fail(s.message);  // tessera, per frame
  glBindVertexArray(vao);
  glDrawElements(GL_TRIANGLES, GLsizei(indices.size()), GL_UNSIGNED_INT, nullptr);
  glFinish();
  const double gl_ms = ms_since(t0);
  if (GLenum e = glGetError(); e != GL_NO_ERROR) return fail("GL error " + std::to_string(e));

  // Read back; GL's row 0 is the bottom, tessera's images are top-down.
  tessera::ImageRGBAF img(a.w, a.h);
  std::vector<float> rows(img.pixels.size());
  glGetTextureImage(colour_tex, 0, GL_RGBA, GL_FLOAT, GLsizei(rows.size() * 4), rows.data());
  const std::size_t row = std::size_t(a.w) * 4;
  for (int y = 0; y < a.h; ++y) {
    std::copy_n(rows.data() + std::size_t(a.h - 1 - y) * row, row,
                img.pixels.data() + std::size_t(y) * row);
  }
  const tessera::ImageRGBA8 srgb = tessera::to_srgb8(img);
  int window_diff = -1;  // the frame in the window (sRGB encoded by the engine's present pass)
  if (platform.windowed()) {
    std::vector<std::uint8_t> shown;
    platform.present(colour_tex, a.w, a.h, false, false, shown);
    window_diff = engine::max_rgb_difference(shown, srgb.pixels.data());
  }
  if (!a.out.empty()) {
    if (auto s = tessera::io::write_png(a.out, srgb); !s.ok()) return fail(s.message);
  }

  if (int rc = report(a, platform, scene, set, camera, img, tex->class_count(), gl_ms, window_diff);
      rc != 0)
    return rc;
  glDeleteProgram(program);
  return 0;
}
