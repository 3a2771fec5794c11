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
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "engine.h"
#include "aa_scene.h"
#include "tessera/core.h"
#include "tessera/io.h"
#include "tessera/metrics.h"
#include "tessera/vk_adaptive.h"

namespace {

struct Args {
  int w = 320, h = 240, m = 4;
  long long budget = -1;  // -1: none
  std::string schedule = "frame_list", out;
  bool json = false, validation = true;
};

int fail(const std::string& msg) {
  std::fprintf(stderr, "engine_aa_vk: %s\n", msg.c_str());
  return 1;
}

// The engine's shading, handed to tessera as the hook: its own frame block and albedo (RT1) in
// its own descriptor set 0; tessera's resources are in set 1 (TESSERA_ADAPTIVE_SET).
const char* kShadingHook = R"(
layout(std140, set = 0, binding = 0) uniform EngineFrame {
  mat4 inv_view;      // camera to world
  vec4 eye_tan;       // eye xyz, tan(fov_y / 2)
  vec4 grid_aspect;   // grid width, height, aspect
  vec4 light_pos[6];  // xyz, radius
  vec4 light_col[6];  // rgb intensity
};
layout(set = 0, binding = 1) uniform sampler2D engine_albedo;  // RT1

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

float half_to_float(std::uint16_t h) {
  const int e = (h >> 10) & 31, m = h & 1023;
  const float s = (h & 0x8000) ? -1.0f : 1.0f;
  if (e == 0) return s * std::ldexp(float(m), -24);
  if (e == 31) return s * 65504.0f;
  return s * std::ldexp(float(m | 1024), e - 25);
}

bool parse(int argc, char** argv, Args& a, std::string& err) {
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    auto next = [&](std::string& v) {
      if (i + 1 >= argc) return false;
      v = argv[++i];
      return true;
    };
    std::string v;
    if (k == "--json") {
      a.json = true;
    } else if (k == "--no-validation") {
      a.validation = false;
    } else if (k != "--size" && k != "--m" && k != "--budget" && k != "--schedule" && k != "-o") {
      err = "unknown argument " + k;
      return false;
    } else if (!next(v)) {
      err = k + " needs a value";
      return false;
    } else if (k == "--size") {
      if (std::sscanf(v.c_str(), "%dx%d", &a.w, &a.h) != 2 || a.w <= 0 || a.h <= 0) {
        err = "--size " + v + ": expected WxH";
        return false;
      }
    } else if (k == "--m") {
      a.m = std::atoi(v.c_str());
    } else if (k == "--budget") {
      a.budget = std::atoll(v.c_str());
      if (a.budget < 0) {
        err = "--budget must be >= 0";
        return false;
      }
    } else if (k == "--schedule") {
      a.schedule = v;
    } else {
      a.out = v;
    }
  }
  return true;
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
  float view[16], inv_view[16], proj[16] = {}, eye[3] = {3.2f, 2.2f, 4.2f}, tan_half = 0,
                                aspect = 1;
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
  const float at[3] = {0.0f, 0.4f, 0.0f};
  f.tan_half = std::tan(0.8f / 2);
  f.aspect = float(a.w) / float(a.h);
  engine::look_at(f.eye, at, f.view, f.inv_view);
  const float zn = 0.1f, zf = 50.0f;  // Vulkan's depth range [0, 1]
  f.proj[0] = 1.0f / (f.tan_half * f.aspect);
  f.proj[5] = 1.0f / f.tan_half;
  f.proj[10] = zf / (zn - zf);
  f.proj[11] = -1.0f;
  f.proj[14] = zn * zf / (zn - zf);
  struct {
    float inv_view[16], eye_tan[4], grid_aspect[4], light_pos[6][4], light_col[6][4];
  } u{};
  std::copy(f.inv_view, f.inv_view + 16, u.inv_view);
  u.eye_tan[0] = f.eye[0], u.eye_tan[1] = f.eye[1], u.eye_tan[2] = f.eye[2];
  u.eye_tan[3] = f.tan_half;
  u.grid_aspect[0] = float(gw), u.grid_aspect[1] = float(gh), u.grid_aspect[2] = f.aspect;
  const float lights[6][8] = {{2.5f, 3.0f, 2.0f, 0, 1.0f, 0.9f, 0.8f, 14.0f},
                              {-3.0f, 2.5f, 1.5f, 0, 0.5f, 0.6f, 1.0f, 10.0f},
                              {0.5f, 1.2f, 2.5f, 0, 1.0f, 0.5f, 0.3f, 4.0f},
                              {-1.0f, 4.0f, -2.5f, 0, 0.9f, 0.9f, 1.0f, 12.0f},
                              {3.0f, 0.6f, -1.0f, 0, 0.3f, 1.0f, 0.4f, 3.0f},
                              {0.0f, 6.0f, 0.0f, 0, 1.0f, 1.0f, 1.0f, 16.0f}};
  for (int i = 0; i < 6; ++i)
    for (int c = 0; c < 4; ++c) {
      u.light_pos[i][c] = lights[i][c];
      u.light_col[i][c] = lights[i][4 + c];
    }
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
  std::copy(f.view, f.view + 16, pc);
  std::copy(f.proj, f.proj + 16, pc + 16);
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

void write_outputs(const Args& a, const tessera::ImageRGBA8& img, const tessera::ImageRGBA8& ref,
                   const tessera::ImageRGBA8& one, const std::vector<std::uint8_t>& counts,
                   std::string& err) {
  std::error_code ec;
  std::filesystem::create_directories(a.out, ec);
  tessera::ImageRGBA8 k(a.w, a.h);
  for (std::size_t i = 0; i < counts.size(); ++i) {
    const auto g = std::uint8_t(255 * (counts[i] - 1) / (a.m * a.m - 1));
    k.pixels[i * 4] = k.pixels[i * 4 + 1] = k.pixels[i * 4 + 2] = g;
    k.pixels[i * 4 + 3] = 255;
  }
  for (const auto& [name, im] : {std::pair{"adaptive.png", &img},
                                 {"reference.png", &ref},
                                 {"first.png", &one},
                                 {"samples.png", &k}}) {
    const std::string path = (std::filesystem::path(a.out) / name).string();
    if (auto s = tessera::io::write_png(path, *im); !s.ok()) {
      err = s.message;
      return;
    }
  }
}

void print_json(const Args& a, const engine::Device& d, const Shot& ad, const Shot& ref,
                const Shot& one, double samples_pct, double p_adaptive, double p_one) {
  std::printf(
      "{\"device\": \"%s\", \"backend\": \"vk\", \"width\": %d, \"height\": %d, \"m\": %d, "
      "\"schedule\": \"%s\", ",
      d.name.c_str(), a.w, a.h, a.m, a.schedule.c_str());
  if (a.budget >= 0) {
    std::printf("\"budget\": %lld, ", a.budget);
  } else {
    std::printf("\"budget\": null, ");
  }
  std::printf(
      "\"extra_samples\": %llu, \"samples_percent\": %.3f, \"psnr_db\": %.3f, "
      "\"psnr_1spp_db\": %.3f, \"gbuffer_ms\": %.3f, \"passes_ms\": {",
      (unsigned long long)ad.profile.extra_samples, samples_pct, p_adaptive, p_one, ad.gbuffer_ms);
  for (std::size_t i = 0; i < ad.profile.passes.size(); ++i) {
    std::printf("%s\"%s\": %.3f", i ? ", " : "", ad.profile.passes[i].pass.c_str(),
                ad.profile.passes[i].ms);
  }
  std::printf(
      "}, \"adaptive_ms\": %.3f, \"first_ms\": %.3f, \"reference_ms\": %.3f, "
      "\"validation\": %s, \"validation_messages\": %d}\n",
      ad.profile.total_ms(), one.profile.total_ms(), ref.profile.total_ms(),
      d.validation ? "true" : "false", d.messages);
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
  o.width = a.w;
  o.height = a.h;
  o.m = a.m;
  o.layout.normal = {0, "rgb"};
  o.layout.depth = {0, "a"};
  o.layout.id = {1, "a", 255.0f, -1.0f};  // (id + 1) / 255 in unorm8; sky = -1
  o.hook.source = kShadingHook;
  o.hook.name = "engine_shading.glsl";
  o.hook_set_layouts = {f.set_layout};  // the hook's set 0; tessera's is set 1
  o.resolve = tessera::AdaptiveResolve::tonemap_weighted;  // HDR lights
  o.output = tessera::AdaptiveOutputFormat::rgba16f;
  o.sample_count_texture = true;
  o.profile = true;  // timestamps and the sample count for --json
  int rc = 0;
  std::string err;
  if (a.schedule == "tile_list") {
    o.schedule = tessera::AdaptiveSchedule::tile_list;
  } else if (a.schedule == "loop") {
    o.schedule = tessera::AdaptiveSchedule::loop;
  } else if (a.schedule != "frame_list") {
    err = "--schedule " + a.schedule + ": frame_list, tile_list or loop";
  }
  auto aa = err.empty() ? tessera::vk::AdaptiveSupersampler::create(ctx, o)
                        : tessera::Result<std::unique_ptr<tessera::vk::AdaptiveSupersampler>>(
                              tessera::Status::error(tessera::ErrorCode::invalid_argument, err));
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
      const tessera::ImageRGBA8 d_img = display(shots[0].image), d_ref = display(shots[1].image),
                                d_one = display(shots[2].image);
      const double pixels = double(a.w) * a.h;
      const double samples_pct =
          100.0 * (pixels + double(shots[0].profile.extra_samples)) / (pixels * a.m * a.m);
      const double p_adaptive = psnr(d_img, d_ref), p_one = psnr(d_one, d_ref);
      if (!a.out.empty()) write_outputs(a, d_img, d_ref, d_one, shots[0].counts, err);
      if (!err.empty()) {
        rc = fail(err);
      } else if (a.json) {
        print_json(a, d, shots[0], shots[1], shots[2], samples_pct, p_adaptive, p_one);
      } else {
        std::printf(
            "engine_aa_vk %dx%d m=%d on %s: %.1f %% samples, PSNR %.2f dB (1 spp %.2f dB) "
            "against full supersampling\n",
            a.w, a.h, a.m, d.name.c_str(), samples_pct, p_adaptive, p_one);
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
  std::string err;
  if (!parse(argc, argv, a, err)) return fail(err);
  engine::Device d;
  if (std::string why = d.create(a.validation); !why.empty()) {
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
