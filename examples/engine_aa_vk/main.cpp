// engine_aa_vk — a minimal Vulkan deferred renderer that anti-aliases with
// tessera::vk::AdaptiveSupersampler.
//
// The engine side is all its own (engine.h/.cpp): a Vulkan 1.3 instance and device (the
// validation layer with synchronization validation when installed; any validation message
// fails the run), a scene of boxes and spheres generated in code, a G-buffer of
//   RT0 R16G16B16A16_SFLOAT  (world normal xyz, linear view depth)
//   RT1 R8G8B8A8_UNORM       (albedo rgb, (material id + 1) / 255; 0 = sky)
// rasterised m x m enlarged with dynamic rendering, six point lights in the engine's own
// uniform buffer (its descriptor set 0, with RT1 as a sampler), and a Blinn-Phong hook with a
// sharp specular lobe and a procedural checker floor (both alias at one sample per pixel).
// The integration with tessera is the block marked "tessera" below.
//
// Usage: engine_aa_vk [--size WxH] [--m M] [--budget B] [--schedule frame_list|tile_list|loop]
//                     [--no-validation] [--json] [-o DIR] [--shader-binary FILE]
//                     [--frame-loop N [--frames-in-flight F] [--views V] [--window]]
//   --frame-loop N  runs N frames as an engine does (frame_loop.h): F frames in flight (2),
//           V views (2), the render scale cycling 100 % -> 70 % -> 85 %; --json reports per
//           frame and view the render size, the extra samples and tessera's GPU time
//   --window  with --frame-loop: view 0 presented every frame in a GLFW window (vk_window.h;
//           under Xvfb lavapipe presents through X11); --json adds the frames presented
//   --json  one JSON object: samples %, PSNR of the adaptive and the 1 spp image against the
//           component's own full supersampling (tonemapped, sRGB8), the component's pass times
//           (GPU timestamps; lavapipe runs them on the CPU), validation messages
//   -o DIR  writes adaptive.png, reference.png, first.png, samples.png (k + 1, grey)
//   --shader-binary FILE  tessera's SPIR-V ahead of time: loaded from FILE when it exists (no
//           GLSL compiled at create), else written there after create; --json has create_ms
// Exit 1 with one line when there is no Vulkan 1.3 device, on bad arguments, or when the
// validation layer reported anything.
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "aa_report.h"  // examples/common: the flags, measures and report both AA engines share
#include "aa_scene.h"   // examples/common: the scene, camera, lights and shading of both
#include "engine.h"
#include "frame_loop.h"
#include "scene_frame.h"
#include "tessera/core.h"
#include "tessera/vk_adaptive.h"
#include "vk_window.h"  // examples/common: the GLFW window and swapchain

