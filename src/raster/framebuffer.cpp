// Frame buffer allocation, clears and the box resolve.
#include <algorithm>
#include <string>

#include "tessera/raster.h"

namespace tessera::raster {

namespace {

/// Largest float count of a frame buffer's payload (4 GiB).
constexpr std::uint64_t kMaxPayloadFloats = std::uint64_t{1} << 30;

}  // namespace

Result<FrameBuffer> FrameBuffer::create(const FrameBufferDesc& desc) {
  if (Status s = check_image_size(desc.width, desc.height, "frame buffer"); !s.ok()) {
    return Status::error(ErrorCode::invalid_argument, s.message);
  }
  if (!valid_msaa(desc.msaa)) {
    return Status::error(ErrorCode::invalid_argument,
                         "frame buffer: msaa must be 1, 2, 4, 8 or 16 (got " +
                             std::to_string(desc.msaa) + ")");
  }
  if (desc.ssaa < 1 || desc.ssaa > 8) {
    return Status::error(ErrorCode::invalid_argument,
                         "frame buffer: ssaa must be in [1, 8] (got " +
                             std::to_string(desc.ssaa) + ")");
  }
  if (desc.channels < 1 || desc.channels > kMaxChannels) {
    return Status::error(ErrorCode::invalid_argument,
                         "frame buffer: channels must be in [1, " + std::to_string(kMaxChannels) +
                             "] (got " + std::to_string(desc.channels) + ")");
  }
  const std::int64_t gw = std::int64_t(desc.width) * desc.ssaa;
  const std::int64_t gh = std::int64_t(desc.height) * desc.ssaa;
  if (Status s = check_image_size(gw, gh, "frame buffer grid"); !s.ok()) return s;
  const std::uint64_t samples = std::uint64_t(gw) * std::uint64_t(gh) * std::uint64_t(desc.msaa);
  if (samples > kMaxImagePixels || samples * std::uint64_t(desc.channels) > kMaxPayloadFloats) {
    return Status::error(ErrorCode::too_large,
                         "frame buffer: " + std::to_string(samples) + " samples of " +
                             std::to_string(desc.channels) + " channels exceed the limit");
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

void FrameBuffer::clear(const float* value, float depth, int threads) {
  const int gh = grid_height();
  parallel_for(
      0, gh, 16,
      [&](std::int64_t y0, std::int64_t y1) {
        clear_rect(0, int(y0), grid_width(), int(y1), value, depth);
      },
      threads);
}

std::vector<float> resolve_channels(const FrameBuffer& fb, int threads) {
  const int w = fb.width(), h = fb.height(), m = fb.ssaa(), ns = fb.msaa();
  const int nc = fb.channels();
  std::vector<float> out(std::size_t(w) * std::size_t(h) * std::size_t(nc));
  const float scale = 1.0f / float(m * m * ns);
  const std::span<const float> data = fb.data();
  parallel_for(
      0, h, 8,
      [&](std::int64_t yb, std::int64_t ye) {
        float acc[kMaxChannels];
        for (std::int64_t y = yb; y < ye; ++y) {
          for (int x = 0; x < w; ++x) {
            std::fill(acc, acc + nc, 0.0f);
            for (int gy = int(y) * m; gy < int(y) * m + m; ++gy) {
              for (int gx = x * m; gx < x * m + m; ++gx) {
                const float* s = &data[fb.sample_index(gx, gy, 0) * std::size_t(nc)];
                for (int k = 0; k < ns * nc; k += nc) {
                  for (int c = 0; c < nc; ++c) acc[c] += s[k + c];
                }
              }
            }
            float* d = &out[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * std::size_t(nc)];
            for (int c = 0; c < nc; ++c) d[c] = acc[c] * scale;
          }
        }
      },
      threads);
  return out;
}

ImageRGBAF resolve(const FrameBuffer& fb, int threads) {
  const std::vector<float> all = resolve_channels(fb, threads);
  const int nc = fb.channels();
  ImageRGBAF img(fb.width(), fb.height());
  const std::size_t n = img.pixel_count();
  for (std::size_t i = 0; i < n; ++i) {
    const float* s = &all[i * std::size_t(nc)];
    float* d = &img.pixels[i * 4];
    for (int c = 0; c < 4; ++c) d[c] = c < nc ? s[c] : (c == 3 ? 1.0f : 0.0f);
  }
  return img;
}

ImageRGBA8 resolve_srgb8(const FrameBuffer& fb, int threads) {
  return to_srgb8(resolve(fb, threads), threads);
}

}  // namespace tessera::raster
