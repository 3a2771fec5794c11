// engine_ptex_vk — a small Vulkan forward renderer that draws a Ptex mesh with its own shader
// and tessera's seamless per-face lookup (seams.glsl, tessera_seams_sample_discard: Toth 2013),
// the Vulkan twin of examples/engine_ptex.
//
// The engine side is all its own (engine.h): its instance (with the validation layer and
// synchronization validation when installed; any validation message makes it exit 1), device
// and queue, its vertex layout (position, normal, per-face UV, integer face id), its frame
// uniform block at set 0, its render pass and pipeline, its GLSL compiled at load with shaderc.
// The integration with tessera is the blocks marked "tessera" (tessera/vk_faces.h): mesh and
// textures from the .obj and .ptx, one vk::FaceTextureSet::create on the engine's device, its
// upload recorded into the engine's first frame (released after that frame's fence), its set
// layout in the engine's pipeline layout at set index 2 (the engine's choice), its
// glsl_defines before the engine's #include "seams.glsl", one bind per frame.
//
// Usage: engine_ptex_vk MESH.obj FILE.ptx [--size WxH] [--orbit K/N] [--shift-px X]
//                       [--face-shift K] [--json] [-o FILE.png]
//                       [--frame-loop N [--frames-in-flight F] [--views V] [--window]]
//   --json         one JSON object with the agreement with tessera's CPU renderer
//                  (faces::FaceRenderer: Discard, trilinear, same camera, resolution and
//                  lighting): PSNR of the 8-bit sRGB images (psnr_db, null when identical),
//                  and the validation messages counted
//   -o FILE.png    the Vulkan image (8-bit sRGB; with --frame-loop: view 0 of the last frame)
//   --frame-loop N runs N frames as an engine does (frame_loop.h): F frames in flight (2..3,
//                  default 2), V views (default 2; view v at orbit (K + v max(1, N/V))/N,
//                  each frame's camera a further 1/64 of an orbit step round), the render scale
//                  cycling 100 % -> 70 % -> 85 % of --size (each side rounded to even), the texture
//                  set's upload in the first frame's command buffer; --json reports per frame
//                  and view the slot, scale and render size, and for the last frame of each
//                  scale (the last 3 frames) every view's image, read back after its fence,
//                  against the CPU renderer at that size and camera (psnr_db)
//   --window       with --frame-loop: view 0 presented every frame in a GLFW window
//                  (examples/common/vk_window.h; under Xvfb lavapipe presents through X11);
//                  --json adds the frames presented
//   --shift-px X   moves the Vulkan camera's image X pixels right (the CPU frame stays)
//   --face-shift K the shader reads face (f + K) mod faces: the wrong textures
// The last two are negative controls for the agreement bound (tests/vk/engine_ptex_vk_test.py).
// Exit 1 with one line when there is no Vulkan device, on bad arguments or input, or on any
// validation message.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "engine.h"
#include "frame_loop.h"
#include "ptex_report.h"  // examples/common: the flags, vertex, frame block and CPU check of both
#include "shaders.h"
#include "tessera/core.h"
#include "tessera/faces.h"
#include "tessera/faces_gpu.h"
#include "tessera/glsl.h"
#include "tessera/io.h"
#include "tessera/ptex.h"
#include "tessera/vk_faces.h"
#include "vk_window.h"  // examples/common: the GLFW window and swapchain