namespace {

// The flags of engine_aa too (aa_report.h), the frame loop's (engine_args.h; frame_loop 0: the
// three measured frames), and the Vulkan engine's own.
struct Args : engine::AaArgs, engine::FrameLoopArgs {
  bool no_validation = false;
  std::string shader_binary;  // --shader-binary FILE: load tessera's SPIR-V, or save it there
};

int fail(const std::string& msg) {
  std::fprintf(stderr, "engine_aa_vk: %s\n", msg.c_str());
  return 1;
}

// The engine's shading, handed to tessera as the hook (aa_scene.h): its own frame block and
// albedo (RT1) in its own descriptor set 0; tessera's resources are in set 1
// (TESSERA_ADAPTIVE_SET).
const std::string kShadingHook =
    engine::shading_hook("std140, set = 0, binding = 0", "set = 0, binding = 1");

using engine::ms_since;

double g_create_ms = 0;  // the component's create, host time (--json: create_ms)

float half_to_float(std::uint16_t h) {
  const int e = (h >> 10) & 31, m = h & 1023;
  const float s = (h & 0x8000) ? -1.0f : 1.0f;
  if (e == 0) return s * std::ldexp(float(m), -24);
  if (e == 31) return s * 65504.0f;
  return s * std::ldexp(float(m | 1024), e - 25);
}

// The command line; "" or the problem.
std::string parse_args(int argc, char** argv, Args& a) {
  engine::CommandLine cl;
  engine::add_aa_flags(cl, a);
  cl.flag("--no-validation", &a.no_validation);
  engine::add_frame_loop_flags(cl, a, 1, 16);
  cl.option("--shader-binary", [&a](const std::string& v) -> std::string {
    a.shader_binary = v;
    return v.empty() ? "--shader-binary: expected a file" : "";
  });
  return cl.parse(argc, argv);
}

struct Shot {
  tessera::ImageRGBAF image;
  std::vector<std::uint8_t> counts;
  tessera::vk::AdaptiveProfile profile;
  double gbuffer_ms = 0;
};

enum class Kind { adaptive, reference, first };

/// One frame: geometry pass then tessera, in one command buffer; the output read back.
tessera::Result<Shot> frame(engine::Device& d, const engine::GeometryPipeline& gp,
                            const engine::Frame& f, tessera::vk::AdaptiveSupersampler& aa,
                            const Args& a, Kind kind) {
  VkCommandBuffer geometry = d.begin();
  engine::record_gbuffer(geometry, gp, f);
  const auto t0 = std::chrono::steady_clock::now();
  d.submit_and_wait(geometry);
  Shot s;
  s.gbuffer_ms = ms_since(t0);  // host time of the geometry pass's submit-and-wait

  VkCommandBuffer cmd = d.begin();
  // ---- tessera: per frame, the engine's G-buffer images in, the commands into its buffer ----
  tessera::vk::AdaptiveFrame in;
  in.gbuffer[0] = engine::rendered(f.rt0);
  in.gbuffer[1] = engine::rendered(f.rt1);
  in.hook_sets = {f.set};
  if (a.budget >= 0) in.budget = a.budget;
  // This frame is the only one in flight (the engine waited for the last): slot 0.
  if (tessera::Status st = aa.begin_frame(0); !st.ok()) return st;
  tessera::Result<tessera::vk::AdaptiveOutput> r = kind == Kind::adaptive ? aa.record(cmd, in)
                                                   : kind == Kind::reference
                                                       ? aa.record_reference(cmd, in)
                                                       : aa.record_first_sample(cmd, in);
  // ---- end of the integration: r->colour is the anti-aliased HDR image (GENERAL) ----
  d.submit_and_wait(cmd);
  if (!r) return r.status();
  auto p = aa.read_profile(r->frame_slot, r->view);
  if (!p) return p.status();
  s.profile = *p;
  engine::Image colour{
      r->colour.image,        VK_NULL_HANDLE,         VK_NULL_HANDLE, r->colour.format, 0,
      r->colour.extent.width, r->colour.extent.height};
  const std::vector<std::uint8_t> half =
      d.read(colour, 8, r->colour.layout, r->colour.stage, r->colour.access);
  s.image = tessera::ImageRGBAF(a.w, a.h);
  for (std::size_t i = 0; i < s.image.pixels.size(); ++i) {
    std::uint16_t h;
    std::memcpy(&h, &half[i * 2], 2);
    s.image.pixels[i] = half_to_float(h);
  }
  engine::Image counts{r->sample_counts.image,
                       VK_NULL_HANDLE,
                       VK_NULL_HANDLE,
                       r->sample_counts.format,
                       0,
                       r->sample_counts.extent.width,
                       r->sample_counts.extent.height};
  s.counts =
      d.read(counts, 1, r->sample_counts.layout, r->sample_counts.stage, r->sample_counts.access);
  return s;
}

// The report (aa_report.h) with the Vulkan engine's own keys: the backend, the validation.
void print_report(const Args& a, const engine::Device& d, const engine::AaReport& r) {
  if (!a.json) {
    engine::print_aa_summary("engine_aa_vk", " on " + d.name, a, r);
    return;
  }
  char create[64];
  std::snprintf(create, sizeof create, "\"create_ms\": %.1f, ", g_create_ms);
  engine::print_aa_json(d.name, a, r, std::string("\"backend\": \"vk\", ") + create, "",
                        std::string(", \"validation\": ") + (d.validation ? "true" : "false") +
                            ", \"validation_messages\": " + std::to_string(d.messages));
}

/// The frame loop (frame_loop.h) and its report: per frame and view the render size, the extra
/// samples and tessera's GPU time.
int frame_loop(engine::Device& d, const engine::GeometryPipeline& gp, const Args& a,
               tessera::vk::AdaptiveSupersampler& aa, engine::Window* window) {
  engine::FrameLoopOptions lo;
  lo.w = a.w;
  lo.h = a.h;
  lo.m = a.m;
  lo.frames = a.frame_loop;
  lo.frames_in_flight = std::uint32_t(a.frames_in_flight);
  lo.views = a.views;
  lo.budget = a.budget;
  lo.window = window;
  std::vector<engine::FrameResult> frames;
  if (std::string e = engine::run_frame_loop(d, gp, lo, aa, frames); !e.empty()) return fail(e);
  if (!a.json) {
    for (const engine::FrameResult& f : frames) {
      for (const engine::ViewResult& v : f.views) {
        std::printf("frame %llu (slot %u) view %d: %ux%u (%d %%), %llu extra samples, %.2f ms\n",
                    f.frame, f.slot, v.view, v.w, v.h, f.scale_percent, v.extra_samples,
                    v.tessera_gpu_ms);
      }
    }
    return 0;
  }
  std::printf(
      "{\"backend\": \"vk\", \"device\": \"%s\", \"frames_in_flight\": %d, \"views\": %d, "
      "\"frames\": [",
      d.name.c_str(), a.frames_in_flight, a.views);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const engine::FrameResult& f = frames[i];
    std::printf("%s{\"frame\": %llu, \"slot\": %u, \"scale_percent\": %d, \"views\": [",
                i ? ", " : "", f.frame, f.slot, f.scale_percent);
    for (std::size_t k = 0; k < f.views.size(); ++k) {
      const engine::ViewResult& v = f.views[k];
      std::printf(
          "%s{\"view\": %d, \"render_size\": [%u, %u], \"extra_samples\": %llu, "
          "\"tessera_gpu_ms\": %.4f}",
          k ? ", " : "", v.view, v.w, v.h, v.extra_samples, v.tessera_gpu_ms);
    }
    std::printf("]}");
  }
  std::printf("], \"presented\": %d, \"validation\": %s, \"validation_messages\": %d}\n",
              window != nullptr ? window->presented : 0, d.validation ? "true" : "false",
              d.messages);
  return 0;
}

