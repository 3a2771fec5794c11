// tessera/pvrtc.h — PVRTC1 (4 bpp and 2 bpp) encoder and decoder.
//
// The decoder is bit-exact with Imagination's PVRTexTool 4.17 (the reference), including
// punch-through blocks, translucent colours, non-square power-of-two sizes and textures
// smaller than the 2x2-block minimum. The encoder implements "Fast PVRTC Compression using
// Intensity Dilation" (Krajcevski & Manocha, JCGT 3(4), 2014) for `Quality::fast`. `normal` and
// `high` run the two-stage scheme of the paper's §1.2: initial endpoints (principal-axis split of
// each block's bilinear footprint: unlike intensity labelling it separates equally bright
// colours, e.g. across the wrap-around seam; pairs of about equal brightness are oriented to
// agree with their neighbours), an exact "reseed" of 4 bpp blocks the footprint start misses
// (endpoints from the block's own texels, kept where the exactly decoded error drops), then
// alternating least-squares optimisation of the block colours (modulation fixed) and
// brute-force modulation (colours fixed), then (4 bpp) an exact greedy search over +-1 moves of
// each block's endpoint codes scored by the exactly decoded error of its 7x7 texel window
// (2 bpp: exact modulation descent, and at `high` an exact endpoint search over the 15x7
// texels a block reaches). `high` also encodes from the dilation start and keeps, block by
// block, the endpoints of whichever encoding errs less (a crossover: the two starts stop in
// different local minima, the dilation one wins along sharp edges), then resumes the exact
// search (2 bpp: the result is kept where its exact total error is lower).
//
// Modulation is always chosen against the exact decoder arithmetic, so the bytes an encode
// returns decode (in tessera or PVRTexTool) to exactly the image the encoder scored.
// 4 bpp RGBA input uses translucent endpoints where they quantise better and punch-through
// (mode 1) blocks where they lower the error; RGB input writes only opaque endpoints.
//
// Data layout: compressed data is a sequence of 64-bit little-endian blocks in Morton
// (twiddled) order, exactly as stored in a PVR v3 file's level data. Each level holds
// `block_count(format, width, height)` blocks; dimensions must be powers of two (not
// necessarily equal); anything smaller than 2x2 blocks is padded to 2x2 blocks.
//
// Threading: every function is thread-safe; `EncodeOptions::threads` and `decode`'s `parallel`
// are the number of worker threads (0 = all). Output bytes are identical for any thread count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "tessera/core.h"

