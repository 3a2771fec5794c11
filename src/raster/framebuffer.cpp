// Frame buffer allocation, clears and the box resolve.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "core/simd.h"
#include "tessera/raster.h"

namespace tessera::raster {

namespace {

/// Largest float count of a frame buffer's payload (4 GiB).
constexpr std::uint64_t kMaxPayloadFloats = std::uint64_t{1} << 30;

/// An explicit sample pattern must have one offset per sample (1..kMaxSamples: the coverage
/// masks' bits), each inside the pixel: the rasteriser's conservative block and bounding-box
/// tests assume a pixel's samples lie in [-8, 7] sixteenths of its centre.
Status check_sample_pattern(const FrameBufferDesc& desc) {
  const std::vector<SampleOffset>& p = desc.sample_pattern;
  if (p.empty()) return Status::success();
  if (desc.msaa < 1 || desc.msaa > kMaxSamples) {
    return Status::error(ErrorCode::invalid_argument,
                         "frame buffer: with a sample pattern, msaa must be in [1, " +
                             std::to_string(kMaxSamples) + "] (got " + std::to_string(desc.msaa) +
                             ")");
  }
  if (p.size() != std::size_t(desc.msaa)) {
    return Status::error(ErrorCode::invalid_argument,
                         "frame buffer: the sample pattern has " + std::to_string(p.size()) +
                             (p.size() == 1 ? " offset" : " offsets") + " but msaa is " +
                             std::to_string(desc.msaa));
  }
  for (std::size_t s = 0; s < p.size(); ++s) {
    if (p[s].x < -8 || p[s].x > 7 || p[s].y < -8 || p[s].y > 7) {
      return Status::error(ErrorCode::invalid_argument,
                           "frame buffer: sample pattern offset " + std::to_string(s) + " (" +
                               std::to_string(p[s].x) + ", " + std::to_string(p[s].y) +
                               ") is outside [-8, 7] sixteenths of the pixel centre");
    }
  }
  return Status::success();
}

}  // namespace

Result<FrameBuffer> FrameBuffer::create(const FrameBufferDesc& desc) {
  if (Status s = check_image_size(desc.width, desc.height, "frame buffer"); !s.ok()) {
    return Status::error(ErrorCode::invalid_argument, s.message);
  }
  if (desc.sample_pattern.empty() && !valid_msaa(desc.msaa)) {
    return Status::error(
        ErrorCode::invalid_argument,
        "frame buffer: msaa must be 1, 2, 4, 8 or 16 (got " + std::to_string(desc.msaa) + ")");
  }
  if (Status s = check_sample_pattern(desc); !s.ok()) return s;
  if (desc.ssaa < 1 || desc.ssaa > 8) {
    return Status::error(ErrorCode::invalid_argument, "frame buffer: ssaa must be in [1, 8] (got " +
                                                          std::to_string(desc.ssaa) + ")");
  }
  if (desc.channels < 1 || desc.channels > kMaxChannels) {
    return Status::error(ErrorCode::invalid_argument, "frame buffer: channels must be in [1, " +
                                                          std::to_string(kMaxChannels) + "] (got " +
                                                          std::to_string(desc.channels) + ")");
  }
  const std::int64_t gw = std::int64_t(desc.width) * desc.ssaa;
  const std::int64_t gh = std::int64_t(desc.height) * desc.ssaa;
  if (Status s = check_image_size(gw, gh, "frame buffer grid"); !s.ok()) return s;
  const std::uint64_t samples = std::uint64_t(gw) * std::uint64_t(gh) * std::uint64_t(desc.msaa);
  if (samples > kMaxImagePixels || samples * std::uint64_t(desc.channels) > kMaxPayloadFloats) {
    return Status::error(ErrorCode::too_large, "frame buffer: " + std::to_string(samples) +
                                                   " samples of " + std::to_string(desc.channels) +
                                                   " channels exceed the limit");
  }
  FrameBuffer fb;
  fb.desc_ = desc;
  fb.data_.assign(samples * std::uint64_t(desc.channels), 0.0f);
  fb.depth_.assign(samples, 1.0f);
  if (desc.primitive_ids) fb.ids_.assign(samples, kNoPrimitive);
  if (desc.coverage_counts) fb.counts_.assign(samples, 0u);
  return fb;
}

void FrameBuffer::clear_rect(int x0, int y0, int x1, int y1, const float* value, float depth) {
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, grid_width());
  y1 = std::min(y1, grid_height());
  if (x0 >= x1 || y0 >= y1) return;
  const int nc = desc_.channels;
  float pattern[kMaxChannels] = {};
  if (value) std::copy(value, value + nc, pattern);
  const std::size_t run = std::size_t(x1 - x0) * std::size_t(desc_.msaa);
  for (int y = y0; y < y1; ++y) {
    const std::size_t first = sample_index(x0, y, 0);
    float* d = &data_[first * std::size_t(nc)];
    if (nc == 4) {
      for (std::size_t i = 0; i < run; ++i, d += 4) {
        d[0] = pattern[0], d[1] = pattern[1], d[2] = pattern[2], d[3] = pattern[3];
      }
    } else {
      for (std::size_t i = 0; i < run; ++i, d += nc) {
        for (int c = 0; c < nc; ++c) d[c] = pattern[c];
      }
    }
    std::fill_n(&depth_[first], run, depth);
    if (!ids_.empty()) std::fill_n(&ids_[first], run, kNoPrimitive);
    if (!counts_.empty()) std::fill_n(&counts_[first], run, 0u);
  }
}