/// Creates the component, runs the three kinds of frame (each twice: the first also pays the
/// driver's pipeline compilation), reports.
int run(engine::Device& d, const Args& a, engine::Window* window) {
  engine::GeometryPipeline gp = engine::geometry_pipeline(d);
  engine::Frame f;
  engine::setup(d, a.w, a.h, a.m, 0, f);
  // ---- tessera: create once per (size, m, options) on the engine's device ----
  tessera::vk::DeviceContext ctx;
  ctx.instance = d.instance;
  ctx.physical_device = d.physical;
  ctx.device = d.device;
  ctx.queue_family = d.family;
  ctx.queue = d.queue;
  ctx.get_instance_proc_addr = vkGetInstanceProcAddr;
  ctx.get_device_proc_addr = vkGetDeviceProcAddr;
  ctx.api_version = VK_API_VERSION_1_3;
  ctx.synchronization2 = true;
  ctx.enabled_features = d.features;
  tessera::vk::AdaptiveSupersamplerOptions o;
  // The G-buffer layout, the hook, the resolve: as engine_aa's (aa_report.h). Its pass times
  // are GPU timestamps here, read back after each frame.
  engine::set_aa_options(o, a, kShadingHook);
  o.hook_set_layouts = {f.set_layout};  // the hook's set 0; tessera's is set 1
  if (a.frame_loop > 0) {
    o.frames_in_flight = std::uint32_t(a.frames_in_flight);
    o.profile = true;  // per view and frame: extra samples and GPU time, read after the fence
  }
  if (!a.shader_binary.empty()) {
    if (std::string why = engine::read_file(a.shader_binary, o.shader_binary); !why.empty()) {
      return fail(why);
    }
  }
  int rc = 0;
  const auto t_create = std::chrono::steady_clock::now();
  auto aa = tessera::vk::AdaptiveSupersampler::create(ctx, o);
  g_create_ms = ms_since(t_create);
  if (aa && !a.shader_binary.empty() && o.shader_binary.empty()) {
    if (std::string why = engine::write_file(a.shader_binary, (*aa)->shader_binary());
        !why.empty()) {
      return fail(why);
    }
  }
  if (!aa) {
    rc = fail((o.shader_binary.empty() ? "" : a.shader_binary + ": ") + aa.status().message);
  } else if (a.frame_loop > 0) {
    rc = frame_loop(d, gp, a, **aa, window);
    aa->reset();
  } else {
    std::array<Shot, 3> shots;
    const Kind kinds[3] = {Kind::adaptive, Kind::reference, Kind::first};
    for (int k = 0; k < 3 && rc == 0; ++k) {
      for (int rep = 0; rep < 2 && rc == 0; ++rep) {
        auto s = frame(d, gp, f, **aa, a, kinds[k]);
        if (!s) {
          rc = fail(s.status().message);
        } else {
          shots[std::size_t(k)] = std::move(*s);
        }
      }
    }
    if (rc == 0) {
      engine::AaReport rep;
      const engine::AaImages images =
          engine::measure(a, shots[0].image, shots[1].image, shots[2].image,
                          (unsigned long long)shots[0].profile.extra_samples, rep);
      rep.gbuffer_ms = shots[0].gbuffer_ms;
      rep.set_passes(shots[0].profile.passes, &tessera::PassTime::gpu_ms);
      rep.adaptive_ms = shots[0].profile.total_gpu_ms();
      rep.reference_ms = shots[1].profile.total_gpu_ms();
      rep.first_ms = shots[2].profile.total_gpu_ms();
      const std::string err =
          a.out.empty() ? "" : engine::write_aa_outputs(a, images, shots[0].counts);
      if (!err.empty()) {
        rc = fail(err);
      } else {
        print_report(a, d, rep);
      }
    }
    aa->reset();
  }
  vkDeviceWaitIdle(d.device);
  engine::destroy(d, f);
  engine::destroy(d, gp);
  return rc;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  if (std::string why = parse_args(argc, argv, a); !why.empty()) return fail(why);
  if (a.window && a.frame_loop == 0) return fail("--window needs --frame-loop N");
  // --window: the engine's window first (its surface extensions go into the instance).
  engine::Window window;
  std::vector<const char*> instance_extensions, device_extensions;
  if (a.window) {
    if (std::string why = window.open(a.w, a.h, "engine_aa_vk"); !why.empty()) {
      window.close();
      return fail("no window: " + why);
    }
    instance_extensions = window.instance_extensions();
    device_extensions = {VK_KHR_SWAPCHAIN_EXTENSION_NAME};
  }
  engine::Device d;
  if (std::string why = d.create(!a.no_validation, instance_extensions, device_extensions);
      !why.empty()) {
    if (a.window) window.destroy(d);
    d.destroy();
    return fail("no Vulkan device: " + why);
  }
  if (a.window) {
    if (std::string why = window.create_swapchain(d, std::uint32_t(a.frames_in_flight));
        !why.empty()) {
      window.destroy(d);
      d.destroy();
      return fail("no swapchain: " + why);
    }
  }
  int rc = run(d, a, a.window ? &window : nullptr);
  if (a.window) window.destroy(d);  // before the device
  d.destroy();                      // leak reports of the validation layer arrive here
  if (d.messages > 0) {
    return fail(std::to_string(d.messages) +
                " validation message(s), the first: " + d.first_message);
  }
  return rc;
}
