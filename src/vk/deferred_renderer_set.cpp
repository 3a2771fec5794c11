// vk::DeferredRenderer (deferred_renderer.h): the deferred descriptor set (deferred_shading.glsl's
// bindings 0..7, then deferred_passes.comp's SSBO 3..8 at 8..13), its buffers, the
// deferred_passes.comp pipelines, one timed pass per submission, and the read-back.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "tessera/glsl.h"
#include "vk/barriers.h"
#include "vk/deferred_renderer.h"
#include "vk/shader.h"

// Vulkan's create-infos are written with designated initializers: the members left out are
// zero-initialised, which is what Vulkan asks of them (null pNext, no flags).
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace tessera::vk {

namespace {

using State = DeferredRenderer::State;

constexpr const char* kWho = "deferred VK";
constexpr std::uint32_t kBindGBuffer0 = 4, kBindTextures = 7, kBindPasses = 8;
/// Bytes per output pixel of the pass buffers (S, terms, k, out, rgba8, rgba8 out).
constexpr std::array<std::size_t, kPassBuffers> kPassBytes = {16, 32, 4, 16, 4, 4};

VkDescriptorType binding_type(std::uint32_t b) {
  if (b == 0) return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  if (b >= kBindGBuffer0 && b <= kBindTextures) return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}

Status write_set(State& st) {
  const Api& api = *st.api;
  std::vector<VkDescriptorBufferInfo> buffers;
  buffers.reserve(4 + kPassBuffers);
  const Buffer* order[4] = {&st.params, &st.lights, &st.materials, &st.waves};
  for (const Buffer* b : order) buffers.push_back({b->get(), 0, VK_WHOLE_SIZE});
  for (const Buffer& b : st.pass) buffers.push_back({b.get(), 0, VK_WHOLE_SIZE});
  std::vector<VkDescriptorImageInfo> images;
  for (const Image& g : st.g) {
    images.push_back(
        {st.gbuffer_sampler.get(), g.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
  }
  for (const TextureArray& a : st.arrays) {
    images.push_back(
        {st.texture_sampler.get(), a.view.get(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
  }
  std::vector<VkWriteDescriptorSet> writes;
  auto write = [&](std::uint32_t binding, std::uint32_t count, const VkDescriptorBufferInfo* b,
                   const VkDescriptorImageInfo* i) {
    VkWriteDescriptorSet w{};
    w.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    w.dstSet = st.set;
    w.dstBinding = binding;
    w.descriptorCount = count;
    w.descriptorType = binding_type(binding);
    w.pBufferInfo = b;
    w.pImageInfo = i;
    writes.push_back(w);
  };
  for (std::uint32_t b = 0; b < 4; ++b) write(b, 1, &buffers[b], nullptr);
  for (std::uint32_t s = 0; s < 3; ++s) write(kBindGBuffer0 + s, 1, nullptr, &images[s]);
  write(kBindTextures, std::uint32_t(st.arrays.size()), nullptr, &images[3]);
  for (std::uint32_t k = 0; k < kPassBuffers; ++k) {
    write(kBindPasses + k, 1, &buffers[4 + k], nullptr);
  }
  api.UpdateDescriptorSets(api.device(), std::uint32_t(writes.size()), writes.data(), 0, nullptr);
  st.set_written = true;
  return Status::success();
}

/// A host-visible buffer of at least `bytes` holding `data` (made again when too small).
Status write_host(State& st, Buffer& b, const void* data, std::size_t bytes,
                  VkBufferUsageFlags usage, const char* what) {
  if (b.get() == VK_NULL_HANDLE || b.size() < bytes) {
    Result<Buffer> n = Buffer::create(*st.api, bytes, usage, true, std::string(kWho) + ": " + what);
    if (!n) return n.status();
    b = std::move(*n);
    st.set_written = false;
  }
  std::memcpy(b.mapped(), data, bytes);
  b.flush();
  return Status::success();
}

Status size_pass_buffers(State& st) {
  if (st.buffers_w == st.w && st.buffers_h == st.h) return Status::success();
  const std::size_t pixels = std::size_t(st.w) * std::size_t(st.h);
  for (std::size_t i = 0; i < kPassBuffers; ++i) {
    Result<Buffer> b =
        Buffer::create(*st.api, pixels * kPassBytes[i],
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, false,
                       std::string(kWho) + ": pass buffer");
    if (!b) return b.status();
    st.pass[i] = std::move(*b);
  }
  // Room for the component's colour (16 bytes per pixel) and sample counts (1) at once.
  Result<Buffer> r = Buffer::create(*st.api, pixels * 20, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true,
                                    std::string(kWho) + ": read-back");
  if (!r) return r.status();
  st.readback = std::move(*r);
  st.buffers_w = st.w;
  st.buffers_h = st.h;
  st.set_written = false;
  return Status::success();
}

Result<VkPipeline> program(State& st, const std::vector<std::string>& defines) {
  const std::vector<std::string> pre =
      deferred::gpu_passes_preamble(int(st.arrays.size()), st.m, defines);
  std::string key;
  for (const std::string& p : pre) key += p + "\n";
  auto it = st.programs.find(key);
  if (it != st.programs.end()) return it->second.get();
  Result<glsl::Source> cs = glsl::shipped_shader(glsl::Stage::compute, "deferred_passes.comp");
  if (!cs) return cs.status();
  glsl::ExpandOptions eo;
  eo.preamble = pre;
  Result<glsl::Expanded> text = glsl::expand_includes(*cs, eo);
  if (!text) return text.status();
  Result<std::vector<std::uint32_t>> spirv = compile_compute_spirv(text->text);
  if (!spirv) {
    return Status::error(
        spirv.status().code,
        std::string(kWho) + ": " + glsl::format_log(spirv.status().message, text->files));
  }
  Result<Pipeline> p = create_compute_pipeline(*st.api, *spirv, st.passes_layout.get(),
                                               std::string(kWho) + ": deferred_passes.comp");
  if (!p) return p.status();
  return st.programs.emplace(key, std::move(*p)).first->second.get();
}

double elapsed_ms(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

Status create_deferred_set(State& st) {
  const Api& api = *st.api;
  std::vector<VkDescriptorSetLayoutBinding> bindings;
  for (std::uint32_t b = 0; b < kBindPasses + kPassBuffers; ++b) {
    bindings.push_back({.binding = b,
                        .descriptorType = binding_type(b),
                        .descriptorCount = b == kBindTextures ? std::uint32_t(st.arrays.size()) : 1,
                        .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT});
  }
  const VkDescriptorSetLayoutCreateInfo set_info{
      .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
      .bindingCount = std::uint32_t(bindings.size()),
      .pBindings = bindings.data()};
  if (Status s =
          assign(st.set_layout, make_owned<SetLayout>(api, &Api::CreateDescriptorSetLayout,
                                                      set_info, "vkCreateDescriptorSetLayout"));
      !s.ok()) {
    return s;
  }
  const VkDescriptorSetLayout layout = st.set_layout.get();
  const VkPipelineLayoutCreateInfo passes_info{
      .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
      .setLayoutCount = 1,
      .pSetLayouts = &layout};
  const std::array<VkDescriptorPoolSize, 3> sizes = {
      VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
      VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3 + kPassBuffers},
      VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                           3 + std::uint32_t(st.arrays.size())}};
  const VkDescriptorPoolCreateInfo pool_info{.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
                                             .maxSets = 1,
                                             .poolSizeCount = std::uint32_t(sizes.size()),
                                             .pPoolSizes = sizes.data()};
  for (Status s :
       {assign(st.passes_layout, make_owned<PipelineLayout>(api, &Api::CreatePipelineLayout,
                                                            passes_info, "vkCreatePipelineLayout")),
        assign(st.pool, make_owned<DescriptorPool>(api, &Api::CreateDescriptorPool, pool_info,
                                                   "vkCreateDescriptorPool"))}) {
    if (!s.ok()) return s;
  }
  const VkDescriptorSetAllocateInfo alloc{.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                          .descriptorPool = st.pool.get(),
                                          .descriptorSetCount = 1,
                                          .pSetLayouts = &layout};
  if (VkResult r = api.AllocateDescriptorSets(api.device(), &alloc, &st.set); r != VK_SUCCESS) {
    return vk_error(std::string(kWho) + ": vkAllocateDescriptorSets", r);
  }
  return Status::success();
}

Status bind_deferred_inputs(State& st, const deferred::ShadingOptions& o,
                            const AdaptiveThresholds* a, const deferred::EdgePerSampleOptions* e) {
  if (st.framebuffer.get() == VK_NULL_HANDLE) {
    return Status::error(ErrorCode::invalid_argument, std::string(kWho) + ": no G-buffer yet");
  }
  if (o.filter != texture::TextureFilter::anisotropic) {
    return Status::error(
        ErrorCode::unsupported,
        std::string(kWho) + ": only TextureFilter::anisotropic shading is implemented");
  }
  const deferred::GpuParams p = deferred::gpu_params(st.camera, st.w, st.h, st.m, o, a, e);
  const std::vector<float> lights = deferred::gpu_lights(o), waves = deferred::gpu_waves(o);
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  for (Status s :
       {write_host(st, st.params, &p, sizeof p, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, "parameters"),
        write_host(st, st.lights, lights.data(), lights.size() * 4, storage, "lights"),
        write_host(st, st.waves, waves.data(), waves.size() * 4, storage, "waves"),
        size_pass_buffers(st)}) {
    if (!s.ok()) return s;
  }
  if (!st.set_written) return write_set(st);
  return Status::success();
}

void record_full_barrier(const Api& api, VkCommandBuffer cmd) {
  Barrier b;
  b.memory(VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
           VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
           VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
  b.record(api, cmd);
}

void record_host_read_barrier(const Api& api, VkCommandBuffer cmd) {
  Barrier h;
  h.memory(VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
           VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
  h.record(api, cmd);
}

void record_gbuffer_readable(State& st, VkCommandBuffer cmd) {
  if (st.g_layout == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL) return;
  Barrier b;
  for (const Image& g : st.g) {
    b.image(g.get(), st.g_layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
            VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  }
  b.record(*st.api, cmd);
  st.g_layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
}

void record_timestamp(State& st, VkCommandBuffer cmd, std::uint32_t query) {
  if (st.device->timestamp_ms_per_tick() <= 0.0) return;
  if (query == 0) st.api->CmdResetQueryPool(cmd, st.queries.get(), 0, 2);
  write_timestamp(*st.api, cmd, st.queries.get(), query);
}

double timestamp_ms(const State& st) {
  const double per_tick = st.device->timestamp_ms_per_tick();
  if (per_tick <= 0.0) return std::nan("");
  std::uint64_t ticks[2] = {0, 0};
  if (st.api->GetQueryPoolResults(st.api->device(), st.queries.get(), 0, 2, sizeof ticks, ticks, 8,
                                  VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT) !=
      VK_SUCCESS) {
    return std::nan("");
  }
  const std::uint32_t bits = st.api->queue_family.timestampValidBits;
  const std::uint64_t mask = bits >= 64 ? ~0ull : (1ull << bits) - 1;
  return double((ticks[1] - ticks[0]) & mask) * per_tick;
}

Status run_deferred_pass(State& st, const std::string& name,
                         const std::vector<std::string>& defines, std::vector<PassTime>& passes) {
  Result<VkPipeline> p = program(st, defines);
  if (!p) return p.status();
  Result<VkCommandBuffer> cmd = st.device->begin();
  if (!cmd) return cmd.status();
  const Api& api = *st.api;
  record_full_barrier(api, *cmd);
  record_gbuffer_readable(st, *cmd);
  record_timestamp(st, *cmd, 0);
  api.CmdBindPipeline(*cmd, VK_PIPELINE_BIND_POINT_COMPUTE, *p);
  api.CmdBindDescriptorSets(*cmd, VK_PIPELINE_BIND_POINT_COMPUTE, st.passes_layout.get(), 0, 1,
                            &st.set, 0, nullptr);
  api.CmdDispatch(*cmd, std::uint32_t((st.w + 7) / 8), std::uint32_t((st.h + 7) / 8), 1);
  record_timestamp(st, *cmd, 1);
  const auto wall0 = std::chrono::steady_clock::now();
  if (Status s = st.device->submit_and_wait(*cmd); !s.ok()) return s;
  passes.push_back({name, elapsed_ms(wall0), timestamp_ms(st)});
  return Status::success();
}

Status read_pass_buffer(State& st, int index, std::size_t bytes, void* out) {
  Result<VkCommandBuffer> cmd = st.device->begin();
  if (!cmd) return cmd.status();
  const Api& api = *st.api;
  record_full_barrier(api, *cmd);
  const VkBufferCopy copy{0, 0, bytes};
  api.CmdCopyBuffer(*cmd, st.pass[std::size_t(index)].get(), st.readback.get(), 1, &copy);
  record_host_read_barrier(api, *cmd);
  if (Status s = st.device->submit_and_wait(*cmd); !s.ok()) return s;
  st.readback.invalidate();
  std::memcpy(out, st.readback.mapped(), bytes);
  return Status::success();
}

}  // namespace tessera::vk
