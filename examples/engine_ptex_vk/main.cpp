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
//   --json         one JSON object with the agreement with tessera's CPU renderer
//                  (faces::FaceRenderer: Discard, trilinear, same camera, resolution and
//                  lighting): PSNR of the 8-bit sRGB images (psnr_db, null when identical),
//                  and the validation messages counted
//   -o FILE.png    the Vulkan image (8-bit sRGB)
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
#include "ptex_report.h"  // examples/common: the flags, vertex, frame block and CPU check of both
#include "shaders.h"
#include "tessera/core.h"
#include "tessera/faces.h"
#include "tessera/faces_gpu.h"
#include "tessera/glsl.h"
#include "tessera/io.h"
#include "tessera/ptex.h"
#include "tessera/vk_faces.h"

namespace {

// The flags of engine_ptex too (ptex_report.h), and the Vulkan engine's own.
struct Args : engine::PtexArgs {
  int face_shift = 0;
};

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
  return engine::parse_ptex_args(cl, argc, argv, a, "engine_ptex_vk");
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

  engine::Device d;
  if (std::string why = d.create(true); !why.empty()) {
    d.destroy();
    return fail("no Vulkan device: " + why);
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
  if (error.empty()) pixels = engine::draw(d, frame, &vk_ms, error);
  if (error.empty()) error = (*tex)->release_staging().message;  // the frame completed
  const int classes = (*tex)->class_count();
  (*tex).reset();  // tessera's objects before the engine's device
  const std::string device_name = d.name;
  const bool validation = d.validation;
  d.destroy();  // leaks are reported here
  if (!error.empty()) return fail(error);
  if (d.messages > 0) {
    return fail(std::to_string(d.messages) +
                " validation message(s), the first: " + d.first_message);
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
