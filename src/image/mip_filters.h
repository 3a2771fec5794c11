// The windowed-sinc mip filters (Lanczos-3, Kaiser) of `generate_mipmaps` (mipmap.cpp).
#pragma once

#include "tessera/core.h"
#include "tessera/image_mipmap.h"

namespace tessera::image::detail {

/// The kernel of `filter` at x, in texels of the smaller image, not normalised: Lanczos-3
/// sinc(x) sinc(x / 3), Kaiser sinc(x) I0(4 sqrt(1 - (x / 3)^2)) / I0(4), both zero from |x| = 3
/// on; box 1 for |x| < 1/2 (the 2x2 box, which `generate_mipmaps` makes with its own loop).
double mip_kernel(MipFilter filter, double x);

/// How `sinc_half` treats the channels.
struct SincHalfOptions {
  MipFilter filter = MipFilter::lanczos;  ///< lanczos or kaiser.
  bool premultiply = false;               ///< Weight colour by alpha (as `generate_mipmaps` does).
  bool clamp_colour = true;               ///< Clamp colour to [0, 1] (false: RGB are vectors).
  int threads = 0;
};

/// The next mip level of `src` (colour not premultiplied, alpha in [0, 1]): each side halves
/// (mip_dimension(side, 1)) by a separable filter with `mip_kernel` scaled to the ratio of the
/// sizes (2 for even sides), edges wrapped, weights normalised to 1; a side of 1 is left
/// unfiltered. Alpha is clamped to [0, 1]. With `premultiply`, colour is the alpha-weighted
/// average where the filtered alpha exceeds 1e-4 (below, it quantises to 0 anyway), else the
/// plain one.
ImageRGBAF sinc_half(const ImageRGBAF& src, const SincHalfOptions& options);

}  // namespace tessera::image::detail