namespace tessera::pvrtc {

/// PVRTC1 variants.
enum class Format {
  pvrtc1_4bpp,  ///< 4x4 texels per 64-bit block.
  pvrtc1_2bpp,  ///< 8x4 texels per 64-bit block.
};

/// Encoder effort.
enum class Quality {
  fast,    ///< Intensity dilation only (the paper's algorithm), 4 bpp mode 0 (+ punch-through).
  normal,  ///< Principal-axis start, 1 reseed pass (4 bpp), 3 refinement sweeps, then (4 bpp)
           ///< one round of the exact search on blocks above ~6.4 RMS per channel; 4 bpp
           ///< also tries mode 1. 2 bpp: every modulation choice of the refinement is followed
           ///< by one sweep of exact coordinate descent on the stored modulation values and
           ///< interpolation variants.
  high,    ///< Principal-axis start, 2 reseed passes (4 bpp), then 4 bpp: 3 refinement sweeps
           ///< and the exact search (with neighbour-copy moves) on every block until no block
           ///< changes (alpha error weighted x2 for RGBA); then a second encoding from the
           ///< dilation start, searched the same way, is crossed in block by block where it
           ///< errs less, and the search resumes where the two meet. 2 bpp: refinement (with
           ///< the modulation descent, as normal) until a sweep gains < 0.25% (at most 16
           ///< sweeps), then two more descent sweeps.
};

/// Block width in texels (4 for 4 bpp, 8 for 2 bpp); blocks are always 4 texels high.
int block_width(Format format);
/// Number of blocks along x / y for a level of the given size (at least 2 each).
int blocks_x(Format format, int width);
int blocks_y(Format format, int height);
/// Number of 64-bit blocks in one level.
std::size_t block_count(Format format, int width, int height);
/// Bytes of one level (block_count * 8).
std::size_t level_size(Format format, int width, int height);

/// Checks that `width` x `height` is encodable: both powers of two, within
/// `kMaxImageDimension`. `what` names the source for the message.
Status check_dimensions(int width, int height, const std::string& what);

/// Morton (twiddled) index of block (bx, by) in a grid of `bw` x `bh` blocks (powers of two):
/// y bit 0, x bit 1, alternating; the surplus high bits of the larger dimension come above.
std::uint32_t morton_index(std::uint32_t bx, std::uint32_t by, std::uint32_t bw, std::uint32_t bh);

/// Encoder options.
struct EncodeOptions {
  Format format = Format::pvrtc1_4bpp;
  Quality quality = Quality::normal;
  /// Refinement sweeps; -1 = the quality preset's default (fast 0, normal 3, high 3 at 4 bpp
  /// and up to 16, until a sweep gains < 0.25%, at 2 bpp).
  int iterations = -1;
  /// 4 bpp only: rounds of exact greedy search over +-1 changes of each block's endpoint codes
  /// after the refinement, keeping changes that lower the exactly decoded error, on blocks
  /// above ~4.5 RMS per channel with up to 4 sweeps of the moves per block (0 = the preset's
  /// default: see `Quality`). A positive value replaces the preset's search.
  int exact_search_rounds = 0;
  /// Allow punch-through (modulation mode 1) blocks for RGBA input.
  bool punch_through = true;
  /// Treat the input as RGBA even if `image.has_alpha` is false (otherwise alpha is ignored and
  /// only opaque colours are written).
  bool force_alpha = false;
  /// The input's RGB is a normal map (unit vectors, x, y, z from [-1, 1] mapped to [0, 255]):
  /// after the quality's passes, which minimise RGB error, every texel's modulation is chosen
  /// by the angle between its decoded vector and the input's (what a renderer that
  /// renormalises sees): 4 bpp, and 2 bpp blocks in direct mode. Never raises a texel's angle.
  bool normal_map = false;
  /// 4 bpp, straight alpha: the encoder weights each texel's colour error (R, G, B) by its
  /// alpha, about what a blending renderer shows (colour x alpha: each colour difference scaled
  /// by alpha / 255, quantised to sixteenths, at least 3/16; alpha error keeps its weight), so
  /// few bits go to the colour of invisible texels (best with --alpha-bleed, which gives them
  /// the nearest visible colour). Opaque texels weigh what they weigh without it, so a fully
  /// opaque image encodes to the same bytes. Only for RGBA input (`has_alpha` or `force_alpha`;
  /// otherwise it changes nothing). With `Format::pvrtc1_2bpp` `encode` fails with
  /// invalid_argument. Meant for straight alpha: premultiplied colour already carries alpha.
  bool alpha_weighted = false;
  int threads = 0;
  /// Optional progress hook: called with the fraction of this encode done, from the thread
  /// that called `encode` only (never from a worker), between the encoder's passes, sweeps and
  /// search rounds. Fractions never decrease (the first may be 0); a successful encode's last
  /// call is exactly 1.0. They estimate elapsed time (each pass weighted by its measured cost),
  /// so they advance unevenly. The hook never changes the output bytes; empty = no calls.
  std::function<void(double fraction)> progress;
};

/// Encodes one level. `image` dimensions must pass `check_dimensions`. Output size is
/// `level_size(options.format, image.width, image.height)`.
Result<std::vector<std::uint8_t>> encode(const ImageRGBA8& image, const EncodeOptions& options);

/// Encodes one level straight from pixels the caller owns (RGB or RGBA, any strides: see
/// `ImageView8`), with the same bytes as encoding `to_image(image)`. Packed RGBA whose alpha is
/// used (or is 255 everywhere) is read in place, without a copy; other layouts are packed in
/// one pass. Alpha is used when `image.has_alpha` or `options.force_alpha`.
Result<std::vector<std::uint8_t>> encode(const ImageView8& image, const EncodeOptions& options);

/// Decodes one level of `width` x `height` from `data` (at least `level_size` bytes) to RGBA8.
/// Output `has_alpha` is true when any decoded alpha differs from 255.
Result<ImageRGBA8> decode(std::span<const std::uint8_t> data, Format format, int width, int height,
                          const Parallel& parallel = {});

/// Whether `data` (64-bit blocks as `decode` takes them; a partial block at the end is ignored)
/// can decode to any texel with alpha below 255: true when a block has a translucent endpoint
/// (colour A or B with its opaque bit, bit 47 or 63, clear) or, at 4 bpp, is a punch-through
/// block (mode bit 32 set) with a texel whose modulation value is 2. Conservative: a translucent
/// endpoint whose weight is 0 at every texel still counts. Containers without an RGB/RGBA
/// distinction (KTX 2.0) derive `has_alpha` from it.
bool may_have_alpha(std::span<const std::uint8_t> data, Format format);

}  // namespace tessera::pvrtc
