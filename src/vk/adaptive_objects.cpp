// vk::AdaptiveSupersampler's Vulkan objects: the immutable sampler, the descriptor-set and
// pipeline layouts, one compute pipeline per pass, the buffers, the output images, the
// descriptor pool and its sets (one per G-buffer view combination), the profile's queries.
#include <algorithm>

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
  for (const auto& [pass, spirv] : st.spirv) {
    Result<Pipeline> p =
        create_compute_pipeline(api, spirv, st.pipeline_layout.get(), kWhat + " (" + pass + ")");
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
  const VkExtent2D extent{std::uint32_t(o.width), std::uint32_t(o.height)};
  const VkImageUsageFlags usage =
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  Result<Image> colour =
      Image::create(api,
                    o.output == AdaptiveOutputFormat::rgba32f ? VK_FORMAT_R32G32B32A32_SFLOAT
                                                              : VK_FORMAT_R16G16B16A16_SFLOAT,
                    extent, usage, kWhat + ": output image");
  if (!colour) return colour.status();
  st.colour = std::move(*colour);
  if (o.sample_count_texture) {
    Result<Image> counts =
        Image::create(api, VK_FORMAT_R8_UINT, extent, usage, kWhat + ": sample-count image");
    if (!counts) return counts.status();
    st.counts = std::move(*counts);
  }
  if (o.profile) {
    Result<Buffer> rb = Buffer::create(api, 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true,
                                       kWhat + ": profile read-back");
    if (!rb) return rb.status();
    st.readback = std::move(*rb);
    st.query_capacity = 32;  // the budget's 17 passes + 7 others, and the start
    VkQueryPoolCreateInfo qi{};
    qi.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
    qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
    qi.queryCount = st.query_capacity;
    VkQueryPool pool = VK_NULL_HANDLE;
    if (VkResult r = api.CreateQueryPool(api.device(), &qi, api.alloc(), &pool); r != VK_SUCCESS) {
      return vk_error(kWhat + ": vkCreateQueryPool", r);
    }
    st.queries = QueryPool(api, pool);
    st.timestamps = api.queue_family.timestampValidBits > 0;
  }
  return Status::success();
}

Status create_sets(State& st) {
  const Api& api = st.api;
  const std::uint32_t count = std::uint32_t(st.options.descriptor_sets);
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, count},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2 * count},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 2 * count},
                                        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4 * count}};
  VkDescriptorPoolCreateInfo pi{};
  pi.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  pi.maxSets = count;
  pi.poolSizeCount = 4;
  pi.pPoolSizes = sizes;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  if (VkResult r = api.CreateDescriptorPool(api.device(), &pi, api.alloc(), &pool);
      r != VK_SUCCESS) {
    return vk_error(kWhat + ": vkCreateDescriptorPool", r);
  }
  st.pool = DescriptorPool(api, pool);
  std::vector<VkDescriptorSetLayout> layouts(count, st.set_layout.get());
  std::vector<VkDescriptorSet> sets(count);
  VkDescriptorSetAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  ai.descriptorPool = pool;
  ai.descriptorSetCount = count;
  ai.pSetLayouts = layouts.data();
  if (VkResult r = api.AllocateDescriptorSets(api.device(), &ai, sets.data()); r != VK_SUCCESS) {
    return vk_error(kWhat + ": vkAllocateDescriptorSets", r);
  }
  // The component's own resources, the same in every set.
  const VkDescriptorBufferInfo params{st.params.get(), 0, VK_WHOLE_SIZE};
  const VkDescriptorBufferInfo work{st.work.get(), 0, VK_WHOLE_SIZE};
  const VkDescriptorBufferInfo list{st.list.get(), 0, VK_WHOLE_SIZE};
  const VkDescriptorImageInfo colour{VK_NULL_HANDLE, st.colour.view(), VK_IMAGE_LAYOUT_GENERAL};
  const VkDescriptorImageInfo counts{VK_NULL_HANDLE, st.counts.view(), VK_IMAGE_LAYOUT_GENERAL};
  for (VkDescriptorSet set : sets) {
    std::vector<VkWriteDescriptorSet> w;
    auto write = [&](std::uint32_t binding, VkDescriptorType type, const VkDescriptorBufferInfo* bi,
                     const VkDescriptorImageInfo* ii) {
      VkWriteDescriptorSet x{};
      x.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
      x.dstSet = set;
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
    api.UpdateDescriptorSets(api.device(), std::uint32_t(w.size()), w.data(), 0, nullptr);
    State::Set entry;
    entry.set = set;
    st.sets.push_back(entry);
  }
  return Status::success();
}

}  // namespace

VkImageLayout adaptive_read_layout(VkImageLayout layout) {
  return layout == VK_IMAGE_LAYOUT_GENERAL ? VK_IMAGE_LAYOUT_GENERAL
                                           : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
}

Status create_adaptive_objects(State& st) {
  if (Status s = create_layouts(st); !s.ok()) return s;
  if (Status s = create_resources(st); !s.ok()) return s;
  return create_sets(st);
}

VkDescriptorSet acquire_adaptive_set(State& st, const AdaptiveFrame& f) {
  std::array<VkImageView, 4> views{};
  std::array<VkImageLayout, 4> layouts{};
  for (std::size_t s = 0; s < 4; ++s) {
    if (!st.derived.slot_used[s]) continue;
    views[s] = f.gbuffer[s].view;
    layouts[s] = adaptive_read_layout(f.gbuffer[s].layout);
  }
  ++st.records;
  for (State::Set& set : st.sets) {
    if (set.used != 0 && set.views == views && set.layouts == layouts) {
      set.used = st.records;
      return set.set;
    }
  }
  // The least recently used set takes the new views (see descriptor_sets in vk_adaptive.h).
  State::Set& set =
      *std::min_element(st.sets.begin(), st.sets.end(),
                        [](const State::Set& a, const State::Set& b) { return a.used < b.used; });
  std::vector<VkDescriptorImageInfo> infos;
  infos.reserve(4);
  std::vector<VkWriteDescriptorSet> w;
  for (std::uint32_t s = 0; s < 4; ++s) {
    if (!st.derived.slot_used[s]) continue;
    const ImageResource& img = f.gbuffer[s];
    infos.push_back({VK_NULL_HANDLE, img.view, layouts[s]});
    VkWriteDescriptorSet x{};
    x.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    x.dstSet = set.set;
    x.dstBinding = kBindGBuffer + s;
    x.descriptorCount = 1;
    x.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    x.pImageInfo = &infos.back();
    w.push_back(x);
  }
  st.api.UpdateDescriptorSets(st.api.device(), std::uint32_t(w.size()), w.data(), 0, nullptr);
  set.views = views;
  set.layouts = layouts;
  set.used = st.records;
  return set.set;
}

}  // namespace tessera::vk
