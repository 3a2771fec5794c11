// Internal to the library: the host side of the adaptive supersampler that does not depend on
// the GPU API, written once for gl::AdaptiveSupersampler (src/gl/adaptive*) and
// vk::AdaptiveSupersampler (src/vk/adaptive*): the option checks with their one-line errors,
// the derived sizes, the GLSL preamble and source of each pass (adaptive_component.glsl), the
// parameter block, the work header and the order of a frame's passes. GL-free, Vulkan-free
// (core `tessera` library). Tests: the backends' (tests/gl/gl_adaptive*, tests/vk/vk_adaptive*).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/adaptive_supersampler.h"
#include "tessera/core.h"
#include "tessera/glsl.h"

namespace tessera::adaptive {

/// std140 layout of TesseraAdaptiveParams (adaptive_component.glsl).
struct Params {
  std::int32_t size[4];
  std::int32_t flags[4];
  float metric[4];
  float metric2[4];
  std::uint32_t budget[4];
  std::int32_t order[64];
};
static_assert(sizeof(Params) == 5 * 16 + 256, "std140 layout");

/// Work-buffer layout (uints; adaptive_component.glsl's header comment).
inline constexpr std::size_t kHeaderUints = 16;
inline constexpr std::size_t kHistogramUints = 8 * 256;
inline constexpr std::size_t kListItemBytes = 24;
inline constexpr std::size_t kMaxPixels = std::size_t(1) << 26;  // item packing

/// What a frame computes: the adaptive image, full supersampling, or S alone.
enum class Mode { adaptive, reference, first };

/// What `check_options` derives from the options.
struct Derived {
  int n = 0;                        ///< m*m.
  std::vector<std::uint8_t> order;  ///< The sample order (the default resolved).
  bool slot_used[4] = {false, false, false, false};
  /// Channels read from each slot: the highest component index + 1 (for the format check).
  int slot_channels[4] = {0, 0, 0, 0};
  std::size_t list_capacity = 0;  ///< frame_list items (1 for the other schedules).
  /// The depth metric accumulates in double (GLSL's double); false: compensated float sums
  /// (TESSERA_ADAPTIVE_NO_FP64, for devices without fp64). Set by the backend.
  bool float64 = true;
  /// The EXTRA pass runs per 8x8 tile in shared memory (tile_list, m <= 4 and the backend's
  /// shared memory holds tile_shared_bytes(n)); else each pixel loops over its samples.
  bool tile = false;
};

/// Workgroup (shared) memory of the tile_list schedule's EXTRA pass for n = m*m samples.
std::size_t tile_shared_bytes(int n);

/// Checks what every backend checks (m, size, hdr_exposure, the hook's entry point, the sample
/// order, the layout); errors are invalid_argument / too_large "`who`: message". Fills `d`
/// (but list_capacity).
Status check_options(const AdaptiveCommonOptions& o, std::string_view who, Derived& d);
/// Bytes of the work buffer (header, histograms, 4 uints per output pixel).
std::size_t work_buffer_bytes(const AdaptiveCommonOptions& o);
/// The frame list's capacity: `list_capacity` or half of full supersampling, at most
/// `max_items` (what the device's largest storage buffer holds); 1 without a list.
std::size_t list_capacity(const AdaptiveCommonOptions& o, int n, std::size_t max_items);

/// Where a backend binds the component's resources in the generated GLSL.
struct GlslBindings {
  std::optional<int> set;  ///< Vulkan's descriptor set (TESSERA_ADAPTIVE_SET); none on GL.
  int gbuffer = 0;         ///< Binding of G-buffer slot 0 (slot s at + s).
  int params = 0, work = 0, image = 0;
};
/// The pass programs a component compiles for its schedule.
std::vector<std::string> pass_programs(AdaptiveSchedule schedule);
/// The pass's source (the hook, or a stand-in for passes that do not shade, with the shipped
/// adaptive_component.glsl included) and its expansion options (the hook's include paths, the
/// preamble: version, defines, G-buffer samplers and accessors from the layout).
glsl::Source pass_source(const AdaptiveCommonOptions& o, const std::string& pass);
glsl::ExpandOptions pass_expand_options(const AdaptiveCommonOptions& o, const Derived& d,
                                        const GlslBindings& b, const std::string& pass);

/// Built-in passes (compiled when tessera is built, tools/vk_passes; adaptive_specialized.cpp):
/// METRICS and LIST read the window size, the presence of UVs and the G-buffer layout as
/// specialization constants and each quantity through a sampler of its own, so one module serves
/// every option set but `float64` (METRICS) and `sample_count_texture` (LIST), its variants.
inline constexpr const char* kSpecializedPasses[] = {"METRICS", "LIST"};
/// The variant of `pass` (a kSpecializedPasses entry) for these options: "METRICS" or
/// "METRICS_NO_FP64", "LIST" or "LIST_COUNTS".
std::string specialized_variant(const AdaptiveCommonOptions& o, const Derived& d,
                                const std::string& pass);
/// Every variant's name.
std::vector<std::string> specialized_variants();
/// The expansion options of a variant: its preamble (specialization constants with the
/// defaults of `o`, a sampler per quantity at binding `b.gbuffer`, accessors reading them).
glsl::ExpandOptions specialized_expand_options(const std::string& variant, const GlslBindings& b);
/// One specialization constant: its constant_id and its 32 bits (int, float or VkBool32).
struct SpecConstant {
  std::uint32_t id = 0, bits = 0;
};
/// The constants that specialize a built-in pass to `o` (m, UVs, the layout's channels,
/// scales and biases).
std::vector<SpecConstant> specialization(const AdaptiveCommonOptions& o);
/// The sampler of each quantity in a built-in pass ("tessera_adaptive_depth_texture", ...) and
/// its binding for `o`'s layout: `gbuffer` + the quantity's slot (absent UVs: the id's slot,
/// never read).
std::vector<std::pair<std::string, std::uint32_t>> specialized_samplers(
    const AdaptiveCommonOptions& o, std::uint32_t gbuffer);

/// The parameter block of the current options for a frame of w x h output pixels (at most
/// the options' width x height: dynamic resolution).
Params params(const AdaptiveCommonOptions& o, const Derived& d, int w, int h);
/// A frame's budget check: invalid_argument "`who`: budget = ..." when negative.
Status check_budget(const std::optional<std::int64_t>& budget, std::string_view who);
/// The work header a frame starts from (counters 0, the budget's state); with a budget the
/// kHistogramUints after it are cleared too.
std::array<std::uint32_t, kHeaderUints> work_header(const std::optional<std::int64_t>& budget);

/// One dispatch of a frame: `program` (then `then`, one group, when set), named `name` in
/// profiles; `groups_x` > 0: that many groups in x, else 8x8 tiles over the output.
struct Step {
  std::string name, program;
  std::uint32_t groups_x = 0;
  bool indirect = false;  ///< Group counts from the work buffer (the frame list's shade pass).
  const char* then = nullptr;
};
/// The passes of a frame, in order.
std::vector<Step> frame_steps(Mode mode, AdaptiveSchedule schedule, bool budgeted);
/// The extra samples (sum of k) of a frame of `pixels` output pixels, `counted` being the
/// adaptive frame's counter.
std::uint64_t extra_samples(const AdaptiveCommonOptions& o, Mode mode, std::uint64_t counted,
                            std::uint64_t pixels);

}  // namespace tessera::adaptive
