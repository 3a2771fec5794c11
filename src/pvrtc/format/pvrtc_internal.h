// pvrtc_internal.h — image-level helpers shared by the PVRTC decoder and encoder drivers.
#pragma once

#include <cstdint>
#include <vector>

#include "pvrtc/format/pvrtc_kernel.h"
#include "tessera/pvrtc.h"

namespace tessera::pvrtc::detail {

/// Geometry of one level: block size, block counts (>= 2 each) and padded extent in texels.
struct Grid {
  Format format = Format::pvrtc1_4bpp;
  int bw = 4;   ///< Block width in texels (block height is always 4).
  int nbx = 2;  ///< Blocks along x.
  int nby = 2;  ///< Blocks along y.
  int pw = 8;   ///< Padded width = nbx * bw.
  int ph = 8;   ///< Padded height = nby * 4.
  std::size_t blocks() const { return std::size_t(nbx) * std::size_t(nby); }
  std::size_t texels() const { return std::size_t(pw) * std::size_t(ph); }
};

Grid make_grid(Format format, int width, int height);

/// Expanded endpoints A and B of every block, in linear (row-major) block order.
void expand_endpoints(const Grid& g, const std::uint64_t* words, Rgba5* ea, Rgba5* eb, int threads);

/// Effective modulation weight (0..8, | kPunchFlag when alpha is punched through) of every
/// texel of the padded level, row-major, from linear-order block words. Exactly PVRTexTool's
/// rules, including 2 bpp interpolated modes whose neighbours lie in adjacent blocks.
void modulation_map(const Grid& g, const std::uint64_t* words, std::uint8_t* m_eff, int threads);

/// 2 bpp: the 2-bit "stored" value of every texel of one block (0..3, row-major 8x4; 0 for the
/// interpolated texels) as PVRTexTool unpacks `word`, and the block's mode (0 direct, 1 H+V
/// interpolated, 2 H only, 3 V only).
void unpack_2bpp_block(std::uint64_t word, std::uint8_t values[32], int& mode);

/// 2 bpp: the 32 modulation bits of a block with stored `values` (as `unpack_2bpp_block` gives
/// them) and `mode`; the block's mode bit is mode != 0. The inverse of `unpack_2bpp_block`:
/// texel (0, 0), and (4, 2) under H / V only, must hold 0 or 3, direct blocks only 0 or 3.
std::uint32_t pack_2bpp_block(const std::uint8_t values[32], int mode);

/// Upscaled 8-bit RGBA of one endpoint image (ea or eb) for padded rows [y0, y1): writes
/// (y1 - y0) * pw * 4 bytes to `out`.
void upscale_rows(const Grid& g, const Rgba5* e, int y0, int y1, std::uint8_t* out);

/// Decodes linear-order words to the padded level (pw * ph RGBA texels).
void decode_padded(const Grid& g, const std::uint64_t* words, std::uint8_t* out, int threads);

/// Whether this build has the AVX2 kernels (*_avx2.cpp) and the CPU (and OS) can run them;
/// checked once. The one CPU check behind every AVX2 dispatch (dilation, 4 bpp modulation).
bool avx2_kernels_usable();

/// Morton-ordered little-endian bytes <-> linear-order words.
void load_words(const Grid& g, const std::uint8_t* data, std::uint64_t* words);
void store_words(const Grid& g, const std::uint64_t* words, std::uint8_t* data);

}  // namespace tessera::pvrtc::detail