void FrameBuffer::clear(const ClearValues& values, const Parallel& parallel) {
  const int gh = grid_height();
  parallel_for(
      0, gh, 16,
      [&](std::int64_t y0, std::int64_t y1) {
        clear_rect(0, int(y0), grid_width(), int(y1), values.value.data(), values.depth);
      },
      parallel);
}

namespace {

/// Mean of the `nc` channels over output pixel (x, y)'s grid pixels and samples, in a fixed
/// order (rows, columns, samples), so every resolve path produces the same floats.
inline void average_pixel(const FrameBuffer& fb, const float* data, int x, int y, int nc,
                          float scale, float* out) {
  const int m = fb.ssaa(), ns = fb.msaa();
  float acc[kMaxChannels] = {};
  for (int gy = y * m; gy < y * m + m; ++gy) {
    for (int gx = x * m; gx < x * m + m; ++gx) {
      const float* s = data + fb.sample_index(gx, gy, 0) * std::size_t(nc);
      for (int k = 0; k < ns * nc; k += nc) {
        for (int c = 0; c < nc; ++c) acc[c] += s[k + c];
      }
    }
  }
  for (int c = 0; c < nc; ++c) out[c] = acc[c] * scale;
}

/// Table-driven, bit-exact equivalent of `linear_to_srgb8` (which evaluates pow per call).
/// Floats in [2^-13, 1) are split into buckets of 2^15 consecutive bit patterns (256 per
/// octave); the encoding changes at most once inside a bucket, so a bucket stores its value
/// at the low end and the first bit pattern of the next value. Below 2^-13 the result is 0,
/// from 1 up it is 255.
class Srgb8Encoder {
 public:
  Srgb8Encoder() {
    for (std::uint32_t i = 0; i < kBuckets; ++i) {
      const std::uint32_t lo = kLo + (i << kShift), hi = lo + (1u << kShift) - 1u;
      const std::uint8_t vlo = linear_to_srgb8(from_bits(lo));
      const std::uint8_t vhi = linear_to_srgb8(from_bits(hi));
      base_[i] = vlo;
      if (vlo == vhi) {
        next_[i] = ~0u;
        continue;
      }
      if (vhi != vlo + 1) {  // not expected; fall back to the exact function
        slow_ = true;
        next_[i] = 0;
        continue;
      }
      std::uint32_t a = lo, b = hi;  // f(a) = vlo, f(b) = vhi
      while (b - a > 1) {
        const std::uint32_t mid = a + (b - a) / 2;
        (linear_to_srgb8(from_bits(mid)) == vlo ? a : b) = mid;
      }
      next_[i] = b;
    }
  }

  std::uint8_t encode(float v) const {
    if (!(v >= kMin)) return 0;  // also NaN
    if (v >= 1.0f) return 255;
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    const std::uint32_t i = (bits - kLo) >> kShift;
    if (slow_) return linear_to_srgb8(v);
    return std::uint8_t(base_[i] + (bits >= next_[i] ? 1 : 0));
  }

