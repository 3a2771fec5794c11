// Colour maps and difference heatmaps.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>

#include "tessera/metrics.h"

namespace tessera::metrics {

namespace {
// Nine samples of matplotlib's perceptually uniform maps at t = 0, 1/8, ..., 1.
constexpr std::array<std::array<std::uint8_t, 3>, 9> kInferno = {{{0, 0, 4},
                                                                  {31, 12, 72},
                                                                  {85, 15, 109},
                                                                  {136, 34, 106},
                                                                  {186, 54, 85},
                                                                  {227, 89, 51},
                                                                  {249, 140, 10},
                                                                  {249, 201, 50},
                                                                  {252, 255, 164}}};
constexpr std::array<std::array<std::uint8_t, 3>, 9> kViridis = {{{68, 1, 84},
                                                                  {71, 44, 122},
                                                                  {59, 81, 139},
                                                                  {44, 113, 142},
                                                                  {33, 144, 141},
                                                                  {39, 173, 129},
                                                                  {92, 200, 99},
                                                                  {170, 220, 50},
                                                                  {253, 231, 37}}};
}  // namespace

void colour_map_rgb(ColourMap map, float t, std::uint8_t rgb[3]) {
  if (!(t == t)) t = 0.0f;
  t = std::clamp(t, 0.0f, 1.0f);
  if (map == ColourMap::grey) {
    rgb[0] = rgb[1] = rgb[2] = std::uint8_t(std::lround(t * 255.0f));
    return;
  }
  const auto& table = map == ColourMap::inferno ? kInferno : kViridis;
  const float f = t * 8.0f;
  const int i = std::min(7, int(f));
  const float w = f - float(i);
  for (int c = 0; c < 3; ++c) {
    rgb[c] =
        std::uint8_t(std::lround(float(table[i][c]) * (1.0f - w) + float(table[i + 1][c]) * w));
  }
}

ImageRGBA8 heatmap(std::span<const float> values, int width, int height, float scale,
                   ColourMap map) {
  ImageRGBA8 img(width, height);
  const float inv = scale > 0.0f ? 1.0f / scale : 0.0f;
  for (std::size_t i = 0; i < img.pixel_count() && i < values.size(); ++i) {
    colour_map_rgb(map, values[i] * inv, &img.pixels[i * 4]);
    img.pixels[i * 4 + 3] = 255;
  }
  return img;
}

Result<ImageRGBA8> difference_heatmap(const ImageRGBA8& a, const ImageRGBA8& b, float scale,
                                      ColourMap map) {
  if (a.width != b.width || a.height != b.height) {
    return Status::error(ErrorCode::size_mismatch, "difference heatmap: image sizes differ");
  }
  const int channels = (a.has_alpha || b.has_alpha) ? 4 : 3;
  std::vector<float> diff(a.pixel_count());
  for (std::size_t i = 0; i < diff.size(); ++i) {
    int m = 0;
    for (int c = 0; c < channels; ++c) {
      m = std::max(m, std::abs(int(a.pixels[i * 4 + c]) - int(b.pixels[i * 4 + c])));
    }
    diff[i] = float(m);
  }
  return heatmap(diff, a.width, a.height, scale, map);
}

}  // namespace tessera::metrics
