// tessera/pvrtc.h — PVRTC1 (4 bpp and 2 bpp) encoder and decoder.
//
// What: `encode` turns an RGBA8 image into PVRTC1 blocks; `decode` turns blocks into RGBA8,
//   bit-exact with Imagination's PVRTexTool 4.17 (punch-through blocks, translucent colours,
//   non-square sizes, textures smaller than the 2x2-block minimum).
// Paper: Krajcevski & Manocha, "Fast PVRTC Compression using Intensity Dilation", JCGT 3(4),
//   2014: §4 is `Quality::fast`; `normal` and `high` add the two-stage refinement of its §1.2
//   and exact searches (pass by pass: docs/architecture.md, "The quality presets").
// Where: src/pvrtc/ (format/: bit layout, decoder; encode/: the passes); tessera/texture_file.h
//   writes the blocks into PVR / KTX files.
// Exactness: modulation is always chosen against the decoder's arithmetic, so the returned
//   bytes decode (in tessera or PVRTexTool) to exactly the image the encoder scored.
// Data: 64-bit little-endian blocks in Morton (twiddled) order, as in a PVR v3 file's level
//   data; power-of-two sizes, padded to at least 2x2 blocks (`block_count`).
// Threads: every function is thread-safe; `EncodeOptions::threads` and `decode`'s `parallel`
//   are worker counts (0 = all); the output bytes are the same for any count.
// Tests: tests/unit/pvrtc_*_test.cpp; tests/oracle/pvrtc_oracle_test.cpp (PVRTexTool); tests/arch/
// (bytes on every SIMD backend).
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

/// Encoder effort: each level costs more time for a lower error (what each runs:
/// docs/architecture.md, "The quality presets, pass by pass"; src/pvrtc/encode/schedule.cpp).
enum class Quality {
  fast,    ///< The paper's intensity dilation and brute-force modulation, nothing more.
  normal,  ///< + a principal-axis start, least-squares refinement and one exact search round
           ///< on the worst blocks (2 bpp: an exact modulation descent instead of the search).
  high,    ///< + the exact search to convergence and a crossover with a second encoding from
           ///< the dilation start (2 bpp: with an exact endpoint search).
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

/// Encoder options: the format, the effort and what the input holds; defaults give 4 bpp at
/// `normal`.
struct EncodeOptions {
  Format format = Format::pvrtc1_4bpp;
  Quality quality = Quality::normal;
  /// At most this many least-squares refinement sweeps; -1 = the preset's (fast 0, normal 3,
  /// high 3 at 4 bpp and 4 at 2 bpp). Every refinement stops early once a sweep gains less than
  /// 0.25% of the error. A value >= 0 also turns `high`'s crossover off.
  int iterations = -1;
  /// Rounds of the exact endpoint search after the refinement; 0 = the preset's. A positive
  /// value replaces the preset's search: 4 bpp, that many rounds (stopping early once no block
  /// changes) of greedy +-1 moves of each block's endpoint codes, kept where the exactly decoded
  /// error drops, on blocks above ~4.5 RMS per channel (RGB), up to 4 sweeps of the moves per
  /// block; 2 bpp, no endpoint search at all. It also turns `high`'s crossover off.
  int exact_search_rounds = 0;
  /// Allow punch-through (modulation mode 1) blocks for RGBA input. RGBA input also gets
  /// translucent endpoints where they quantise better; RGB input only opaque ones.
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
  int threads = 0;  ///< Worker threads (0 = all); the bytes are the same for any count.
  /// Optional progress hook: called with the fraction of this encode done, from the thread
  /// that called `encode` only (never from a worker), between the encoder's passes, sweeps and
  /// search rounds. Fractions never decrease (the first may be 0); a successful encode's last
  /// call is exactly 1.0. They estimate elapsed time (each pass weighted by its measured cost),
  /// so they advance unevenly. The hook never changes the output bytes; empty = no calls.
  std::function<void(double fraction)> progress;
};

/// Encodes one level of `image` into `level_size(options.format, width, height)` bytes of
/// blocks. The dimensions must pass `check_dimensions` (else its error status).
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
