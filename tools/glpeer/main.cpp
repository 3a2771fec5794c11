// tessera-glpeer — renders a scene with OpenGL 4.5 core through EGL's surfaceless platform
// (Mesa llvmpipe on a machine without a GPU), as the peer of tessera's software rasterizer.
//
// Same inputs and conventions as `tessera render`: the scene loaders of tessera/scene.h, the
// camera of --camera / --orbit, an unlit shader (base colour factor x base-colour texture,
// sampled trilinear or 16x anisotropic with GL_REPEAT), sRGB textures decoded by the hardware
// path (GL_SRGB8_ALPHA8, glGenerateMipmap), colour accumulated in a multisampled RGBA32F
// buffer, resolved by glBlitFramebuffer (box filter in linear light) and encoded to sRGB on the
// CPU exactly as tessera encodes its own images. Timing covers clear, draw and resolve of each
// frame, ended by glFinish; the read-back is excluded.
#define GL_GLEXT_PROTOTYPES 1
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tessera/io.h"
#include "tessera/render.h"
#include "tessera/scene.h"

#ifndef EGL_PLATFORM_SURFACELESS_MESA
#define EGL_PLATFORM_SURFACELESS_MESA 0x31DD
#endif
#ifndef GL_TEXTURE_MAX_ANISOTROPY
#define GL_TEXTURE_MAX_ANISOTROPY 0x84FE
#endif

namespace {

using namespace tessera;

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

GLuint compile(GLenum type, const char* src, std::string& log) {
  GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char buf[2048];
    glGetShaderInfoLog(s, sizeof buf, nullptr, buf);
    log = buf;
  }
  return s;
}

