// engine_context_check — tessera's engine components on contexts tessera did not make.
//
// What an engine does: makes its own OpenGL 4.5 core context (a surfaceless EGL context, or a
// GLFW window through GLX), installs its own GL_KHR_debug callback and sets its own GL state,
// then runs gl::AdaptiveSupersampler (create, dispatch, dispatch_reference) and gl::FaceTextureSet
// (upload, bind, and its own draw calling tessera_seams_sample_discard). This program does that
// and prints one JSON object: FNV-1a hashes of the images (read back by the engine itself),
// whether the engine's debug callback, its user pointer and the GL state listed in tessera's
// headers survived, and the one-line errors of calls made with no context current.
//
// Usage: engine_context_check --context egl|glfw|tessera|both [--loader host|none] [--shift]
//   egl      the program's own EGL context          glfw  a GLFW window context (GLX)
//   tessera  a tessera gl::Context (the reference)  both  an EGL context and a gl::Context alive
//            at once, the components run on each in turn; "images" then lists both
//   --loader host  gl::load_entry_points(eglGetProcAddress / glfwGetProcAddress) (default);
//            none: no loader, tessera resolves its entry points on first use
//   --shift  moves the G-buffer and the face lookups by one texel (a negative control: the
//            hashes must change)
// Built in the repository (tests/gl, CTest gl_engine_context*) and outside it against the
// installed package (tests/install/install_test.sh). Exit 0 with the JSON; 1 with one line on
// failure; 3 when no context of the kind can be made (no EGL device, no display).
// The GL, EGL and GLFW headers as the example engines include them, and their shader
// compilation (examples/common/engine_context.h; its Platform is not used: this program makes
// its contexts itself, in more ways).
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "engine_context.h"
#include "tessera/core.h"
#include "tessera/faces.h"
#include "tessera/gl.h"
#include "tessera/gl_adaptive.h"
#include "tessera/gl_faces.h"
#include "tessera/glsl.h"

namespace {

constexpr int kW = 48, kH = 32, kM = 2;  // output pixels, window side

[[noreturn]] void die(int code, const std::string& msg) {
  std::fprintf(stderr, "engine_context_check: %s\n", msg.c_str());
  std::exit(code);
}

std::string hash_floats(GLuint texture, int w, int h) {
  std::vector<float> px(std::size_t(w) * std::size_t(h) * 4);
  glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, GLsizei(px.size() * 4), px.data());
  std::uint64_t x = 1469598103934665603ull;
  const auto* b = reinterpret_cast<const unsigned char*>(px.data());
  for (std::size_t i = 0; i < px.size() * 4; ++i) x = (x ^ b[i]) * 1099511628211ull;
  int distinct = 0;  // a blank image would hash equal everywhere: count its colours
  for (std::size_t i = 4; i < px.size() && distinct < 8; i += 4) distinct += px[i] != px[i - 4];
  char s[40];
  std::snprintf(s, sizeof s, "%016llx%s", static_cast<unsigned long long>(x),
                distinct < 8 ? "-flat" : "");
  return s;
}

// ---- the engine's contexts -------------------------------------------------------------------

struct EglContext {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  void make_current() const { eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context); }
  void release() const { eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT); }
  ~EglContext() {
    if (context == EGL_NO_CONTEXT) return;
    release();
    eglDestroyContext(display, context);
  }
};

std::unique_ptr<EglContext> make_egl() {
  auto e = std::make_unique<EglContext>();
  e->display = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (e->display == EGL_NO_DISPLAY || !eglInitialize(e->display, nullptr, nullptr)) {
    die(3, "no EGL surfaceless display");
  }
  eglBindAPI(EGL_OPENGL_API);
  const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                            4,
                            EGL_CONTEXT_MINOR_VERSION,
                            5,
                            EGL_CONTEXT_OPENGL_PROFILE_MASK,
                            EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                            EGL_CONTEXT_OPENGL_DEBUG,
                            EGL_TRUE,
                            EGL_NONE};
  e->context = eglCreateContext(e->display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
  if (e->context == EGL_NO_CONTEXT) die(3, "no OpenGL 4.5 core EGL context");
  e->make_current();
  return e;
}

// ---- the engine's debug callback and state ---------------------------------------------------

struct EngineDebug {
  int messages = 0;
};

void APIENTRY engine_callback(GLenum, GLenum, GLuint, GLenum, GLsizei, const GLchar*,
                              const void* user) {
  ++static_cast<EngineDebug*>(const_cast<void*>(user))->messages;
}

