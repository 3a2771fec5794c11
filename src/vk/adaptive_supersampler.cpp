// vk::AdaptiveSupersampler: Vulkan's device and option checks (the shared checks and GLSL are
// src/adaptive/), each pass's GLSL compiled to SPIR-V, then the Vulkan objects
// (adaptive_objects.cpp).
#include <algorithm>
#include <cmath>

#include "tessera/glsl.h"
#include "vk/adaptive_internal.h"
#include "vk/shader.h"
#include "vk/shader_binary.h"

namespace tessera::vk {

namespace {

using State = AdaptiveSupersampler::State;

constexpr const char* kWho = "vk adaptive supersampler";

Status invalid(const std::string& what) {
  return Status::error(ErrorCode::invalid_argument, std::string(kWho) + ": " + what);
}
Status unsupported(const std::string& what) {
  return Status::error(ErrorCode::unsupported, std::string(kWho) + ": " + what);
}
Status too_large(const std::string& what) {
  return Status::error(ErrorCode::too_large, std::string(kWho) + ": " + what);
}

/// A storage-image format the device must support (optimal tiling).
Status check_storage_format(const State& st, VkFormat f, const char* name) {
  VkFormatProperties p{};
  st.api.GetPhysicalDeviceFormatProperties(st.api.ctx.physical_device, f, &p);
  if ((p.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT) == 0) {
    return unsupported(std::string("the device cannot store to ") + name + " images");
  }
  return Status::success();
}

/// Checks everything that needs no Vulkan object; fills the state's derived fields.
Status check_options(State& st) {
  const AdaptiveSupersamplerOptions& o = st.options;
  if (Status s = adaptive::check_options(o, kWho, st.derived); !s.ok()) return s;
  if (o.frames_in_flight < 1 || o.frames_in_flight > 16) {
    return invalid("frames_in_flight = " + std::to_string(o.frames_in_flight) + " (1..16)");
  }
  for (std::size_t i = 0; i < o.hook_set_layouts.size(); ++i) {
    if (o.hook_set_layouts[i] == VK_NULL_HANDLE) {
      return invalid("hook_set_layouts[" + std::to_string(i) + "] is VK_NULL_HANDLE");
    }
  }
  st.set_index = std::uint32_t(o.hook_set_layouts.size());
  const VkPhysicalDeviceLimits& lim = st.api.properties.limits;
  if (st.set_index + 1 > lim.maxBoundDescriptorSets) {
    return unsupported(std::to_string(st.set_index) +
                       " hook sets + 1 exceed maxBoundDescriptorSets = " +
                       std::to_string(lim.maxBoundDescriptorSets));
  }
  if (std::uint64_t(o.m) * std::uint64_t(o.width) > lim.maxImageDimension2D ||
      std::uint64_t(o.m) * std::uint64_t(o.height) > lim.maxImageDimension2D) {
    return too_large("G-buffer " + std::to_string(o.m * o.width) + "x" +
                     std::to_string(o.m * o.height) +
                     " exceeds maxImageDimension2D = " + std::to_string(lim.maxImageDimension2D));
  }
  const std::uint32_t gx = std::uint32_t((o.width + 7) / 8), gy = std::uint32_t((o.height + 7) / 8);
  if (gx > lim.maxComputeWorkGroupCount[0] || gy > lim.maxComputeWorkGroupCount[1]) {
    return too_large("output " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                     " exceeds maxComputeWorkGroupCount");
  }
  const std::size_t work_bytes = adaptive::work_buffer_bytes(o);
  if (work_bytes > lim.maxStorageBufferRange) {
    return too_large(
        "work buffer of " + std::to_string(work_bytes) +
        " bytes exceeds maxStorageBufferRange = " + std::to_string(lim.maxStorageBufferRange));
  }
  st.derived.list_capacity = adaptive::list_capacity(
      o, st.derived.n, (std::size_t(lim.maxStorageBufferRange) - 16) / adaptive::kListItemBytes);
  // Without fp64 the depth metric accumulates in float; tile_list beyond the device's shared
  // memory runs `loop` (the same image).
  st.derived.float64 = st.api.ctx.enabled_features.shaderFloat64 == VK_TRUE;
  if (st.derived.tile &&
      adaptive::tile_shared_bytes(st.derived.n) > lim.maxComputeSharedMemorySize) {
    st.derived.tile = false;
  }
  if (o.sample_count_texture) {
    if (!st.api.ctx.enabled_features.shaderStorageImageExtendedFormats) {
      return unsupported(
          "sample_count_texture needs the device feature shaderStorageImageExtendedFormats "
          "(r8ui storage images), not enabled in DeviceContext::enabled_features");
    }
    if (Status s = check_storage_format(st, VK_FORMAT_R8_UINT, "R8_UINT"); !s.ok()) return s;
  }
  const bool f32 = o.output == AdaptiveOutputFormat::rgba32f;
  return check_storage_format(st,
                              f32 ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_R16G16B16A16_SFLOAT,
                              f32 ? "R32G32B32A32_SFLOAT" : "R16G16B16A16_SFLOAT");
}

/// One pass's GLSL, expanded (the preamble, the hook, tessera's files).
Result<glsl::Expanded> expand(const State& st, const std::string& pass) {
  adaptive::GlslBindings b;
  b.set = int(st.set_index);
  b.gbuffer = int(kBindGBuffer);
  b.params = int(kBindParams);
  b.work = int(kBindWork);
  b.image = int(kBindColour);
  const glsl::Source src = adaptive::pass_source(st.options, pass);
  const glsl::ExpandOptions eo = adaptive::pass_expand_options(st.options, st.derived, b, pass);
  Result<glsl::Expanded> e = glsl::expand_includes(src, eo);
  if (!e) return Status::error(e.status().code, std::string(kWho) + ": " + e.status().message);
  return e;
}

/// Every pass's SPIR-V: from the options' shader binary when its key matches, else compiled
/// (a compile error is "vk adaptive supersampler: HOOK:LINE: message"); the binary kept.
Status make_spirv(State& st) {
  std::map<std::string, glsl::Expanded> expanded;
  std::map<std::string, std::string> texts;
  const std::vector<std::string> passes = adaptive::pass_programs(st.options.schedule);
  for (const std::string& p : passes) {
    Result<glsl::Expanded> e = expand(st, p);
    if (!e) return e.status();
    texts.emplace(p, e->text);
    expanded.emplace(p, std::move(*e));
  }
  const std::uint64_t key = shader_key(texts);
  if (!st.options.shader_binary.empty()) {
    auto spirv = read_shader_binary(st.options.shader_binary, key, passes);
    if (!spirv) {
      return Status::error(spirv.status().code, std::string(kWho) + ": " + spirv.status().message);
    }
    st.spirv = std::move(*spirv);
  } else {
    for (const std::string& p : passes) {
      const glsl::Expanded& e = expanded.at(p);
      Result<std::vector<std::uint32_t>> spirv = compile_compute_spirv(e.text);
      if (!spirv) {
        return Status::error(
            spirv.status().code,
            std::string(kWho) + ": " + glsl::format_log(spirv.status().message, e.files));
      }
      st.spirv.emplace(p, std::move(*spirv));
    }
  }
  st.binary = write_shader_binary(key, st.spirv);
  return Status::success();
}

}  // namespace

Status create_adaptive_objects(State& st);  // adaptive_objects.cpp

double AdaptiveProfile::total_ms() const {
  double t = 0;
  for (const PassTime& p : passes) t += p.ms;
  return t;
}

AdaptiveSupersampler::~AdaptiveSupersampler() = default;

const AdaptiveSupersamplerOptions& AdaptiveSupersampler::options() const { return state_->options; }
std::uint32_t AdaptiveSupersampler::descriptor_set_index() const { return state_->set_index; }
AdaptiveSchedule AdaptiveSupersampler::schedule() const {
  const State& st = *state_;
  if (st.options.schedule == AdaptiveSchedule::tile_list && !st.derived.tile) {
    return AdaptiveSchedule::loop;
  }
  return st.options.schedule;
}
bool AdaptiveSupersampler::float64() const { return state_->derived.float64; }
const std::vector<std::uint8_t>& AdaptiveSupersampler::shader_binary() const {
  return state_->binary;
}

void AdaptiveSupersampler::set_thresholds(const AdaptiveThresholds& thresholds) {
  state_->options.thresholds = thresholds;  // recorded with the next record
}

Result<std::unique_ptr<AdaptiveSupersampler>> AdaptiveSupersampler::create(
    const DeviceContext& device, const AdaptiveSupersamplerOptions& options) {
  auto st = std::make_unique<State>();
  st->options = options;
  Result<Api> api = load_api(device);
  if (!api)
    return Status::error(api.status().code, std::string(kWho) + ": " + api.status().message);
  st->api = std::move(*api);
  if (Status s = check_options(*st); !s.ok()) return s;
  if (Status s = make_spirv(*st); !s.ok()) return s;
  if (Status s = create_adaptive_objects(*st); !s.ok()) return s;
  st->spirv.clear();
  std::unique_ptr<AdaptiveSupersampler> r(new AdaptiveSupersampler());
  r->state_ = std::move(st);
  return r;
}

}  // namespace tessera::vk