namespace {

// The flags of engine_ptex too (ptex_report.h), the frame loop's (engine_args.h; frame_loop 0:
// one frame), and the Vulkan engine's own.
struct Args : engine::PtexArgs, engine::FrameLoopArgs {
  int face_shift = 0;
};

// The frame loop's cameras: view v at orbit (K + v max(1, N / V))/N (the views spread round
// the orbit: 1/8 and 5/8 by default, the single frame's two checked orbits), frame i a further
// i/kOrbitSteps of an orbit step round (an engine's camera moves every frame, so a view drawn
// with another frame's uniform buffer would not match its check).
constexpr int kOrbitSteps = 64;
// The frames whose views are checked against the CPU renderer: the last of each render scale.
constexpr int kCheckedFrames = 3;

int fail(const std::string& msg) {
  std::fprintf(stderr, "engine_ptex_vk: %s\n", msg.c_str());
  return 1;
}

// The engine's vertex (ptex_report.h): 4 per Ptex face, each face with its own UVs.
using Vertex = engine::FaceVertex;

// The command line; "" or the problem.
std::string parse_args(int argc, char** argv, Args& a) {
  engine::CommandLine cl;
  engine::add_ptex_flags(cl, a);
  cl.option("--face-shift", [&a](const std::string& v) -> std::string {
    a.face_shift = std::atoi(v.c_str());
    return a.face_shift < 0 ? "--face-shift: K >= 0" : "";
  });
  engine::add_frame_loop_flags(cl, a, 2, 3);
  if (std::string why = engine::parse_ptex_args(cl, argc, argv, a, "engine_ptex_vk");
      !why.empty()) {
    return why;
  }
  return a.window && a.frame_loop == 0 ? "--window needs --frame-loop N" : "";
}

// The engine's frame: 4 vertices and 2 triangles per face, the camera (moved `shift_px`
// pixels right), the light; vertex layout and the frame block's bytes.
engine::Frame make_frame(const Args& a, const tessera::faces::QuadMesh& mesh,
                         const tessera::scene::Camera& camera, std::vector<Vertex>& verts) {
  engine::Frame f;
  f.width = a.w;
  f.height = a.h;
  for (int c = 0; c < 3; ++c) f.background[c] = tessera::faces::kFaceBackground[std::size_t(c)];
  engine::face_vertices(mesh, verts, f.indices);
  f.vertices = verts.data();
  f.vertex_bytes = verts.size() * sizeof(Vertex);
  f.stride = sizeof(Vertex);
  f.attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0},
                  {1, 0, VK_FORMAT_R32G32B32_SFLOAT, 12},
                  {2, 0, VK_FORMAT_R32G32_SFLOAT, 24},
                  {3, 0, VK_FORMAT_R32_SINT, 32}};
  const engine::ForwardFrameBlock block = engine::forward_frame_block(camera, a.w, a.h, a.shift_px);
  f.block.resize(sizeof block);
  std::memcpy(f.block.data(), &block, sizeof block);
  return f;
}

// The frame block's bytes of `camera` at w x h (the shift applied).
std::vector<std::uint8_t> block_bytes(const Args& a, const tessera::scene::Camera& camera, int w,
                                      int h) {
  const engine::ForwardFrameBlock block = engine::forward_frame_block(camera, w, h, a.shift_px);
  std::vector<std::uint8_t> bytes(sizeof block);
  std::memcpy(bytes.data(), &block, sizeof block);
  return bytes;
}

// The camera of view `view` in frame `frame` of the frame loop: orbit position
// loop_orbit(...) of a.orbit_n * kOrbitSteps.
int loop_orbit(const Args& a, int frame, int view) {
  return (a.orbit_k + view * std::max(1, a.orbit_n / a.views)) * kOrbitSteps + frame;
}
tessera::scene::Camera loop_camera(const Args& a, const tessera::faces::FaceScene& scene, int frame,
                                   int view) {
  return tessera::faces::face_orbit_camera(scene, loop_orbit(a, frame, view),
                                           a.orbit_n * kOrbitSteps);
}

// An RGBA32F image of w x h from read-back texels.
tessera::ImageRGBAF to_image(int w, int h, std::vector<float> pixels) {
  tessera::ImageRGBAF img(w, h);
  img.pixels = std::move(pixels);
  return img;
}

