// tessera/image_ops.h — per-texel preparations of an image before it is compressed: flips,
// premultiplied alpha, alpha bleeding and normal-map renormalisation.
//
// `texture_file::compress_image` applies them in the order its `CompressOptions` documents;
// they are public so that a pipeline can run them on its own. Every function is deterministic
// (the same bytes for any thread count) and thread-safe on distinct images.
// Tests: tests/unit/image_ops_test.cpp.
#pragma once

#include "tessera/core.h"

namespace tessera::image {

/// Flips `image` upside down in place (row 0 becomes the last).
void flip_y(ImageRGBA8& image);

/// Multiplies colour by alpha in place. With `srgb` the colour is decoded to linear light,
/// multiplied and re-encoded (exact sRGB curves in single precision, `srgb8_to_linear` and
/// `linear_to_srgb8`, rounded to nearest); otherwise the stored values are multiplied
/// (round(c * a / 255), in integers). Alpha is unchanged; an image without alpha is unchanged.
void premultiply_alpha(ImageRGBA8& image, bool srgb, const Parallel& parallel = {});

/// Alpha bleeding: every texel whose alpha is 0 takes the colour of the nearest texel whose
/// alpha is not 0 (Euclidean distance with the image wrapped around its edges, as PVRTC's
/// block interpolation and repeating textures wrap; among equally near texels the first in
/// row-major order), keeping alpha 0. An image with no visible texel, or without alpha, is
/// unchanged. Exact (a separable distance transform), O(pixels).
void bleed_alpha(ImageRGBA8& image, const Parallel& parallel = {});

/// Normal maps: each texel's RGB, read as a vector (2 c / 255 - 1), is scaled to unit length
/// and written back (c = round((v + 1) * 127.5)); a vector shorter than 1e-6 becomes +Z
/// (128, 128, 255), which 8-bit input never holds (each component is at least 1/255 from 0)
/// but filtered mip levels can. Alpha is unchanged.
void normalise_normals(ImageRGBA8& image, const Parallel& parallel = {});

}  // namespace tessera::image