struct Snapshot {
  std::vector<GLint> ints;
  const void* callback = nullptr;
  const void* user = nullptr;
  bool operator==(const Snapshot& o) const {
    return ints == o.ints && callback == o.callback && user == o.user;
  }
};

// The state tessera's headers promise to leave alone (gl_adaptive.h: everything it touches is
// put back; gl_faces.h: upload changes nothing, bind only its units and storage binding).
Snapshot snapshot() {
  Snapshot s;
  for (GLenum e :
       {GL_CURRENT_PROGRAM, GL_ACTIVE_TEXTURE, GL_DRAW_FRAMEBUFFER_BINDING,
        GL_READ_FRAMEBUFFER_BINDING, GL_VERTEX_ARRAY_BINDING, GL_UNIFORM_BUFFER_BINDING,
        GL_SHADER_STORAGE_BUFFER_BINDING, GL_PIXEL_UNPACK_BUFFER_BINDING, GL_UNPACK_ALIGNMENT,
        GL_UNPACK_ROW_LENGTH, GL_PACK_ALIGNMENT, GL_DISPATCH_INDIRECT_BUFFER_BINDING,
        GL_DEBUG_OUTPUT, GL_DEBUG_OUTPUT_SYNCHRONOUS}) {
    GLint v = 0;
    glGetIntegerv(e, &v);
    s.ints.push_back(v);
  }
  GLint vp[4];
  glGetIntegerv(GL_VIEWPORT, vp);
  s.ints.insert(s.ints.end(), vp, vp + 4);
  GLint active = 0;
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
  for (GLenum unit : {GL_TEXTURE0, GL_TEXTURE1, GL_TEXTURE2}) {  // tessera's: 8.. and the top
    GLint t = 0;
    glActiveTexture(unit);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &t);
    s.ints.push_back(t);
  }
  glActiveTexture(GLenum(active));
  glGetPointerv(GL_DEBUG_CALLBACK_FUNCTION, const_cast<void**>(&s.callback));
  glGetPointerv(GL_DEBUG_CALLBACK_USER_PARAM, const_cast<void**>(&s.user));
  return s;
}

// Objects and state of the engine's own, set before tessera runs.
struct EngineState {
  GLuint program = 0, fbo = 0, tex = 0, vao = 0, ubo = 0, pbo = 0;
  EngineDebug debug;
  void set(bool install_callback) {
    if (install_callback) {
      glEnable(GL_DEBUG_OUTPUT);
      glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
      glDebugMessageCallback(engine_callback, &debug);
    }
    program = glCreateProgram();  // a linked program of the engine's, bound while tessera runs
    const char* cs = "#version 450 core\nlayout(local_size_x = 1) in;\nvoid main() {}\n";
    const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
    glShaderSource(shader, 1, &cs, nullptr);
    glCompileShader(shader);
    glAttachShader(program, shader);
    glLinkProgram(program);
    glDeleteShader(shader);
    glCreateFramebuffers(1, &fbo);
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, GL_RGBA8, 4, 4);
    glCreateVertexArrays(1, &vao);
    glCreateBuffers(1, &ubo);
    glNamedBufferStorage(ubo, 256, nullptr, 0);
    glCreateBuffers(1, &pbo);
    glNamedBufferStorage(pbo, 256, nullptr, 0);
    glUseProgram(program);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glBindVertexArray(vao);
    glActiveTexture(GL_TEXTURE2);
    glBindTextureUnit(1, tex);
    glBindBuffer(GL_UNIFORM_BUFFER, ubo);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, ubo);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, pbo);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 7);
    glPixelStorei(GL_PACK_ALIGNMENT, 2);
    glViewport(1, 2, 3, 4);
  }
  void unbind_for_own_work() const {  // the engine's own uploads and draws below
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  }
  void rebind() const {
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, pbo);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 7);
  }
};

// ---- the workload ----------------------------------------------------------------------------

const char* kHook = R"(
vec4 tessera_shade_sample(ivec2 g, float footprint) {
  int id = tessera_adaptive_id(g);
  if (id < 0) return vec4(0.1, 0.2, 0.3, 1.0);
  vec3 n = normalize(tessera_adaptive_normal(g));
  float checker = mod(floor(float(g.x) / 3.0) + floor(float(g.y) / 3.0), 2.0);
  return vec4((0.5 + 0.5 * n) * (0.4 + 0.6 * checker) * float(id), 1.0);
}
)";

struct Images {
  std::string adaptive, reference, faces;
  std::string state_error;  // the first state check that failed, "" when all held
};