// The frame loop's report: per frame and view the slot, scale and render size, and for the
// read-back views the agreement with the CPU renderer at that size and camera.
int report_loop(const Args& a, const tessera::faces::FaceScene& scene,
                const tessera::faces::FaceTextureSet& set, int classes,
                const std::string& device_name, bool validation, int messages, int presented,
                const std::vector<engine::FrameResult>& frames) {
  auto cpu = tessera::faces::FaceRenderer::create(scene, set);
  if (!cpu) return fail(cpu.status().message);
  std::string text;
  double psnr_min = INFINITY, cpu_ms = 0;
  int checked = 0;
  char buf[512];
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const engine::FrameResult& f = frames[i];
    std::snprintf(buf, sizeof buf,
                  "%s{\"frame\": %d, \"slot\": %u, \"scale_percent\": %d, \"views\": [",
                  i ? ", " : "", f.frame, f.slot, f.scale_percent);
    text += buf;
    for (std::size_t k = 0; k < f.views.size(); ++k) {
      const engine::ViewResult& v = f.views[k];
      std::snprintf(
          buf, sizeof buf, "%s{\"view\": %d, \"render_size\": [%u, %u], \"orbit\": \"%d/%d\"",
          k ? ", " : "", v.view, v.w, v.h, loop_orbit(a, f.frame, v.view), a.orbit_n * kOrbitSteps);
      text += buf;
      std::string psnr = "unchecked";
      if (!v.image.empty()) {
        const tessera::ImageRGBAF img = to_image(int(v.w), int(v.h), v.image);
        auto agree = engine::cpu_agreement(**cpu, loop_camera(a, scene, f.frame, v.view), img);
        if (!agree) return fail(agree.status().message);
        ++checked;
        cpu_ms += agree->cpu_ms;
        psnr_min = std::min(psnr_min, agree->psnr);
        text += ", \"psnr_db\": " + engine::psnr_text(agree->psnr, true);
        psnr = engine::psnr_text(agree->psnr, false) + " dB";
      }
      text += "}";
      if (!a.json) {
        std::printf("frame %d (slot %u) view %d: %ux%u (%d %%), PSNR vs CPU Discard: %s\n", f.frame,
                    f.slot, v.view, v.w, v.h, f.scale_percent, psnr.c_str());
      }
    }
    text += "]}";
  }
  if (!a.out.empty() && !frames.empty() && !frames.back().views.empty() &&
      !frames.back().views[0].image.empty()) {
    const engine::ViewResult& v = frames.back().views[0];
    const tessera::ImageRGBAF img = to_image(int(v.w), int(v.h), v.image);
    if (auto s = tessera::io::write_png(a.out, tessera::to_srgb8(img)); !s.ok()) {
      return fail(s.message);
    }
  }
  if (!a.json) return 0;
  std::printf(
      "{\"backend\": \"vk\", \"device\": \"%s\", \"mesh\": \"%s\", \"faces\": %d, "
      "\"classes\": %d, \"width\": %d, \"height\": %d, \"frames_in_flight\": %d, "
      "\"views\": %d, \"shift_px\": %.3f, \"face_shift\": %d, \"frames\": [%s], "
      "\"checked\": %d, \"psnr_min_db\": %s, \"cpu_ms\": %.3f, \"presented\": %d, "
      "\"validation\": %s, \"validation_messages\": %d}\n",
      device_name.c_str(), scene.name.c_str(), scene.mesh.face_count(), classes, a.w, a.h,
      a.frames_in_flight, a.views, double(a.shift_px), a.face_shift, text.c_str(), checked,
      checked ? engine::psnr_text(psnr_min, true).c_str() : "null", cpu_ms, presented,
      validation ? "true" : "false", messages);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  if (std::string why = parse_args(argc, argv, a); !why.empty()) return fail(why);

  // ---- tessera, step 1 (pure; ptex_report.h, as engine_ptex): the quad faces of the Ptex
  // file and their textures ----
  auto loaded = engine::load_ptex_scene(a);
  if (!loaded) return fail(loaded.status().message);
  const tessera::faces::FaceScene& scene = loaded->scene;
  const tessera::faces::FaceTextureSet& set = loaded->set;
  // ---- end of step 1 ----

  // --window: the engine's window first (its surface extensions go into the instance).
  engine::Window window;
  std::vector<const char*> instance_extensions, device_extensions;
  if (a.window) {
    if (std::string why = window.open(a.w, a.h, "engine_ptex_vk"); !why.empty()) {
      window.close();
      return fail("no window: " + why);
    }
    instance_extensions = window.instance_extensions();
    device_extensions = {VK_KHR_SWAPCHAIN_EXTENSION_NAME};
  }
  engine::Device d;
  if (std::string why = d.create(true, instance_extensions, device_extensions); !why.empty()) {
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
  const tessera::scene::Camera camera =
      tessera::faces::face_orbit_camera(scene, a.orbit_k, a.orbit_n);
  std::vector<Vertex> verts;
  engine::Frame frame = make_frame(a, scene.mesh, camera, verts);

  // ---- tessera, step 2: the engine's device, one upload; set index 2 is the engine's ----
  tessera::vk::DeviceContext ctx;
  ctx.instance = d.instance;
  ctx.physical_device = d.physical;
  ctx.device = d.device;
  ctx.queue_family = d.family;
  ctx.queue = d.queue;
  ctx.get_instance_proc_addr = vkGetInstanceProcAddr;
  ctx.get_device_proc_addr = vkGetDeviceProcAddr;
  ctx.api_version = d.api_version;
  ctx.enabled_features = d.features;
  tessera::vk::FaceTextureSetOptions to;
  to.max_anisotropy = 1.0f;  // trilinear: the filter the CPU check uses
  // The upload goes into the engine's first frame (no submit inside tessera).
  to.upload = tessera::vk::FaceUpload::engine_command_buffer;
  auto tex = tessera::vk::FaceTextureSet::create(ctx, set, to);
  if (!tex) {
    if (a.window) window.destroy(d);
    d.destroy();
    return fail(tex.status().message);
  }
  const std::uint32_t kSet = 2;  // set 1 stays free for the engine's own material set
  tessera::glsl::ExpandOptions so;
  so.preamble = (*tex)->glsl_defines(kSet);
  so.preamble.push_back("#define ENGINE_FACES " + std::to_string(scene.mesh.face_count()));
  so.preamble.push_back("#define ENGINE_FACE_SHIFT " + std::to_string(a.face_shift));
  auto fragment = tessera::glsl::expand_includes(
      {tessera::glsl::Stage::fragment, engine::kFragmentShader, "engine_ptex_vk.frag"}, so);
  frame.extra_layouts = {VK_NULL_HANDLE, (*tex)->set_layout()};
  frame.bind_extra = [&](VkCommandBuffer cmd, VkPipelineLayout layout) {
    return (*tex)->bind(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, kSet).message;
  };
  frame.before_pass = [&](VkCommandBuffer cmd) {
    return (*tex)->upload_recorded() ? std::string() : (*tex)->record_upload(cmd).message;
  };
  // ---- end of step 2 ----

  std::string error = fragment ? "" : fragment.status().message;
  std::string log;
  if (error.empty()) {
    frame.vertex_spirv = engine::compile(engine::kVertexShader, true, "engine_ptex_vk.vert", log);
    frame.fragment_spirv = engine::compile(fragment->text, false, "engine_ptex_vk.frag", log);
    if (!log.empty()) error = tessera::glsl::format_log(log, fragment->files);
  }
  double vk_ms = 0;
  std::vector<float> pixels;
  std::vector<engine::FrameResult> frames;
  if (error.empty() && a.frame_loop > 0) {
    engine::FrameLoopOptions lo;
    lo.w = a.w;
    lo.h = a.h;
    lo.frames = a.frame_loop;
    lo.frames_in_flight = std::uint32_t(a.frames_in_flight);
    lo.views = a.views;
    lo.read_back_from = std::max(0, a.frame_loop - kCheckedFrames);
    lo.frame_block = [&](int i, int v, VkExtent2D size) {
      return block_bytes(a, loop_camera(a, scene, i, v), int(size.width), int(size.height));
    };
    // ---- tessera: the first frame's command buffer (the upload) completed ----
    lo.first_frame_completed = [&] { return (*tex)->release_staging().message; };
    lo.window = a.window ? &window : nullptr;
    error = engine::run_frame_loop(d, frame, lo, frames);
  } else if (error.empty()) {
    pixels = engine::draw(d, frame, &vk_ms, error);
    if (error.empty()) error = (*tex)->release_staging().message;  // the frame completed
  }
  const int classes = (*tex)->class_count();
  (*tex).reset();                   // tessera's objects before the engine's device
  if (a.window) window.destroy(d);  // before the device
  const std::string device_name = d.name;
  const bool validation = d.validation;
  d.destroy();  // leaks are reported here
  if (!error.empty()) return fail(error);
  if (d.messages > 0) {
    return fail(std::to_string(d.messages) +
                " validation message(s), the first: " + d.first_message);
  }
  if (a.frame_loop > 0) {
    return report_loop(a, scene, set, classes, device_name, validation, d.messages,
                       window.presented, frames);
  }
  tessera::ImageRGBAF img(a.w, a.h);
  img.pixels = std::move(pixels);
  if (!a.out.empty()) {
    if (auto s = tessera::io::write_png(a.out, tessera::to_srgb8(img)); !s.ok()) {
      return fail(s.message);
    }
  }
  // The same frame through tessera's CPU renderer (ptex_report.h).
  auto agree = engine::cpu_agreement(scene, set, camera, img);
  if (!agree) return fail(agree.status().message);
  if (a.json) {
    std::printf(
        "{\"backend\": \"vk\", \"device\": \"%s\", \"mesh\": \"%s\", \"faces\": %d, "
        "\"classes\": %d, \"width\": %d, \"height\": %d, \"orbit\": \"%d/%d\", "
        "\"shift_px\": %.3f, \"face_shift\": %d, \"psnr_db\": %s, \"validation\": %s, "
        "\"validation_messages\": %d, \"vk_ms\": %.3f, \"cpu_ms\": %.3f}\n",
        device_name.c_str(), scene.name.c_str(), scene.mesh.face_count(), classes, a.w, a.h,
        a.orbit_k, a.orbit_n, double(a.shift_px), a.face_shift,
        engine::psnr_text(agree->psnr, true).c_str(), validation ? "true" : "false", d.messages,
        vk_ms, agree->cpu_ms);
  } else {
    std::printf("engine_ptex_vk %dx%d, %d faces: Vulkan (%s) vs CPU Discard: PSNR %s dB\n", a.w,
                a.h, scene.mesh.face_count(), device_name.c_str(),
                engine::psnr_text(agree->psnr, false).c_str());
  }
  return 0;
}