 private:
  static float from_bits(std::uint32_t b) {
    float f;
    std::memcpy(&f, &b, sizeof f);
    return f;
  }
  static constexpr std::uint32_t kLo = 0x39000000u;  // 2^-13
  static constexpr std::uint32_t kHi = 0x3F800000u;  // 1.0
  static constexpr int kShift = 15;
  static constexpr std::uint32_t kBuckets = (kHi - kLo) >> kShift;
  static constexpr float kMin = 1.0f / 8192.0f;
  std::uint8_t base_[kBuckets];
  std::uint32_t next_[kBuckets];
  bool slow_ = false;
};

const Srgb8Encoder& srgb8_encoder() {
  static const Srgb8Encoder e;
  return e;
}

/// Alpha as in `to_srgb8`: linear, clamped to [0, 1], NaN -> 0, times 255 rounded half away
/// from zero. Equals `std::lround(a * 255)` without the libm call: for 0 <= v < 2^23,
/// v - trunc(v) is exact.
inline std::uint8_t alpha8(float a) {
  const float v = std::clamp(a == a ? a : 0.0f, 0.0f, 1.0f) * 255.0f;
  const int r = int(v);
  return std::uint8_t(r + (v - float(r) >= 0.5f ? 1 : 0));
}

/// Resolves one row of a 4-channel, ssaa 1 frame buffer to sRGB8: `src` is the row's first
/// sample, `ns` samples per pixel. Bit-identical to `average_pixel` + encode (lane-wise IEEE
/// additions in the same order, then one multiply).
inline void resolve_row_rgba(const float* src, int w, int ns, float scale, const Srgb8Encoder& enc,
                             std::uint8_t* d) {
  using simd::vf32x4;
  const vf32x4 vscale(scale);
  const auto store = [&](vf32x4 sum) {
    alignas(16) float acc[4];
    simd::storef4_aligned(sum * vscale, acc);
    d[0] = enc.encode(acc[0]);
    d[1] = enc.encode(acc[1]);
    d[2] = enc.encode(acc[2]);
    d[3] = acc[3] == 1.0f ? std::uint8_t(255) : alpha8(acc[3]);  // alpha8(1) == 255
  };
  if (ns == 1) {
    // One sample: the same 0 + v and multiply as the loop below, without the loop.
    for (int x = 0; x < w; ++x, d += 4, src += 4) store(vf32x4() + simd::loadf4(src));
    return;
  }
  for (int x = 0; x < w; ++x, d += 4) {
    vf32x4 acc;
    for (int s = 0; s < ns; ++s, src += 4) acc = acc + simd::loadf4(src);
    store(acc);
  }
}

}  // namespace

std::vector<float> resolve_channels(const FrameBuffer& fb, const Parallel& parallel) {
  const int w = fb.width(), h = fb.height(), nc = fb.channels();
  std::vector<float> out(std::size_t(w) * std::size_t(h) * std::size_t(nc));
  const float scale = 1.0f / float(fb.ssaa() * fb.ssaa() * fb.msaa());
  const float* data = fb.data().data();
  parallel_for(
      0, h, 8,
      [&](std::int64_t yb, std::int64_t ye) {
        for (std::int64_t y = yb; y < ye; ++y) {
          for (int x = 0; x < w; ++x) {
            average_pixel(
                fb, data, x, int(y), nc, scale,
                &out[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * std::size_t(nc)]);
          }
        }
      },
      parallel);
  return out;
}

ImageRGBAF resolve(const FrameBuffer& fb, const Parallel& parallel) {
  const int w = fb.width(), h = fb.height(), nc = fb.channels();
  ImageRGBAF img(w, h);
  const float scale = 1.0f / float(fb.ssaa() * fb.ssaa() * fb.msaa());
  const float* data = fb.data().data();
  parallel_for(
      0, h, 8,
      [&](std::int64_t yb, std::int64_t ye) {
        float px[kMaxChannels];
        for (std::int64_t y = yb; y < ye; ++y) {
          for (int x = 0; x < w; ++x) {
            average_pixel(fb, data, x, int(y), nc, scale, px);
            float* d = img.at(x, int(y));
            for (int c = 0; c < 4; ++c) d[c] = c < nc ? px[c] : (c == 3 ? 1.0f : 0.0f);
          }
        }
      },
      parallel);
  return img;
}

ImageRGBA8 resolve_srgb8(const FrameBuffer& fb, const Parallel& parallel) {
  const int w = fb.width(), h = fb.height(), nc = fb.channels();
  ImageRGBA8 img(w, h);
  const float scale = 1.0f / float(fb.ssaa() * fb.ssaa() * fb.msaa());
  const float* data = fb.data().data();
  const Srgb8Encoder& enc = srgb8_encoder();
  const bool rgba_fast = nc == 4 && fb.ssaa() == 1;
  parallel_for(
      0, h, 8,
      [&](std::int64_t yb, std::int64_t ye) {
        float px[kMaxChannels];
        for (std::int64_t y = yb; y < ye; ++y) {
          std::uint8_t* d = img.at(0, int(y));
          if (rgba_fast) {
            // The common colour case: the same sums in the same order as `average_pixel`,
            // four channels per vector operation.
            resolve_row_rgba(data + fb.sample_index(0, int(y), 0) * 4, w, fb.msaa(), scale, enc, d);
            continue;
          }
          for (int x = 0; x < w; ++x, d += 4) {
            average_pixel(fb, data, x, int(y), nc, scale, px);
            for (int c = 0; c < 3; ++c) d[c] = c < nc ? enc.encode(px[c]) : 0;
            d[3] = alpha8(nc > 3 ? px[3] : 1.0f);
          }
        }
      },
      parallel);
  return img;
}

}  // namespace tessera::raster