// Two G-buffer textures: (normal, depth) and (id, 0, 0, 0): a sphere over a floor.
std::array<GLuint, 2> make_gbuffer(bool shift) {
  const int gw = kW * kM, gh = kH * kM;
  std::vector<float> t0(std::size_t(gw) * gh * 4), t1(std::size_t(gw) * gh * 4, 0.0f);
  for (int y = 0; y < gh; ++y) {
    for (int x = 0; x < gw; ++x) {
      const std::size_t i = (std::size_t(y) * gw + std::size_t(x)) * 4;
      const float px = float(x + (shift ? 1 : 0)) - 0.45f * gw, py = float(y) - 0.5f * gh;
      const float r = 0.3f * gh, d2 = px * px + py * py;
      if (d2 < r * r) {
        const float nz = std::sqrt(r * r - d2) / r;
        t0[i] = px / r, t0[i + 1] = py / r, t0[i + 2] = nz, t0[i + 3] = 5.0f - 2.0f * nz;
        t1[i] = 2.0f;
      } else {
        t0[i] = 0, t0[i + 1] = 1, t0[i + 2] = 0, t0[i + 3] = 8.0f + 0.01f * float(y);
        t1[i] = y < gh / 4 ? -1.0f : 1.0f;
      }
    }
  }
  std::array<GLuint, 2> tex{};
  glCreateTextures(GL_TEXTURE_2D, 2, tex.data());
  for (int k = 0; k < 2; ++k) {
    glTextureStorage2D(tex[std::size_t(k)], 1, GL_RGBA32F, gw, gh);
    glTextureSubImage2D(tex[std::size_t(k)], 0, 0, 0, gw, gh, GL_RGBA, GL_FLOAT,
                        (k == 0 ? t0 : t1).data());
  }
  return tex;
}

// The component's options on the program's G-buffer (its layout, its hook).
tessera::gl::AdaptiveSupersamplerOptions adaptive_options() {
  tessera::gl::AdaptiveSupersamplerOptions o;
  o.width = kW;
  o.height = kH;
  o.m = kM;
  o.layout.normal = {0, "rgb"};
  o.layout.depth = {0, "a"};
  o.layout.id = {1, "r"};
  o.hook = {kHook, "engine_hook.glsl", {}};
  return o;
}

void run_adaptive(Images& out, EngineState& engine, bool shift) {
  engine.unbind_for_own_work();
  const std::array<GLuint, 2> gbuffer = make_gbuffer(shift);
  engine.rebind();
  const Snapshot before = snapshot();
  tessera::gl::AdaptiveSupersamplerOptions o = adaptive_options();
  o.output = tessera::AdaptiveOutputFormat::rgba32f;
  auto aa = tessera::gl::AdaptiveSupersampler::create(o);
  if (!aa) die(1, aa.status().message);
  tessera::gl::AdaptiveFrame frame;
  frame.gbuffer = {gbuffer[0], gbuffer[1], 0, 0};
  auto r = (*aa)->dispatch(frame);
  if (!r) die(1, r.status().message);
  out.adaptive = hash_floats(r->colour, kW, kH);
  r = (*aa)->dispatch_reference(frame);
  if (!r) die(1, r.status().message);
  out.reference = hash_floats(r->colour, kW, kH);
  if (!(snapshot() == before) && out.state_error.empty()) {
    out.state_error = "AdaptiveSupersampler changed the engine's GL state";
  }
  aa->reset();
  glDeleteTextures(2, gbuffer.data());
}

// Four faces in a 2x2 grid, two resolutions (two classes), drawn by the engine's own fragment
// shader: face and UV from the pixel, tessera_seams_sample_discard across the shared edges.
tessera::faces::FaceTextureSet make_faces() {
  tessera::faces::QuadMesh mesh;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) mesh.positions.push_back({float(x), float(y), 0.0f});
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      const int a = y * 3 + x;
      mesh.quads.push_back({a, a + 1, a + 4, a + 3});
    }
  auto adjacency = tessera::faces::build_adjacency(mesh);
  if (!adjacency) die(1, adjacency.status().message);
  std::vector<tessera::ImageRGBAF> images;
  for (int f = 0; f < 4; ++f) {
    const int n = f % 2 == 0 ? 16 : 8;
    tessera::ImageRGBAF img(n, n);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        float* p = &img.pixels[(std::size_t(y) * n + std::size_t(x)) * 4];
        p[0] = float(x) / float(n), p[1] = float(y) / float(n), p[2] = 0.25f * float(f);
        p[3] = 1.0f;
      }
    images.push_back(std::move(img));
  }
  auto set = tessera::faces::FaceTextureSet::create(images, std::move(*adjacency));
  if (!set) die(1, set.status().message);
  return std::move(*set);
}

