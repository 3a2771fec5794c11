// vk::AdaptiveSupersampler's Vulkan objects: the immutable sampler, the descriptor-set and
// pipeline layouts, one compute pipeline per pass, the shared buffers; per (frame slot, view)
// the descriptor set (from pools grown kSetsPerPool at a time), the output images and the
// profile's queries and read-back, made at the view's first record.
#include <algorithm>
#include <cstring>

#include "vk/adaptive_internal.h"
#include "vk/shader.h"

namespace tessera::vk {

namespace {

using State = AdaptiveSupersampler::State;
const std::string kWhat = "vk adaptive supersampler";

Status create_layouts(State& st) {
  const Api& api = st.api;
  VkSamplerCreateInfo si{};
  si.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
  si.magFilter = VK_FILTER_NEAREST;
  si.minFilter = VK_FILTER_NEAREST;
  si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  si.maxLod = 0.0f;
  VkSampler sampler = VK_NULL_HANDLE;
  if (VkResult r = api.CreateSampler(api.device(), &si, api.alloc(), &sampler); r != VK_SUCCESS) {
    return vk_error(kWhat + ": vkCreateSampler", r);
  }
  st.sampler = Sampler(api, sampler);
  const VkSampler immutable = st.sampler.get();
  std::vector<VkDescriptorSetLayoutBinding> b;
  auto add = [&](std::uint32_t binding, VkDescriptorType type) {
    VkDescriptorSetLayoutBinding x{};
    x.binding = binding;
    x.descriptorType = type;
    x.descriptorCount = 1;
    x.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    if (type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER) x.pImmutableSamplers = &immutable;
    b.push_back(x);
  };
  add(kBindParams, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
  add(kBindWork, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  add(kBindList, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  add(kBindColour, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
  if (st.options.sample_count_texture) add(kBindCounts, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
  for (std::uint32_t s = 0; s < 4; ++s) {
    if (st.derived.slot_used[s]) add(kBindGBuffer + s, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
  }
  VkDescriptorSetLayoutCreateInfo li{};
  li.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  li.bindingCount = std::uint32_t(b.size());
  li.pBindings = b.data();
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  if (VkResult r = api.CreateDescriptorSetLayout(api.device(), &li, api.alloc(), &set_layout);
      r != VK_SUCCESS) {
    return vk_error(kWhat + ": vkCreateDescriptorSetLayout", r);
  }
  st.set_layout = SetLayout(api, set_layout);
  std::vector<VkDescriptorSetLayout> sets = st.options.hook_set_layouts;
  sets.push_back(st.set_layout.get());
  VkPipelineLayoutCreateInfo pi{};
  pi.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  pi.setLayoutCount = std::uint32_t(sets.size());
  pi.pSetLayouts = sets.data();
  VkPipelineLayout layout = VK_NULL_HANDLE;
  if (VkResult r = api.CreatePipelineLayout(api.device(), &pi, api.alloc(), &layout);
      r != VK_SUCCESS) {
    return vk_error(kWhat + ": vkCreatePipelineLayout", r);
  }
  st.pipeline_layout = PipelineLayout(api, layout);
  // The built-in METRICS and LIST read m and the layout as specialization constants (ids a
  // module does not declare are ignored: the same info serves every pass).
  const std::vector<adaptive::SpecConstant> constants = adaptive::specialization(st.options);
  std::vector<VkSpecializationMapEntry> entries;
  std::vector<std::uint32_t> values;
  for (const adaptive::SpecConstant& c : constants) {
    entries.push_back({c.id, std::uint32_t(values.size() * 4), 4});
    values.push_back(c.bits);
  }
  VkSpecializationInfo specialization{std::uint32_t(entries.size()), entries.data(),
                                      values.size() * 4, values.data()};
  for (const auto& [pass, spirv] : st.spirv) {
    Result<Pipeline> p =
        create_compute_pipeline(api, spirv, st.pipeline_layout.get(), kWhat + " (" + pass + ")",
                                st.options.pipeline_cache, &specialization);
    if (!p) return p.status();
    st.pipelines.emplace(pass, std::move(*p));
  }
  return Status::success();
}

Status create_resources(State& st) {
  const Api& api = st.api;
  const AdaptiveSupersamplerOptions& o = st.options;
  Result<Buffer> params =
      Buffer::create(api, sizeof(adaptive::Params),
                     VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false,
                     kWhat + ": parameter block");
  if (!params) return params.status();
  st.params = std::move(*params);
  Result<Buffer> work =
      Buffer::create(api, adaptive::work_buffer_bytes(o),
                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                         VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                     false, kWhat + ": work buffer");
  if (!work) return work.status();
  st.work = std::move(*work);
  // std430: the items (8 bytes each), the colours from the next multiple of 16 bytes.
  const std::size_t items = st.derived.list_capacity;
  Result<Buffer> list =
      Buffer::create(api, (items * 8 + 15) / 16 * 16 + items * 16,
                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false, kWhat + ": frame list");
  if (!list) return list.status();
  st.list = std::move(*list);
  if (o.profile) {
    st.query_capacity = 32;  // the start, the budget's 17 passes + 5 others
    st.timestamps = api.queue_family.timestampValidBits > 0;
  }
  st.frames.resize(o.frames_in_flight);
  return Status::success();
}

/// One more descriptor set of the component's layout (a new pool of kSetsPerPool when full).
Result<VkDescriptorSet> allocate_set(State& st) {
  const Api& api = st.api;
  if (st.pool_sets_left == 0) {
    const std::uint32_t n = kSetsPerPool;
    const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, n},
                                          {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2 * n},
                                          {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 2 * n},
                                          {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4 * n}};
    VkDescriptorPoolCreateInfo pi{};
    pi.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    pi.maxSets = n;
    pi.poolSizeCount = 4;
    pi.pPoolSizes = sizes;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    if (VkResult r = api.CreateDescriptorPool(api.device(), &pi, api.alloc(), &pool);
        r != VK_SUCCESS) {
      return vk_error(kWhat + ": vkCreateDescriptorPool", r);
    }
    st.pools.emplace_back(api, pool);
    st.pool_sets_left = n;
  }
  const VkDescriptorSetLayout layout = st.set_layout.get();
  VkDescriptorSetAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  ai.descriptorPool = st.pools.back().get();
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &layout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  if (VkResult r = api.AllocateDescriptorSets(api.device(), &ai, &set); r != VK_SUCCESS) {
    return vk_error(kWhat + ": vkAllocateDescriptorSets", r);
  }
  --st.pool_sets_left;
  return set;
}

/// A new view's descriptor set and, with `profile`, its query pool and read-back buffer.
Status create_view(State& st, State::View& v) {
  const Api& api = st.api;
  Result<VkDescriptorSet> set = allocate_set(st);
  if (!set) return set.status();
  v.set = *set;
  if (!st.options.profile) return Status::success();
  const std::size_t bytes = kReadbackTicks + 8 * std::size_t(st.query_capacity);
  Result<Buffer> rb = Buffer::create(api, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true,
                                     kWhat + ": profile read-back");
  if (!rb) return rb.status();
  v.readback = std::move(*rb);
  std::memset(v.readback.mapped(), 0, bytes);
  v.readback.flush();
  VkQueryPoolCreateInfo qi{};
  qi.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
  qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
  qi.queryCount = st.query_capacity;
  VkQueryPool pool = VK_NULL_HANDLE;
  if (VkResult r = api.CreateQueryPool(api.device(), &qi, api.alloc(), &pool); r != VK_SUCCESS) {
    return vk_error(kWhat + ": vkCreateQueryPool", r);
  }
  v.queries = QueryPool(api, pool);
  return Status::success();
}

/// The view's own output images (largest size), made when first needed.
Status create_outputs(State& st, State::View& v, bool colour) {
  const Api& api = st.api;
  const AdaptiveSupersamplerOptions& o = st.options;
  const VkExtent2D extent{std::uint32_t(o.width), std::uint32_t(o.height)};
  const VkImageUsageFlags usage =
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  if (colour && v.colour.get() == VK_NULL_HANDLE) {
    Result<Image> img =
        Image::create(api, adaptive_output_format(o), extent, usage, kWhat + ": output image");
    if (!img) return img.status();
    v.colour = std::move(*img);
  }
  if (o.sample_count_texture && v.counts.get() == VK_NULL_HANDLE) {
    Result<Image> img =
        Image::create(api, VK_FORMAT_R8_UINT, extent, usage, kWhat + ": sample-count image");
    if (!img) return img.status();
    v.counts = std::move(*img);
  }
  return Status::success();
}

/// Writes every binding of the view's set: the shared buffers, this record's outputs and
/// G-buffer views.
void write_view_set(State& st, const State::View& v, const AdaptiveFrame& f) {
  const VkDescriptorBufferInfo params{st.params.get(), 0, VK_WHOLE_SIZE};
  const VkDescriptorBufferInfo work{st.work.get(), 0, VK_WHOLE_SIZE};
  const VkDescriptorBufferInfo list{st.list.get(), 0, VK_WHOLE_SIZE};
  const VkImageView out = f.output.image != VK_NULL_HANDLE ? f.output.view : v.colour.view();
  const VkDescriptorImageInfo colour{VK_NULL_HANDLE, out, VK_IMAGE_LAYOUT_GENERAL};
  const VkDescriptorImageInfo counts{VK_NULL_HANDLE, v.counts.view(), VK_IMAGE_LAYOUT_GENERAL};
  std::array<VkDescriptorImageInfo, 4> gbuffer{};
  std::vector<VkWriteDescriptorSet> w;
  auto write = [&](std::uint32_t binding, VkDescriptorType type, const VkDescriptorBufferInfo* bi,
                   const VkDescriptorImageInfo* ii) {
    VkWriteDescriptorSet x{};
    x.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    x.dstSet = v.set;
    x.dstBinding = binding;
    x.descriptorCount = 1;
    x.descriptorType = type;
    x.pBufferInfo = bi;
    x.pImageInfo = ii;
    w.push_back(x);
  };
  write(kBindParams, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &params, nullptr);
  write(kBindWork, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &work, nullptr);
  write(kBindList, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &list, nullptr);
  write(kBindColour, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, nullptr, &colour);
  if (st.options.sample_count_texture) {
    write(kBindCounts, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, nullptr, &counts);
  }
  for (std::uint32_t s = 0; s < 4; ++s) {
    if (!st.derived.slot_used[s]) continue;
    const ImageResource& img = f.gbuffer[s];
    gbuffer[s] = {VK_NULL_HANDLE, img.view, adaptive_read_layout(img.layout)};
    write(kBindGBuffer + s, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, nullptr, &gbuffer[s]);
  }
  st.api.UpdateDescriptorSets(st.api.device(), std::uint32_t(w.size()), w.data(), 0, nullptr);
}

}  // namespace

VkImageLayout adaptive_read_layout(VkImageLayout layout) {
  return layout == VK_IMAGE_LAYOUT_GENERAL ? VK_IMAGE_LAYOUT_GENERAL
                                           : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
}

VkFormat adaptive_output_format(const AdaptiveCommonOptions& o) {
  return o.output == AdaptiveOutputFormat::rgba32f ? VK_FORMAT_R32G32B32A32_SFLOAT
                                                   : VK_FORMAT_R16G16B16A16_SFLOAT;
}

Status create_adaptive_objects(State& st) {
  if (Status s = create_layouts(st); !s.ok()) return s;
  return create_resources(st);
}

Result<State::View*> acquire_adaptive_view(State& st, const AdaptiveFrame& f) {
  std::deque<State::View>& views = st.frames[st.slot];
  if (views.size() <= st.views) {
    State::View v;
    if (Status s = create_view(st, v); !s.ok()) return s;
    views.push_back(std::move(v));
  }
  State::View& v = views[st.views];
  if (Status s = create_outputs(st, v, f.output.image == VK_NULL_HANDLE); !s.ok()) return s;
  write_view_set(st, v, f);
  return &v;
}

}  // namespace tessera::vk
