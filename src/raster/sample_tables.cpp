// Direct3D 11 standard multisample patterns (D3D11_STANDARD_MULTISAMPLE_PATTERN).
//
// Offsets from the pixel centre in 1/16 pixel, x right, y down, in sample-index order, as
// defined by the Direct3D 10.1/11 functional specification (the same tables are the Vulkan
// "standard sample locations" for 1/2/4/8/16 samples). The 16x pattern reaches -8/16, i.e. the
// left and top pixel edges, which the rasteriser's conservative block bounds account for.
#include "tessera/raster.h"

namespace tessera::raster {

namespace {

constexpr SampleOffset kPattern1[] = {{0, 0}};
constexpr SampleOffset kPattern2[] = {{4, 4}, {-4, -4}};
constexpr SampleOffset kPattern4[] = {{-2, -6}, {6, -2}, {-6, 2}, {2, 6}};
constexpr SampleOffset kPattern8[] = {{1, -3}, {-1, 3},  {5, 1}, {-3, -5},
                                      {-5, 5}, {-7, -1}, {3, 7}, {7, -7}};
constexpr SampleOffset kPattern16[] = {{1, 1},  {-1, -3}, {-3, 2}, {4, -1}, {-5, -2}, {2, 5},
                                       {5, 3},  {3, -5},  {-2, 6}, {0, -7}, {-4, -6}, {-6, 4},
                                       {-8, 0}, {7, -4},  {6, 7},  {-7, -8}};

}  // namespace

std::span<const SampleOffset> sample_positions(int count) {
  switch (count) {
    case 1:
      return kPattern1;
    case 2:
      return kPattern2;
    case 4:
      return kPattern4;
    case 8:
      return kPattern8;
    case 16:
      return kPattern16;
    default:
      return {};
  }
}

bool valid_msaa(int count) { return !sample_positions(count).empty(); }

}  // namespace tessera::raster