const char* kFacesFs = R"(#version 450 core
#include "seams.glsl"
uniform float shift;
layout(location = 0) out vec4 colour;
void main() {
  vec2 p = (gl_FragCoord.xy + vec2(shift, 0.0)) / vec2(32.0);  // 2x2 faces of 32x32 pixels
  int face = clamp(int(p.x), 0, 1) + 2 * clamp(int(p.y), 0, 1);
  vec2 uv = fract(p);
  colour = tessera_seams_sample_discard(face, uv, vec2(1.0 / 32.0, 0.0), vec2(0.0, 1.0 / 32.0),
                                        true);
})";
const char* kFacesVs = R"(#version 450 core
void main() {
  vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
  gl_Position = vec4(p, 0.0, 1.0);
})";

GLuint compile_program(const char* vs, const char* fs) {
  std::string log;
  const GLuint p = engine::compile_program(vs, fs, log);
  if (p == 0) die(1, "engine shader: " + log);
  return p;
}

void run_faces(Images& out, EngineState& engine, bool shift) {
  const tessera::faces::FaceTextureSet set = make_faces();
  const Snapshot before = snapshot();
  auto tex = tessera::gl::FaceTextureSet::upload(set);
  if (!tex) die(1, tex.status().message);
  if (!(snapshot() == before) && out.state_error.empty()) {
    out.state_error = "FaceTextureSet::upload changed the engine's GL state";
  }
  tessera::gl::FaceTextureSetBindings b;
  b.border_unit = 8;
  b.clamp_unit = 12;
  b.records_binding = 5;
  // The engine compiles its own shader: tessera gives the full source (seams.glsl from the
  // copy embedded in the library, no file read).
  tessera::glsl::ExpandOptions eo;
  eo.preamble = tex->glsl_defines(b);
  auto fs =
      tessera::glsl::expand_includes({tessera::glsl::Stage::fragment, kFacesFs, "faces.frag"}, eo);
  if (!fs) die(1, fs.status().message);
  const GLuint program = compile_program(kFacesVs, fs->text.c_str());
  if (tessera::Status s = tex->bind(b); !s.ok()) die(1, s.message);
  if (!(snapshot() == before) && out.state_error.empty()) {
    out.state_error = "FaceTextureSet::bind changed state beyond its binding points";
  }
  // The engine's draw: its own target and vertex array, tessera's lookup in its shader.
  GLuint target = 0, fbo = 0, vao = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &target);
  glTextureStorage2D(target, 1, GL_RGBA32F, 64, 64);
  glCreateFramebuffers(1, &fbo);
  glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, target, 0);
  glCreateVertexArrays(1, &vao);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glViewport(0, 0, 64, 64);
  glUseProgram(program);
  glUniform1f(glGetUniformLocation(program, "shift"), shift ? 1.0f : 0.0f);
  glBindVertexArray(vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  out.faces = hash_floats(target, 64, 64);
  glBindFramebuffer(GL_FRAMEBUFFER, engine.fbo);
  glViewport(1, 2, 3, 4);
  glUseProgram(engine.program);
  glBindVertexArray(engine.vao);
  // The binding points the engine gave tessera, cleared by the engine (multi-bind: the generic
  // bindings stay) before the objects go: Mesa's glDeleteBuffers on a buffer still bound at an
  // indexed point clears it as glBindBufferBase would, the generic binding included.
  glBindTextures(8, 8, nullptr);
  glBindSamplers(8, 8, nullptr);
  glBindBuffersBase(GL_SHADER_STORAGE_BUFFER, 5, 1, nullptr);
  glDeleteTextures(1, &target);
  glDeleteFramebuffers(1, &fbo);
  glDeleteVertexArrays(1, &vao);
  glDeleteProgram(program);
}

