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
//                     [--no-validation] [--json] [-o DIR]
//   --json  one JSON object: samples %, PSNR of the adaptive and the 1 spp image against the
//           component's own full supersampling (tonemapped, sRGB8), the component's pass times
//           (GPU timestamps; lavapipe runs them on the CPU), validation messages
//   -o DIR  writes adaptive.png, reference.png, first.png, samples.png (k + 1, grey)
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
#include "tessera/core.h"
#include "tessera/vk_adaptive.h"

namespace {

// The flags of engine_aa too (aa_report.h), and the Vulkan engine's own.
struct Args : engine::AaArgs {
  bool no_validation = false;
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
  return cl.parse(argc, argv);
}

/// The engine's G-buffer and its frame data.
struct Frame {
  engine::Image rt0, rt1, depth;
  engine::Buffer vertices, ubo;
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkDescriptorSet set = VK_NULL_HANDLE;
  VkSampler sampler = VK_NULL_HANDLE;
  std::size_t vertex_count = 0;
  engine::Camera cam;  // aa_scene.h's, with Vulkan's projection
};

void setup(engine::Device& d, const Args& a, Frame& f) {
  const std::uint32_t gw = std::uint32_t(a.w * a.m), gh = std::uint32_t(a.h * a.m);
  const VkImageUsageFlags rt = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  f.rt0 = d.image(VK_FORMAT_R16G16B16A16_SFLOAT, gw, gh, rt);
  f.rt1 = d.image(VK_FORMAT_R8G8B8A8_UNORM, gw, gh, rt);
  f.depth = d.image(VK_FORMAT_D32_SFLOAT, gw, gh, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                    VK_IMAGE_ASPECT_DEPTH_BIT);
  const std::vector<engine::Vertex> verts = engine::make_scene();
  f.vertex_count = verts.size();
  f.vertices =
      d.buffer(verts.size() * sizeof(engine::Vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, true);
  std::memcpy(f.vertices.data, verts.data(), verts.size() * sizeof(engine::Vertex));
  f.cam = engine::make_camera(a.w, a.h);
  const float zn = 0.1f, zf = 50.0f;  // Vulkan's depth range [0, 1]
  f.cam.proj[0] = 1.0f / (f.cam.tan_half * f.cam.aspect);
  f.cam.proj[5] = 1.0f / f.cam.tan_half;
  f.cam.proj[10] = zf / (zn - zf);
  f.cam.proj[11] = -1.0f;
  f.cam.proj[14] = zn * zf / (zn - zf);
  const engine::FrameBlock u = engine::frame_block(f.cam, int(gw), int(gh));
  f.ubo = d.buffer(sizeof u, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
  std::memcpy(f.ubo.data, &u, sizeof u);
  // The engine's descriptor set 0 for the hook: its frame block, RT1 as a sampler.
  VkSamplerCreateInfo si{};
  si.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
  vkCreateSampler(d.device, &si, nullptr, &f.sampler);
  const VkDescriptorSetLayoutBinding b[2] = {
      {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
  VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO, nullptr,
                                     0, 2, b};
  vkCreateDescriptorSetLayout(d.device, &li, nullptr, &f.set_layout);
  const VkDescriptorPoolSize ps[2] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                      {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1}};
  VkDescriptorPoolCreateInfo pi{
      VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, nullptr, 0, 1, 2, ps};
  vkCreateDescriptorPool(d.device, &pi, nullptr, &f.pool);
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO, nullptr, f.pool, 1,
                                 &f.set_layout};
  vkAllocateDescriptorSets(d.device, &ai, &f.set);
  const VkDescriptorBufferInfo bi{f.ubo.buffer, 0, VK_WHOLE_SIZE};
  // tessera leaves the G-buffer in SHADER_READ_ONLY_OPTIMAL while its passes run.
  const VkDescriptorImageInfo ii{f.sampler, f.rt1.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkWriteDescriptorSet w[2]{};
  for (int i = 0; i < 2; ++i) {
    w[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    w[i].dstSet = f.set;
    w[i].dstBinding = std::uint32_t(i);
    w[i].descriptorCount = 1;
  }
  w[0].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  w[0].pBufferInfo = &bi;
  w[1].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  w[1].pImageInfo = &ii;
  vkUpdateDescriptorSets(d.device, 2, w, 0, nullptr);
}

/// The geometry pass: dynamic rendering into RT0, RT1 and depth (from UNDEFINED: cleared).
void record_gbuffer(VkCommandBuffer cmd, const engine::GeometryPipeline& gp, const Frame& f) {
  const VkPipelineStageFlags2 out = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
  for (const engine::Image* rt : {&f.rt0, &f.rt1}) {
    engine::barrier(
        cmd, rt->image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, 0, out, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  }
  const VkPipelineStageFlags2 tests =
      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
  engine::barrier(cmd, f.depth.image, VK_IMAGE_LAYOUT_UNDEFINED,
                  VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, tests,
                  VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, tests,
                  VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT,
                  VK_IMAGE_ASPECT_DEPTH_BIT);
  VkRenderingAttachmentInfo colour[2]{};
  for (int i = 0; i < 2; ++i) {
    colour[i].sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
    colour[i].imageView = i == 0 ? f.rt0.view : f.rt1.view;
    colour[i].imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    colour[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    colour[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  }
  VkRenderingAttachmentInfo depth{};
  depth.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
  depth.imageView = f.depth.view;
  depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  depth.clearValue.depthStencil = {1.0f, 0};
  VkRenderingInfo ri{};
  ri.sType = VK_STRUCTURE_TYPE_RENDERING_INFO;
  ri.renderArea = {{0, 0}, {f.rt0.w, f.rt0.h}};
  ri.layerCount = 1;
  ri.colorAttachmentCount = 2;
  ri.pColorAttachments = colour;
  ri.pDepthAttachment = &depth;
  vkCmdBeginRendering(cmd, &ri);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, gp.pipeline);
  const VkViewport vp{0, 0, float(f.rt0.w), float(f.rt0.h), 0, 1};
  vkCmdSetViewport(cmd, 0, 1, &vp);
  vkCmdSetScissor(cmd, 0, 1, &ri.renderArea);
  float pc[32];
  std::copy(f.cam.view, f.cam.view + 16, pc);
  std::copy(f.cam.proj, f.cam.proj + 16, pc + 16);
  vkCmdPushConstants(cmd, gp.layout, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof pc, pc);
  const VkDeviceSize zero = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &f.vertices.buffer, &zero);
  vkCmdDraw(cmd, std::uint32_t(f.vertex_count), 1, 0, 0);
  vkCmdEndRendering(cmd);
}

/// tessera's view of an engine image just rendered (COLOR_ATTACHMENT_OPTIMAL, written by the
/// colour-attachment output stage).
tessera::vk::ImageResource rendered(const engine::Image& img) {
  tessera::vk::ImageResource r;
  r.image = img.image;
  r.view = img.view;
  r.format = img.format;
  r.extent = {img.w, img.h};
  r.usage = img.usage;
  r.layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  r.stage = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
  r.access = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
  return r;
}

struct Shot {
  tessera::ImageRGBAF image;
  std::vector<std::uint8_t> counts;
  tessera::vk::AdaptiveProfile profile;
  double gbuffer_ms = 0;
};

enum class Kind { adaptive, reference, first };

/// One frame: geometry pass then tessera, in one command buffer; the output read back.
tessera::Result<Shot> frame(engine::Device& d, const engine::GeometryPipeline& gp, const Frame& f,
                            tessera::vk::AdaptiveSupersampler& aa, const Args& a, Kind kind) {
  VkCommandBuffer geometry = d.begin();
  record_gbuffer(geometry, gp, f);
  const auto t0 = std::chrono::steady_clock::now();
  d.submit_and_wait(geometry);
  Shot s;
  s.gbuffer_ms = ms_since(t0);  // host time of the geometry pass's submit-and-wait

  VkCommandBuffer cmd = d.begin();
  // ---- tessera: per frame, the engine's G-buffer images in, the commands into its buffer ----
  tessera::vk::AdaptiveFrame in;
  in.gbuffer[0] = rendered(f.rt0);
  in.gbuffer[1] = rendered(f.rt1);
  in.hook_sets = {f.set};
  if (a.budget >= 0) in.budget = a.budget;
  tessera::Result<tessera::vk::AdaptiveRecord> r = kind == Kind::adaptive ? aa.record(cmd, in)
                                                   : kind == Kind::reference
                                                       ? aa.record_reference(cmd, in)
                                                       : aa.record_first_sample(cmd, in);
  // ---- end of the integration: r->colour is the anti-aliased HDR image (GENERAL) ----
  d.submit_and_wait(cmd);
  if (!r) return r.status();
  auto p = aa.read_profile();
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
  engine::print_aa_json(d.name, a, r, "\"backend\": \"vk\", ", "",
                        std::string(", \"validation\": ") + (d.validation ? "true" : "false") +
                            ", \"validation_messages\": " + std::to_string(d.messages));
}

/// Creates the component, runs the three kinds of frame (each twice: the first also pays the
/// driver's pipeline compilation), reports.
int run(engine::Device& d, const Args& a) {
  engine::GeometryPipeline gp = engine::geometry_pipeline(d);
  Frame f;
  setup(d, a, f);
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
  int rc = 0;
  auto aa = tessera::vk::AdaptiveSupersampler::create(ctx, o);
  if (!aa) {
    rc = fail(aa.status().message);
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
      rep.set_passes(shots[0].profile.passes);
      rep.adaptive_ms = shots[0].profile.total_ms();
      rep.reference_ms = shots[1].profile.total_ms();
      rep.first_ms = shots[2].profile.total_ms();
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
  vkDestroyDescriptorPool(d.device, f.pool, nullptr);
  vkDestroyDescriptorSetLayout(d.device, f.set_layout, nullptr);
  vkDestroySampler(d.device, f.sampler, nullptr);
  d.destroy(f.vertices);
  d.destroy(f.ubo);
  d.destroy(f.rt0);
  d.destroy(f.rt1);
  d.destroy(f.depth);
  engine::destroy(d, gp);
  return rc;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  if (std::string why = parse_args(argc, argv, a); !why.empty()) return fail(why);
  engine::Device d;
  if (std::string why = d.create(!a.no_validation); !why.empty()) {
    d.destroy();
    return fail("no Vulkan device: " + why);
  }
  int rc = run(d, a);
  d.destroy();  // leak reports of the validation layer arrive here
  if (d.messages > 0) {
    return fail(std::to_string(d.messages) +
                " validation message(s), the first: " + d.first_message);
  }
  return rc;
}
