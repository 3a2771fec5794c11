// tessera/image_mipmap.h — mip chains and resampling for texture compression.
//
// `generate_mipmaps` builds a full chain, each level from the one above, so non-square images
// go all the way down to 1x1. The filter (`MipFilter`) is by default the 2x2 box (2x1 / 1x2
// once one side reached 1); `lanczos` and `kaiser` are separable windowed sincs that halve
// each side, with the kernel's x in texels of the level being made (output texel i is centred
// between texels 2 i and 2 i + 1 of the level above), zero from |x| = 3 (12 taps of the level
// above, 6 each side), edges wrapped as a repeating texture's are, weights normalised to 1:
//    lanczos(x) = sinc(x) sinc(x / 3),   kaiser(x) = sinc(x) I0(4 sqrt(1 - (x / 3)^2)) / I0(4)
// with sinc(x) = sin(pi x) / (pi x). A side of 1 is not filtered; an odd side (of a
// non-power-of-two image) is stretched to the exact ratio of the sizes. Every filter:
//  * sRGB data is averaged in linear light (gamma-correct) and re-encoded to sRGB;
//    `srgb = false` averages the stored values directly (linear data, masks).
//  * with alpha, colours are weighted by alpha (premultiplied averaging) and un-premultiplied
//    afterwards, so transparent texels do not bleed their colour into visible ones. A fully
//    transparent footprint keeps the plain average of its colours (for the sincs: wherever the
//    filtered alpha is at most 1e-4, which quantises to 0).
//  * each level is computed from the previous level kept in float, so rounding does not
//    accumulate down the chain. The sincs' results (which may ring) are clamped to [0, 1], in
//    the float level too (normal vectors are renormalised instead).
//  * with `normal_map`, RGB are vectors: level 0's are decoded (2 c / 255 - 1) and normalised,
//    each level's are filtered as plain vectors (no sRGB, no alpha weighting), renormalised (a
//    zero vector becomes +Z) and stored as `normalise_normals` stores them (image_ops.h); the
//    next level is made from the renormalised vectors. Alpha is filtered as usual.
//
// `resize_image` resamples to an arbitrary size with a separable Lanczos-3 filter (windowed
// sinc, support 3 output texels when minifying), in the same light/alpha conventions; used by
// `tessera compress --resize-pot`.
//
// All functions are deterministic (identical output for any thread count) and thread-safe.
// Tests: tests/unit/mipmap_test.cpp.
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
  kaiser,   ///< Separable Kaiser-windowed sinc (alpha 4, half-width 3 texels of the level made,
            ///< i.e. 6 of the level above, as NVIDIA Texture Tools' KaiserFilter(3) resamples),
            ///< edges wrapped; a little less ringing than Lanczos (a step overshoots by 7.7% of
            ///< its height instead of 8.2%).
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
  int threads = 0;  ///< Worker threads (0 = all).
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
