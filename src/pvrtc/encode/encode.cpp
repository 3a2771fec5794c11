// PVRTC1 encoder driver: resolves the schedule (schedule.h) once, then intensity-dilation
// (start/dilation.cpp) or principal-axis (start/principal_axis.cpp) endpoints, the
// homogeneous-block shortcut, brute-force modulation against the exactly upscaled endpoint
// images (modulation/modulation.cpp), then the scheduled passes of passes.cpp (reseed,
// refinement, exact searches) and, at high, the crossover with a second encoding from the
// dilation start.
#include <algorithm>
#include <array>
#include <atomic>
#include <cstring>
#include <limits>

#include "core/simd.h"
#include "pvrtc/encode/encode_internal.h"
#include "tessera/pvrtc.h"

namespace tessera::pvrtc {

using namespace detail;

namespace detail {

namespace {

/// `code_nearest` of an RGB channel of `kBits` bits (by table, see pvrtc_kernel.h).
template <int kBits>
inline std::uint32_t nearest_rgb(float level) {
  static_assert(kBits >= 3 && kBits <= 5);
  return code_nearest_fast(kBits == 5 ? kNearest5 : kBits == 4 ? kNearest4 : kNearest3, level);
}

}  // namespace

namespace {

/// The squared error of channel level c against code `code` of `kBits` bits.
template <int kBits>
inline float code_err(std::uint32_t code, float c) {
  const float d = float(code_level_rgb(code, kBits)) - c;
  return d * d;
}

/// Opaque and translucent candidates for endpoint B (kB) or A; the smaller error wins.
template <bool kB>
std::uint16_t quantise_either(const float c[4]) {
  EndpointCodes o;
  o.opaque = true;
  o.r = nearest_rgb<5>(c[0]);
  o.g = nearest_rgb<5>(c[1]);
  o.b = nearest_rgb < kB ? 5 : 4 > (c[2]);
  float eo = (255.0f - c[3]) * (255.0f - c[3]);
  eo += code_err<5>(o.r, c[0]);
  eo += code_err<5>(o.g, c[1]);
  eo += code_err < kB ? 5 : 4 > (o.b, c[2]);
  EndpointCodes t;
  t.opaque = false;
  t.a = code_nearest_fast(kNearestAlpha3, c[3]);
  float et = (float(code_level_alpha(t.a)) - c[3]) * (float(code_level_alpha(t.a)) - c[3]);
  t.r = nearest_rgb<4>(c[0]);
  t.g = nearest_rgb<4>(c[1]);
  t.b = nearest_rgb < kB ? 4 : 3 > (c[2]);
  et += code_err<4>(t.r, c[0]);
  et += code_err<4>(t.g, c[1]);
  et += code_err < kB ? 4 : 3 > (t.b, c[2]);
  return std::uint16_t(pack_endpoint(kB, et < eo ? t : o));
}

}  // namespace

std::uint16_t quantise_endpoint(const float c[4], bool is_b, bool allow_translucent) {
  if (allow_translucent) return is_b ? quantise_either<true>(c) : quantise_either<false>(c);
  EndpointCodes o;  // opaque: the nearest codes, no errors needed
  o.opaque = true;
  o.r = nearest_rgb<5>(c[0]);
  o.g = nearest_rgb<5>(c[1]);
  o.b = is_b ? nearest_rgb<5>(c[2]) : nearest_rgb<4>(c[2]);
  return std::uint16_t(pack_endpoint(is_b, o));
}

namespace {

// Optimal single-colour endpoint codes: for an 8-bit value v, codes (a, b) of an A channel
// with `abits` bits and a B channel with 5 bits such that (LA (8 - m) + LB m) / 8 is nearest
// to v in a uniform region, for modulation weight m = 3 (index 0) or 5 (index 1). The 2 bpp
// tables also weigh the error of LA itself (1 texel in 16 of an interpolated-mode block can
// only use weight 0 or 8).
struct SingleColour {
  std::uint8_t a, b;
  std::uint16_t err;  ///< Squared-error cost of the pair.
};
SingleColour best_single(int abits, int m, bool two_bpp, int v) {
  SingleColour best{0, 0, 0xffff};
  for (int a = 0; a < (1 << abits); ++a) {
    for (int b = 0; b < 32; ++b) {
      const int la = code_level_rgb(std::uint32_t(a), abits),
                lb = code_level_rgb(std::uint32_t(b), 5);
      const int d = (la * (8 - m) + lb * m) / 8 - v;
      const int cost = two_bpp ? 15 * d * d + (la - v) * (la - v) : d * d;
      if (cost < best.err)
        best = {std::uint8_t(a), std::uint8_t(b), std::uint16_t(std::min(cost, 0xfffe))};
    }
  }
  return best;
}

// Entries are found on first use: a uniform block needs three per mode, so building whole
// tables would cost more than most encodes use. Relaxed atomics (bit 31 = known): racing threads
// store the same value.
template <int kABits, int kM, bool kTwoBpp>
SingleColour single_entry(int v) {
  static std::atomic<std::uint32_t> memo[256] = {};
  std::uint32_t e = memo[v].load(std::memory_order_relaxed);
  if (e == 0) {
    const SingleColour c = best_single(kABits, kM, kTwoBpp, v);
    e = 0x80000000u | (std::uint32_t(c.a) << 21) | (std::uint32_t(c.b) << 16) | c.err;
    memo[v].store(e, std::memory_order_relaxed);
  }
  return {std::uint8_t((e >> 21) & 31), std::uint8_t((e >> 16) & 31), std::uint16_t(e & 0xffff)};
}

SingleColour single_colour(int abits, int mi, bool two_bpp, int v) {
  switch ((two_bpp ? 4 : 0) + (abits == 4 ? 2 : 0) + mi) {
    case 0:
      return single_entry<5, 3, false>(v);
    case 1:
      return single_entry<5, 5, false>(v);
    case 2:
      return single_entry<4, 3, false>(v);
    case 3:
      return single_entry<4, 5, false>(v);
    case 4:
      return single_entry<5, 3, true>(v);
    case 5:
      return single_entry<5, 5, true>(v);
    case 6:
      return single_entry<4, 3, true>(v);
    default:
      return single_entry<4, 5, true>(v);
  }
}

}  // namespace

}  // namespace detail

namespace {

// Estimated costs of the starts (endpoints and the first modulation choice), in the units of
// passes.cpp's: seconds per megapixel on one thread.
constexpr double kDilationStartCost = 0.04;
constexpr double kPrincipalStartCost = 0.19;

// Homogeneous blocks (all texels equal and opaque): optimal single-colour endpoints from the
// lookup tables, replacing the dilation result. `flat` (may be null): only blocks marked 1 there
// can be uniform (see dilation_endpoints).
void homogeneous_shortcut(EncoderState& s, const std::uint8_t* flat) {
  const Grid& g = s.g;
  parallel_for(
      0, g.nby, 16,
      [&](std::int64_t by0, std::int64_t by1) {
        for (int by = int(by0); by < int(by1); ++by) {
          for (int bx = 0; bx < g.nbx; ++bx) {
            if (flat != nullptr && !flat[std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx)])
              continue;
            const std::uint8_t* first =
                &s.target[(std::size_t(by * 4) * std::size_t(g.pw) + std::size_t(bx * g.bw)) * 4];
            bool uniform = first[3] == 255;
            for (int y = 0; y < 4 && uniform; ++y) {
              const std::uint8_t* row =
                  &s.target[(std::size_t(by * 4 + y) * std::size_t(g.pw) + std::size_t(bx * g.bw)) *
                            4];
              for (int x = 0; x < g.bw && uniform; ++x)
                uniform = std::memcmp(row + x * 4, first, 4) == 0;
            }
            if (!uniform) continue;
            const bool two = g.format == Format::pvrtc1_2bpp;
            int best_mi = 0, best_err = 1 << 30;
            for (int mi = 0; mi < 2; ++mi) {
              const int e = single_colour(5, mi, two, first[0]).err +
                            single_colour(5, mi, two, first[1]).err +
                            single_colour(4, mi, two, first[2]).err;
              if (e < best_err) {
                best_err = e;
                best_mi = mi;
              }
            }
            EndpointCodes a, b;
            const SingleColour r = single_colour(5, best_mi, two, first[0]);
            const SingleColour gg = single_colour(5, best_mi, two, first[1]);
            const SingleColour bb = single_colour(4, best_mi, two, first[2]);
            a.r = r.a;
            a.g = gg.a;
            a.b = bb.a;
            b.r = r.b;
            b.g = gg.b;
            b.b = bb.b;
            const std::size_t bi = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
            s.ca[bi] = std::uint16_t(pack_endpoint(false, a));
            s.cb[bi] = std::uint16_t(pack_endpoint(true, b));
          }
        }
      },
      {s.threads});
}

// Initial endpoints of every block (the dilation start or the principal-axis start, then the
// homogeneous-block shortcut) and their modulation; returns the total error (as total_error).
std::uint64_t start_endpoints(EncoderState& s, bool dilation) {
  const Grid& g = s.g;
  std::vector<float> low, high;
  // Dilation start: only blocks of one intensity can be uniform, and the dilation knows them,
  // so the shortcut skips its pass over the target.
  std::vector<std::uint8_t> flat;
  if (dilation) {
    dilation_endpoints(s, low, high, &flat);
  } else {
    principal_endpoints(s, low, high);
    orient_endpoints(g, s.alpha_mode ? 4 : 3, low, high);
  }
  parallel_for(
      0, std::int64_t(g.blocks()), 4096,
      [&](std::int64_t b0, std::int64_t b1) {
        for (std::int64_t i = b0; i < b1; ++i) {
          s.ca[std::size_t(i)] = quantise_endpoint(&low[std::size_t(i) * 4], false, s.alpha_mode);
          s.cb[std::size_t(i)] = quantise_endpoint(&high[std::size_t(i) * 4], true, s.alpha_mode);
        }
      },
      {s.threads});
  // The float endpoints are done with: their pages go back to the heap for the modulation
  // search's buffers (a lower peak).
  std::vector<float>().swap(low);
  std::vector<float>().swap(high);
  homogeneous_shortcut(s, dilation ? flat.data() : nullptr);
  return choose_modulation(s);
}

}  // namespace