// Both components on the current context, with the engine's state set first (and its debug
// callback when `callback`); the engine's callback must still be the one installed and fire.
Images run_all(bool shift, bool callback) {
  Images out;
  EngineState engine;
  engine.set(callback);
  const Snapshot before = snapshot();
  run_adaptive(out, engine, shift);
  run_faces(out, engine, shift);
  if (const Snapshot after = snapshot(); !(after == before) && out.state_error.empty()) {
    out.state_error = "engine state lost";
    for (std::size_t i = 0; i < after.ints.size(); ++i) {
      if (after.ints[i] != before.ints[i]) {
        out.state_error += ' ';
        out.state_error += std::to_string(i);
      }
    }
  }
  if (callback) {
    const int seen = engine.debug.messages;
    glBindTextureUnit(0, 0xFFFFFFu);  // an error of the engine's own: its callback must see it
    while (glGetError() != GL_NO_ERROR) {
    }
    if (engine.debug.messages <= seen && out.state_error.empty()) {
      out.state_error = "the engine's debug callback no longer receives messages";
    }
    glDebugMessageCallback(nullptr, nullptr);
  }
  return out;
}

std::string json_images(const Images& i) {
  return "{\"adaptive\": \"" + i.adaptive + "\", \"reference\": \"" + i.reference +
         "\", \"faces\": \"" + i.faces + "\", \"state_error\": \"" + i.state_error + "\"}";
}

// Calls with no context current: each must fail with one line.
std::string no_context_errors() {
  std::string all;
  tessera::gl::AdaptiveSupersamplerOptions o = adaptive_options();
  auto aa = tessera::gl::AdaptiveSupersampler::create(o);
  all += aa ? std::string("created without a context") : aa.status().message;
  auto tex = tessera::gl::FaceTextureSet::upload(make_faces());
  all += '|';
  all += tex ? std::string("uploaded without a context") : tex.status().message;
  all += '|';
  all += tessera::gl::check_errors("check_errors").message;
  for (char& c : all) {
    if (c == '"' || c == '\\') c = '\'';
  }
  return all;
}

}  // namespace

int main(int argc, char** argv) {
  std::string context, loader = "host";
  bool shift = false;
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    if (k == "--context" && i + 1 < argc) {
      context = argv[++i];
    } else if (k == "--loader" && i + 1 < argc) {
      loader = argv[++i];
    } else if (k == "--shift") {
      shift = true;
    } else {
      die(1, "unknown argument " + k);
    }
  }
  if (loader != "host" && loader != "none") die(1, "--loader " + loader + ": host or none");
  std::string images, errors;
  if (context == "egl") {
    auto egl = make_egl();
    if (loader == "host") {
      if (auto s = tessera::gl::load_entry_points(eglGetProcAddress); !s.ok()) die(1, s.message);
    }
    images = json_images(run_all(shift, true));
    egl->release();
    errors = no_context_errors();
  } else if (context == "glfw") {
#if ENGINE_HAVE_GLFW
    if (!glfwInit()) die(3, "no window system for GLFW");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
    glfwWindowHint(GLFW_CONTEXT_CREATION_API, GLFW_NATIVE_CONTEXT_API);
    GLFWwindow* window = glfwCreateWindow(64, 64, "engine_context_check", nullptr, nullptr);
    if (window == nullptr) die(3, "no OpenGL 4.5 core GLFW window");
    glfwMakeContextCurrent(window);
    if (loader == "host") {
      if (auto s = tessera::gl::load_entry_points(glfwGetProcAddress); !s.ok()) die(1, s.message);
    }
    images = json_images(run_all(shift, true));
    glfwMakeContextCurrent(nullptr);
    errors = no_context_errors();
    glfwDestroyWindow(window);
    glfwTerminate();
#else
    die(3, "built without GLFW");
#endif
  } else if (context == "tessera") {
    auto ctx = tessera::gl::Context::create();
    if (!ctx) die(3, ctx.status().message);
    images = json_images(run_all(shift, false));
  } else if (context == "both") {
    auto egl = make_egl();  // the engine's, made first
    if (auto s = tessera::gl::load_entry_points(eglGetProcAddress); !s.ok()) die(1, s.message);
    auto ctx = tessera::gl::Context::create();  // current now
    if (!ctx) die(3, ctx.status().message);
    const std::string on_tessera = json_images(run_all(shift, false));
    egl->make_current();  // the engine's again, with the gl::Context alive
    const std::string on_engine = json_images(run_all(shift, true));
    if (tessera::Status s = (*ctx)->make_current(); !s.ok()) die(1, s.message);
    const std::string again = json_images(run_all(shift, false));
    images = "[" + on_tessera + ", " + on_engine + ", " + again + "]";
  } else {
    die(1, "--context egl|glfw|tessera|both");
  }
  std::printf("{\"context\": \"%s\", \"loader\": \"%s\", \"images\": %s, \"no_context\": \"%s\"}\n",
              context.c_str(), loader.c_str(), images.c_str(), errors.c_str());
  return 0;
}
