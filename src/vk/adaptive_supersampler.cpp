// vk::AdaptiveSupersampler: Vulkan's device and option checks (the shared checks and GLSL are
// src/adaptive/), each pass's GLSL compiled to SPIR-V, then the Vulkan objects
// (adaptive_objects.cpp).
#include <algorithm>
#include <cmath>

#include "tessera/glsl.h"
#include "vk/adaptive_internal.h"
#include "vk/embedded_passes.h"
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

/// What of `api`'s device decides the shaders.
AdaptiveShaderTarget target_of(const Api& api) {
  AdaptiveShaderTarget t;
  t.float64 = api.ctx.enabled_features.shaderFloat64 == VK_TRUE;
  t.max_compute_shared_memory_size = api.properties.limits.maxComputeSharedMemorySize;
  t.max_storage_buffer_range = api.properties.limits.maxStorageBufferRange;
  return t;
}

/// The derived fields a device decides: the frame list's capacity; without fp64 the depth
/// metric accumulates in float; tile_list beyond the device's shared memory runs `loop` (the
/// same image).
void apply_target(const AdaptiveSupersamplerOptions& o, const AdaptiveShaderTarget& t,
                  adaptive::Derived& d) {
  d.list_capacity = adaptive::list_capacity(
      o, d.n, (std::size_t(t.max_storage_buffer_range) - 16) / adaptive::kListItemBytes);
  d.float64 = t.float64;
  if (d.tile && adaptive::tile_shared_bytes(d.n) > t.max_compute_shared_memory_size) {
    d.tile = false;
  }
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
  apply_target(o, target_of(st.api), st.derived);
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
Result<glsl::Expanded> expand(const AdaptiveSupersamplerOptions& o, const adaptive::Derived& d,
                              std::uint32_t set_index, const std::string& pass) {
  adaptive::GlslBindings b;
  b.set = int(set_index);
  b.gbuffer = int(kBindGBuffer);
  b.params = int(kBindParams);
  b.work = int(kBindWork);
  b.image = int(kBindColour);
  const glsl::Source src = adaptive::pass_source(o, pass);
  const glsl::ExpandOptions eo = adaptive::pass_expand_options(o, d, b, pass);
  Result<glsl::Expanded> e = glsl::expand_includes(src, eo);
  if (!e) return Status::error(e.status().code, std::string(kWho) + ": " + e.status().message);
  return e;
}

/// Every pass's GLSL, expanded, and the shader binary's key of them.
struct ExpandedPasses {
  std::uint32_t set_index = 0;
  std::vector<std::string> passes;
  std::map<std::string, glsl::Expanded> expanded;
  std::uint64_t key = 0;
};
Result<ExpandedPasses> expand_all(const AdaptiveSupersamplerOptions& o, const adaptive::Derived& d,
                                  std::uint32_t set_index) {
  ExpandedPasses x;
  x.set_index = set_index;
  x.passes = adaptive::pass_programs(o.schedule);
  std::map<std::string, std::string> texts;
  for (const std::string& p : x.passes) {
    Result<glsl::Expanded> e = expand(o, d, set_index, p);
    if (!e) return e.status();
    texts.emplace(p, e->text);
    x.expanded.emplace(p, std::move(*e));
  }
  x.key = shader_key(texts);
  return x;
}

/// Every pass's SPIR-V: the embedded ones' (embedded_passes.h) in the component's set (METRICS
/// and LIST: their variant for `o` and `d`, its samplers bound to the layout's slots), the
/// others compiled (a compile error is "vk adaptive supersampler: HOOK:LINE: message").
Result<ShaderPasses> compile_all(const AdaptiveSupersamplerOptions& o, const adaptive::Derived& d,
                                 const ExpandedPasses& x) {
  ShaderPasses spirv;
  const auto samplers = adaptive::specialized_samplers(o, kBindGBuffer);
  for (const std::string& p : x.passes) {
    const bool specialized = p == "METRICS" || p == "LIST";
    const std::string name = adaptive::specialized_variant(o, d, p);
    std::vector<std::uint32_t> words =
        specialized ? embedded_pass(name, x.set_index, samplers) : embedded_pass(name, x.set_index);
    if (!words.empty()) {
      spirv.emplace(p, std::move(words));
      continue;
    }
    const glsl::Expanded& e = x.expanded.at(p);
    Result<std::vector<std::uint32_t>> code = compile_compute_spirv(e.text);
    if (!code) {
      return Status::error(
          code.status().code,
          std::string(kWho) + ": " + glsl::format_log(code.status().message, e.files));
    }
    spirv.emplace(p, std::move(*code));
  }
  return spirv;
}

/// Every pass's SPIR-V: from the options' shader binary when it has an entry for these options
/// and this device, else compiled; the binary of this device kept.
Status make_spirv(State& st) {
  Result<ExpandedPasses> x = expand_all(st.options, st.derived, st.set_index);
  if (!x) return x.status();
  if (!st.options.shader_binary.empty()) {
    auto spirv = read_shader_binary(st.options.shader_binary, x->key, x->passes);
    if (!spirv) {
      return Status::error(spirv.status().code, std::string(kWho) + ": " + spirv.status().message);
    }
    st.spirv = std::move(*spirv);
  } else {
    Result<ShaderPasses> spirv = compile_all(st.options, st.derived, *x);
    if (!spirv) return spirv.status();
    st.spirv = std::move(*spirv);
  }
  st.binary = write_shader_binary({{x->key, st.spirv}});
  return Status::success();
}

}  // namespace

Status create_adaptive_objects(State& st);  // adaptive_objects.cpp

double AdaptiveProfile::total_gpu_ms() const { return tessera::total_gpu_ms(passes); }

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

Result<std::vector<std::uint8_t>> AdaptiveSupersampler::compile_shader_binary(
    const AdaptiveSupersamplerOptions& options, const std::vector<AdaptiveShaderTarget>& targets) {
  if (targets.empty()) return invalid("compile_shader_binary: no device target");
  std::vector<ShaderBinaryEntry> entries;
  for (const AdaptiveShaderTarget& t : targets) {
    adaptive::Derived d;
    if (Status s = adaptive::check_options(options, kWho, d); !s.ok()) return s;
    apply_target(options, t, d);
    Result<ExpandedPasses> x =
        expand_all(options, d, std::uint32_t(options.hook_set_layouts.size()));
    if (!x) return x.status();
    const bool known = std::any_of(entries.begin(), entries.end(),
                                   [&](const ShaderBinaryEntry& e) { return e.key == x->key; });
    if (known) continue;  // another target with the same shaders
    Result<ShaderPasses> spirv = compile_all(options, d, *x);
    if (!spirv) return spirv.status();
    entries.push_back({x->key, std::move(*spirv)});
  }
  return write_shader_binary(entries);
}

Result<AdaptiveShaderTarget> AdaptiveSupersampler::shader_target(const DeviceContext& device) {
  Result<Api> api = load_api(device);
  if (!api) {
    return Status::error(api.status().code, std::string(kWho) + ": " + api.status().message);
  }
  return target_of(*api);
}

}  // namespace tessera::vk