Result<std::vector<std::uint8_t>> encode(const ImageRGBA8& image, const EncodeOptions& options) {
  if (image.pixels.size() != image.pixel_count() * 4) {
    return Status::error(ErrorCode::invalid_argument,
                         "pvrtc::encode: pixel buffer size does not match the image size");
  }
  return encode(ImageView8::of(image), options);
}

Result<std::vector<std::uint8_t>> encode(const ImageView8& image, const EncodeOptions& options) {
  if (Status st = check_dimensions(image.width, image.height, "pvrtc::encode"); !st.ok()) return st;
  if (Status st = check_view(image, "pvrtc::encode"); !st.ok()) return st;
  if (options.iterations < -1 || options.exact_search_rounds < 0) {
    return Status::error(ErrorCode::invalid_argument,
                         "pvrtc::encode: iterations must be >= -1 and exact_search_rounds >= 0");
  }
  if (options.alpha_weighted && options.format != Format::pvrtc1_4bpp) {
    return Status::error(ErrorCode::invalid_argument,
                         "pvrtc::encode: alpha_weighted is for PVRTC1 4 bpp only, not 2 bpp");
  }
  const EncodeSchedule schedule = resolve_schedule(options.quality, options.format,
                                                   options.iterations, options.exact_search_rounds);
  EncoderState s;
  s.g = make_grid(options.format, image.width, image.height);
  s.alpha_mode = image.has_alpha || options.force_alpha;
  s.punch = s.alpha_mode && options.punch_through && options.format == Format::pvrtc1_4bpp;
  s.mode1 = schedule.try_mode1;
  s.threads = options.threads;
  s.modulation_descent = schedule.modulation_descent;
  const Grid& g = s.g;
  // Progress (progress.h): the start, the passes and the crossover by their estimated costs.
  ProgressSink sink(options.progress);
  const Progress whole(&sink, 0.0, 1.0);
  whole.at(0.0);
  const double start_cost = schedule.dilation_start ? kDilationStartCost : kPrincipalStartCost;
  ProgressSteps steps(whole, start_cost + optimise_cost(schedule, options.format) +
                                 (schedule.crossover ? kDilationStartCost : 0.0) +
                                 alt_cost(schedule, options.format) +
                                 crossover_cost(schedule, options.format));
  // Target: the source tiled over the padded level (only textures under 2x2 blocks differ),
  // alpha forced to 255 unless alpha_mode. The caller's pixels are used in place when they
  // already are exactly that (no copy, no page faults for one); otherwise one pass writes them
  // packed (RGB views get their alpha there).
  const bool padded = g.pw != image.width || g.ph != image.height;
  const std::size_t bytes = image.pixel_count() * 4;
  if (!padded && image.packed_rgba() && (s.alpha_mode || all_opaque(image))) {
    s.target = std::span<const std::uint8_t>(image.data, bytes);
  } else if (!padded) {
    copy_to_rgba8(image, s.new_target(bytes), !s.alpha_mode);
  } else {
    std::vector<std::uint8_t> packed(bytes);
    copy_to_rgba8(image, packed.data(), !s.alpha_mode);
    std::uint8_t* t = s.new_target(g.texels() * 4);
    const std::size_t row = std::size_t(image.width) * 4;
    for (int y = 0; y < g.ph; ++y) {
      std::uint8_t* d = t + std::size_t(y) * std::size_t(g.pw) * 4;
      for (int x0 = 0; x0 < g.pw; x0 += image.width) {
        std::memcpy(d + std::size_t(x0) * 4, &packed[std::size_t(y % image.height) * row],
                    std::size_t(std::min(image.width, g.pw - x0)) * 4);
      }
    }
  }
  if (options.alpha_weighted && s.alpha_mode) {
    // Colour error weighted by alpha (encode_internal.h: colour_scale_of, scale_diff).
    s.colour_scale.resize(g.texels());
    parallel_for(0, std::int64_t(g.texels()), 1 << 16,
                 [&](std::int64_t i0, std::int64_t i1) {
                   for (std::int64_t i = i0; i < i1; ++i) {
                     s.colour_scale[std::size_t(i)] =
                         std::uint8_t(colour_scale_of(s.target[std::size_t(i) * 4 + 3]));
                   }
                 },
                 {s.threads});
  }
  s.ca.assign(g.blocks(), 0);
  s.cb.assign(g.blocks(), 0);
  s.mode.assign(g.blocks(), 0);
  s.mod.assign(g.blocks(), 0);
  // high: a second encoding from the dilation start, crossed with the first at the end
  // (crossover.cpp).
  EncoderState alt;
  if (schedule.crossover) alt = s;
  // fast: the paper's intensity dilation; normal / high start the refinement from
  // principal-axis endpoints, which separate equally bright colours (see principal_axis.cpp).
  // Then reseed, least-squares refinement and the exact search, as scheduled (passes.cpp).
  steps.next(start_cost);
  const std::uint64_t start_error = start_endpoints(s, schedule.dilation_start);
  s.progress = steps.next(optimise_cost(schedule, options.format));
  optimise(s, schedule, start_error);
  if (schedule.crossover) {
    // The two encodings share nothing until the crossover, yet one after the other on all the
    // threads beats both at once on half of them each: every pass keeps the threads busy, and
    // the first encoding takes longer than the second (docs/benchmarks/pvrtc_history.md).
    steps.next(kDilationStartCost);
    alt.progress = steps.next(alt_cost(schedule, options.format));
    optimise_alt(alt, start_endpoints(alt, true), schedule);
    s.progress = steps.next(crossover_cost(schedule, options.format));
    optimise_crossover(s, alt, schedule);
  }
  if (options.normal_map) choose_modulation_angular(s);
  std::vector<std::uint8_t> out(level_size(options.format, image.width, image.height));
  const std::vector<std::uint64_t> w = s.words();
  store_words(g, w.data(), out.data());
  sink.report(1.0);
  return out;
}

}  // namespace tessera::pvrtc