struct GpuMesh {
  GLuint vao = 0, vbo = 0, ibo = 0;
  GLsizei count = 0;
  int material = 0;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Render a scene with OpenGL (Mesa llvmpipe) as the peer of `tessera render`",
               "tessera-glpeer"};
  std::string scene_path, out_path, camera_text, orbit_text, json_path, filter = "trilinear",
      shading = "textured";
  int width = 1024, height = 768, msaa = 1, frames = 1;
  app.add_option("SCENE", scene_path, "Scene file (.obj, .gltf, .glb) or 'builtin'")->required();
  app.add_option("--width", width)->check(CLI::Range(1, 8192));
  app.add_option("--height", height)->check(CLI::Range(1, 8192));
  app.add_option("--camera", camera_text, "eye,target,up,fov (10 numbers)");
  app.add_option("--orbit", orbit_text, "FRAME/N: camera on the scene's orbit");
  app.add_option("--msaa", msaa, "Samples per pixel (1, 2, 4, 8)")->check(CLI::IsMember({1, 2, 4, 8, 16}));
  app.add_option("--filter", filter)->check(CLI::IsMember({"trilinear", "aniso16"}));
  app.add_option("--shading", shading, "textured, or flat white (coverage only)")
      ->check(CLI::IsMember({"textured", "flat"}));
  app.add_option("--frames", frames, "Frames to time (same camera); the image is the last")
      ->check(CLI::Range(1, 10000));
  app.add_option("-o,--out", out_path, "Output PNG")->required();
  app.add_option("--json", json_path, "Write timings and details as JSON here ('-' = stdout)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return e.get_exit_code() == 0 ? 0 : 2;
  }

  Result<scene::Scene> loaded =
      scene_path == "builtin" ? Result<scene::Scene>(scene::builtin_scene()) : scene::load_scene(scene_path);
  if (!loaded) return fail(loaded.status().message);
  const scene::Scene& sc = *loaded;
  Result<scene::Camera> cam = scene::camera_from_text(sc, camera_text, orbit_text);
  if (!cam) {
    std::fprintf(stderr, "tessera-glpeer: %s\n", cam.status().message.c_str());
    return 2;
  }
  const scene::Camera camera = *cam;

  // EGL, surfaceless, OpenGL 4.5 core.
  EGLDisplay dpy = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, nullptr, nullptr)) {
    return fail("cannot open an EGL surfaceless display (install libegl-mesa0 libgl1-mesa-dri)");
  }
  eglBindAPI(EGL_OPENGL_API);
  const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext ctx = eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, ctx_attribs);
  if (ctx == EGL_NO_CONTEXT || !eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
    return fail("cannot create an OpenGL 4.5 core context through EGL");
  }
  const std::string renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));

  std::string log;
  GLuint vs = compile(GL_VERTEX_SHADER, kVertex, log);
  GLuint fs = compile(GL_FRAGMENT_SHADER, kFragment, log);
  if (!log.empty()) return fail("shader: " + log);
  GLuint prog = glCreateProgram();
  glAttachShader(prog, vs);
  glAttachShader(prog, fs);
  glLinkProgram(prog);
  glUseProgram(prog);

  // Textures.
  std::vector<GLuint> textures(sc.textures.size(), 0);
  for (std::size_t i = 0; i < sc.textures.size(); ++i) {
    const scene::Texture& t = sc.textures[i];
    glGenTextures(1, &textures[i]);
    glBindTexture(GL_TEXTURE_2D, textures[i]);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, t.srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, t.image.width,
                 t.image.height, 0, GL_RGBA, GL_UNSIGNED_BYTE, t.image.pixels.data());
    glGenerateMipmap(GL_TEXTURE_2D);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MAX_ANISOTROPY, filter == "aniso16" ? 16.0f : 1.0f);
  }
  // Meshes: interleaved position + uv.
  std::vector<GpuMesh> meshes;
  for (const scene::Mesh& m : sc.meshes) {
    GpuMesh g;
    std::vector<float> v;
    v.reserve(m.positions.size() * 5);
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
      v.insert(v.end(), {m.positions[i].x, m.positions[i].y, m.positions[i].z, m.uvs[i].x, m.uvs[i].y});
    }
    glGenVertexArrays(1, &g.vao);
    glBindVertexArray(g.vao);
    glGenBuffers(1, &g.vbo);
    glBindBuffer(GL_ARRAY_BUFFER, g.vbo);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(v.size() * sizeof(float)), v.data(), GL_STATIC_DRAW);
    glGenBuffers(1, &g.ibo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.ibo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(m.indices.size() * 4), m.indices.data(), GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 20, nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, 20, reinterpret_cast<void*>(12));
    g.count = GLsizei(m.indices.size());
    g.material = m.material;
    meshes.push_back(g);
  }

  // Framebuffers: multisampled RGBA32F + depth, resolved into single-sampled RGBA32F.
  GLuint ms_fbo = 0, ms_colour = 0, ms_depth = 0, fbo = 0, colour = 0;
  glGenFramebuffers(1, &ms_fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, ms_fbo);
  glGenRenderbuffers(1, &ms_colour);
  glBindRenderbuffer(GL_RENDERBUFFER, ms_colour);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, msaa > 1 ? msaa : 0, GL_RGBA32F, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, ms_colour);
  glGenRenderbuffers(1, &ms_depth);
  glBindRenderbuffer(GL_RENDERBUFFER, ms_depth);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, msaa > 1 ? msaa : 0, GL_DEPTH_COMPONENT32F, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, ms_depth);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    return fail("multisampled framebuffer incomplete (" + std::to_string(msaa) + " samples)");
  }
  GLint samples = 0;
  glGetIntegerv(GL_SAMPLES, &samples);
  glGenFramebuffers(1, &fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glGenRenderbuffers(1, &colour);
  glBindRenderbuffer(GL_RENDERBUFFER, colour);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA32F, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);

  const Mat4 vp = camera.view_projection(float(width) / float(height));
  glUniformMatrix4fv(glGetUniformLocation(prog, "view_projection"), 1, GL_FALSE, &vp.m[0][0]);
  glUniform1i(glGetUniformLocation(prog, "base_texture"), 0);
  const GLint loc_color = glGetUniformLocation(prog, "base_color");
  const GLint loc_has = glGetUniformLocation(prog, "has_texture");
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  if (msaa > 1) glEnable(GL_MULTISAMPLE);

  std::vector<double> times;
  for (int f = 0; f < frames; ++f) {
    const auto t0 = std::chrono::steady_clock::now();
    glBindFramebuffer(GL_FRAMEBUFFER, ms_fbo);
    glViewport(0, 0, width, height);
    glClearColor(render::kBackground[0], render::kBackground[1], render::kBackground[2], 1.0f);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glActiveTexture(GL_TEXTURE0);
    for (const GpuMesh& g : meshes) {
      const scene::Material& m = sc.materials[std::size_t(g.material)];
      const float white[4] = {1, 1, 1, 1};
      const bool flat = shading == "flat";
      glUniform4fv(loc_color, 1, flat ? white : m.base_color);
      const bool has = !flat && m.base_color_texture >= 0;
      glUniform1i(loc_has, has ? 1 : 0);
      if (has) glBindTexture(GL_TEXTURE_2D, textures[std::size_t(m.base_color_texture)]);
      glBindVertexArray(g.vao);
      glDrawElements(GL_TRIANGLES, g.count, GL_UNSIGNED_INT, nullptr);
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, ms_fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glFinish();
    times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  // Read back (bottom-up in GL) and encode like tessera does.
  std::vector<float> px(std::size_t(width) * std::size_t(height) * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, px.data());
  ImageRGBAF lin(width, height);
  for (int y = 0; y < height; ++y) {
    std::memcpy(lin.at(0, y), &px[std::size_t(height - 1 - y) * std::size_t(width) * 4],
                std::size_t(width) * 4 * sizeof(float));
  }
  const GLenum err = glGetError();
  if (err != GL_NO_ERROR) return fail("OpenGL error " + std::to_string(err));
  if (Status s = write_png(out_path, to_srgb8(lin)); !s.ok()) return fail(s.message);

  std::vector<double> sorted = times;
  std::sort(sorted.begin(), sorted.end());
  nlohmann::json j = {{"renderer", renderer},         {"width", width},
                      {"height", height},             {"msaa", msaa},
                      {"samples", samples},           {"filter", filter},
                      {"triangles", sc.triangle_count()}, {"frames", frames},
                      {"frame_ms", times},            {"median_ms", sorted[sorted.size() / 2]}};
  if (json_path == "-") {
    std::printf("%s\n", j.dump(2).c_str());
  } else if (!json_path.empty()) {
    const std::string text = j.dump(2) + "\n";
    if (Status s = write_file_atomic(json_path, {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()}); !s.ok()) {
      return fail(s.message);
    }
  }
  eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(dpy, ctx);
  eglTerminate(dpy);
  return 0;
}
