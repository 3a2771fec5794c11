// tessera/mipmap.h — mip chains and resampling for texture compression.
//
// `generate_mipmaps` builds a full chain by repeated 2x2 box filtering (2x1 / 1x2 once one
// side reached 1), so non-square power-of-two images go all the way down to 1x1:
//  * sRGB data is averaged in linear light (gamma-correct) and re-encoded to sRGB;
//    `srgb = false` averages the stored values directly (linear data, normal maps, masks).
//  * with alpha, colours are weighted by alpha (premultiplied averaging) and un-premultiplied
//    afterwards, so transparent texels do not bleed their colour into visible ones. A fully
//    transparent footprint keeps the plain average of its colours.
//  * each level is computed from the previous level kept in float, so rounding does not
//    accumulate down the chain.
//
// `resize_image` resamples to an arbitrary size with a separable Lanczos-3 filter (windowed
// sinc, support 3 output texels when minifying), in the same light/alpha conventions; used by
// `tessera compress --resize-pot`.
//
// All functions are deterministic (identical output for any thread count) and thread-safe.
#pragma once

#include <vector>

#include "tessera/core.h"

namespace tessera::image {

/// The kernel that makes each mip level from the one above (every one in linear light when
/// `srgb`, alpha-weighted when `premultiply`).
enum class MipFilter {
  box,      ///< 2x2 box (2x1 / 1x2 once a side is 1): the default, and what GPUs' own
            ///< glGenerateMipmap does.
  lanczos,  ///< Separable Lanczos-3 windowed sinc, halving (support 6 texels of the level above
            ///< each way), edges wrapped; sharper than box, may ring (clamped to [0, 255]).
  kaiser,   ///< Separable Kaiser-windowed sinc (alpha 4, half-width 3 texels of the level above,
            ///< as NVIDIA Texture Tools' kaiser), edges wrapped; less ringing than Lanczos.
};

/// "box", "lanczos", "kaiser".
const char* mip_filter_name(MipFilter filter);

/// How colour is filtered.
struct MipmapOptions {
  bool srgb = true;         ///< Colour channels hold sRGB-encoded values: filter in linear light.
  bool premultiply = true;  ///< Weight colour by alpha when the image has alpha.
  int max_levels = 0;       ///< Levels to produce including level 0; 0 = down to 1x1.
  MipFilter filter = MipFilter::box;  ///< The kernel of each level.
  /// RGB holds unit vectors (x, y, z from [-1, 1] mapped to [0, 255]): levels are filtered as
  /// vectors and renormalised (a vector that averages to zero becomes +Z); `srgb` and
  /// `premultiply` do not apply to RGB then.
  bool normal_map = false;
  int threads = 0;          ///< Worker threads (0 = all).
};

// Level sizes and counts: `mip_dimension` and `mip_level_count` (tessera/core.h).

/// Builds the mip chain, level 0 (a copy of `image`) first. Level i is
/// mip_dimension(width, i) x mip_dimension(height, i). Fails on an empty image.
Result<std::vector<ImageRGBA8>> generate_mipmaps(const ImageRGBA8& image,
                                                 const MipmapOptions& options = {});

/// Resamples `image` to `width` x `height` with a separable Lanczos-3 filter (scaled to the
/// minification ratio), in linear light when `options.srgb`, premultiplied when
/// `options.premultiply` and the image has alpha. Results are clamped to [0, 255].
/// Working memory: about 16 bytes per source texel plus 28 per (target width x source height)
/// texel.
Result<ImageRGBA8> resize_image(const ImageRGBA8& image, int width, int height,
                                const MipmapOptions& options = {});

/// The power of two nearest to `size` (ties go up), at least 1.
int nearest_power_of_two(int size);

}  // namespace tessera::image
