// gl::AdaptiveSupersampler against gl::DeferredRenderer on the same frame: gl::DeferredRenderer
// renders its G-buffer, shades it adaptively (itself through a component whose hook keeps S's light
// terms for sample 0 again), and a component shades the same G-buffer textures with
// gl::DeferredRenderer's Blinn-Phong (deferred_shading.glsl) as a plain hook. Prints one JSON line
// per method: samples %, whether the image equals gl::DeferredRenderer's bit for bit, and the
// per-pass host times (dispatch to the end of a glFinish; medians over the timed frames).
//
// Usage: aa_gl_component [--scene FILE.gltf] [--size WxH] [--m M] [--frames N] [--heavy]
//                        [--budget-fraction F]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "gl/gl_api.h"
#include "tessera/deferred.h"
#include "tessera/gl.h"
#include "tessera/gl_adaptive.h"
#include "tessera/gl_deferred.h"
#include "tessera/scene.h"

namespace {

using namespace tessera;
using namespace tessera::gl::api;

int fail(const std::string& m) {
  std::fprintf(stderr, "aa_gl_component: %s\n", m.c_str());
  return 1;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

/// Median per pass name over frames, in first-frame order; "budget*" passes summed per frame.
std::string passes_json(const std::vector<std::vector<PassTime>>& frames, double* total) {
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> ms;
  for (const auto& f : frames) {
    std::map<std::string, double> sum;
    for (const PassTime& p : f) {
      const std::string name = p.pass.rfind("budget_", 0) == 0 ? "budget" : p.pass;
      if (std::find(order.begin(), order.end(), name) == order.end()) order.push_back(name);
      sum[name] += p.wall_ms;
    }
    for (const auto& [k, v] : sum) ms[k].push_back(v);
  }
  std::string s = "{";
  *total = 0;
  for (const std::string& n : order) {
    const double m = median(ms[n]);
    *total += m;
    char b[96];
    std::snprintf(b, sizeof b, "%s\"%s\": %.2f", s.size() > 1 ? ", " : "", n.c_str(), m);
    s += b;
  }
  return s + "}";
}

struct Args {
  std::string scene_path;
  int w = 320, h = 240, m = 4, frames = 3;
  bool heavy = false;
  double budget_fraction = 0.5;
};

/// Parses the command line into `a`; the unknown word in `bad` when there is one.
bool parse(int argc, char** argv, Args& a, std::string& bad) {
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    if (i + 1 < argc && k == "--scene")
      a.scene_path = argv[++i];
    else if (i + 1 < argc && k == "--size")
      std::sscanf(argv[++i], "%dx%d", &a.w, &a.h);
    else if (i + 1 < argc && k == "--m")
      a.m = std::atoi(argv[++i]);
    else if (i + 1 < argc && k == "--frames")
      a.frames = std::max(1, std::atoi(argv[++i]));
    else if (i + 1 < argc && k == "--budget-fraction")
      a.budget_fraction = std::atof(argv[++i]);
    else if (k == "--heavy")
      a.heavy = true;
    else {
      bad = k;
      return false;
    }
  }
  return true;
}

/// gl::DeferredRenderer leaves its G-buffer textures on units 0..2 and its texture arrays on
/// 3.. bound: the G-buffer into `frame`, the number of texture classes returned.
int bound_gbuffer(gl::AdaptiveFrame& frame) {
  int classes = 0;
  for (int u = 0; u < 11; ++u) {
    glActiveTexture(GLenum(GL_TEXTURE0 + u));
    GLint name = 0;
    glGetIntegerv(u < 3 ? GL_TEXTURE_BINDING_2D : GL_TEXTURE_BINDING_2D_ARRAY, &name);
    if (u < 3)
      frame.gbuffer[std::size_t(u)] = GLuint(name);
    else if (name != 0 && classes == u - 3)
      ++classes;
  }
  glActiveTexture(GL_TEXTURE0);
  return classes;
}

/// The component on gl::DeferredRenderer's G-buffer layout with its Blinn-Phong as the hook.
gl::AdaptiveSupersamplerOptions component_options(const Args& a, AdaptiveSchedule schedule,
                                                  int classes) {
  gl::AdaptiveSupersamplerOptions o;
  o.width = a.w;
  o.height = a.h;
  o.m = a.m;
  o.schedule = schedule;
  o.output = AdaptiveOutputFormat::rgba32f;
  o.glsl_dir = TESSERA_GLSL_DIR;
  o.profile = true;
  o.layout.depth = {0, "r"};
  o.layout.normal = {0, "gba"};
  o.layout.id = {1, "r"};
  o.layout.uv = {1, "gb"};
  o.layout.uv_derivatives = {2, "rgba"};
  o.hook.name = "blinn_phong";
  o.hook.source = "#define TESSERA_DEFERRED_CLASSES " + std::to_string(std::max(classes, 1)) +
                  "\n#include \"deferred_shading.glsl\"\nvec4 tessera_shade_sample(ivec2 g, "
                  "float f) { return vec4(tessera_shade(g, f), 1.0); }\n";
  return o;
}

/// One JSON line: `method`'s samples %, whether its image is the renderer's (`same`: -1 for
/// not compared) and the median pass times.
void print_method(const Args& a, const char* method,
                  const std::vector<std::vector<PassTime>>& times, std::uint64_t extra,
                  long long budget, long long same) {
  const std::size_t pixels = std::size_t(a.w) * std::size_t(a.h);
  double total = 0;
  const std::string passes = passes_json(times, &total);
  std::printf(
      "{\"method\": \"%s\", \"width\": %d, \"height\": %d, \"m\": %d, \"heavy\": %s, "
      "\"budget\": %lld, \"samples_percent\": %.2f, \"same_image\": %s, "
      "\"total_ms\": %.2f, \"passes_ms\": %s}\n",
      method, a.w, a.h, a.m, a.heavy ? "true" : "false", budget,
      100.0 * double(pixels + extra) / double(pixels * std::size_t(a.m * a.m)),
      same < 0 ? "null" : (same ? "true" : "false"), total, passes.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  if (std::string bad; !parse(argc, argv, a, bad)) return fail("unknown argument " + bad);
  const int w = a.w, h = a.h, m = a.m, frames = a.frames;
  auto ctx = gl::Context::create();
  if (!ctx) return fail("no OpenGL 4.5 device: " + ctx.status().message);
  scene::Scene sc;
  if (a.scene_path.empty()) {
    sc = scene::builtin_scene();
  } else {
    auto l = scene::load_scene(a.scene_path);
    if (!l) return fail(l.status().message);
    sc = std::move(*l);
  }
  const scene::Camera cam = scene::orbit_camera(sc, 1, 8);
  gl::DeferredRendererOptions go;
  go.glsl_dir = TESSERA_GLSL_DIR;
  auto dgl = gl::DeferredRenderer::create(sc, go);
  if (!dgl) return fail(dgl.status().message);
  if (Status s = (*dgl)->render_gbuffer(cam, w, h, m); !s.ok()) return fail(s.message);
  deferred::ShadingOptions shading = deferred::scene_shading(sc, 8, &cam);
  shading.heavy = a.heavy;
  shading.heavy_terms = 256;

  // gl::DeferredRenderer: warm-up, then timed frames.
  std::vector<std::vector<PassTime>> dgl_frames;
  deferred::ShadeResult dgl_result;
  for (int f = 0; f <= frames; ++f) {
    Result<deferred::ShadeResult> r = (*dgl)->shade_adaptive(shading, AdaptiveThresholds{});
    if (!r) return fail(r.status().message);
    if (f > 0) dgl_frames.push_back(r->passes);
    dgl_result = std::move(*r);
  }
  const deferred::ShadeResult* ref = &dgl_result;
  gl::AdaptiveFrame frame;
  const int classes = bound_gbuffer(frame);
  std::uint64_t asked = 0;
  for (std::uint8_t c : ref->samples) asked += c - 1u;
  print_method(a, "DeferredRenderer", dgl_frames, asked, -1, -1);

  const struct {
    const char* name;
    AdaptiveSchedule schedule;
    bool budget;
  } runs[] = {{"component frame_list", AdaptiveSchedule::frame_list, false},
              {"component tile_list", AdaptiveSchedule::tile_list, false},
              {"component loop", AdaptiveSchedule::loop, false},
              {"component frame_list, budget", AdaptiveSchedule::frame_list, true}};
  for (const auto& run : runs) {
    auto c = gl::AdaptiveSupersampler::create(component_options(a, run.schedule, classes));
    if (!c) return fail(c.status().message);
    frame.budget.reset();
    if (run.budget) frame.budget = std::int64_t(double(asked) * a.budget_fraction);
    std::vector<std::vector<PassTime>> times;
    std::uint64_t extra = 0;
    long long same = -1;
    for (int f = 0; f <= frames; ++f) {
      auto r = (*c)->dispatch(frame);
      if (!r) return fail(r.status().message);
      if (f == 0) continue;
      times.push_back(r->passes);
      extra = r->extra_samples;
      Result<ImageRGBAF> img = gl::read_texture_rgbaf(r->colour);
      if (!img) return fail(img.status().message);
      same = std::memcmp(img->pixels.data(), ref->image.pixels.data(), img->pixels.size() * 4) == 0;
    }
    print_method(a, run.name, times, extra, frame.budget ? *frame.budget : -1, same);
  }
  return 0;
}
