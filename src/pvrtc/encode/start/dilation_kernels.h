// dilation_kernels.h — the row kernels of the intensity-dilation stage (dilation.cpp), as a
// table of plain function pointers chosen once at run time: the baseline kernels (SSE2 through
// simd.h, or scalar) everywhere, the AVX2 ones (dilation_avx2.cpp, built with -mavx2) where the
// CPU has AVX2. Both give bit-identical rows.
//
// This header is included by the AVX2 translation unit, so it must stay plain declarations: no
// inline functions, templates or standard headers that define any (an AVX2-compiled copy of an
// inline function could be the one the linker keeps for the whole program).
//
// Row conventions: every row pointer points at texel 0 of a row of `w` elements (w a power of
// two >= 8) stored with kDilationPad writable elements of padding on both sides. Kernels may
// read and write anything in the pads (lanes past w are don't-care, and must not be relied on);
// they set the wrap-around pad elements x = -1 and x = w of the rows they wrap (documented per
// kernel) themselves. Texel rows (`src`) are w RGBA8 texels, read only within the row.
#pragma once

#include <cstddef>
#include <cstdint>

namespace tessera::pvrtc::detail {

/// Elements of padding on each side of every row the kernels read or write.
constexpr int kDilationPad = 32;

/// The brightest and darkest texel of one block (texel coordinates). Trivial on purpose (no
/// member initialisers): an implicit constructor is an inline function, see above.
struct DilationExtremes {
  int xmax, ymax, xmin, ymin;
};

/// Row kernels of the dilation pipeline. `np` is the number of colour planes (3, or 4 in alpha
/// mode); images have np + 1 planes, the last one the filled flag (0 / 1).
struct DilationKernels {
  /// Intensity (Rec.709 luma, weights summing to 65536; times alpha / 255 floored when
  /// `alpha`) of the w texels at `src` into `out`, wrap-padded.
  void (*intensity_row)(const std::uint8_t* src, int w, bool alpha, float* out);
  /// Labels (1: local maximum, 2: local minimum, 0: neither; a texel whose 3x3 neighbourhood
  /// has one intensity is neither, so never both) of the row whose intensity is `i1`
  /// (i0 the row above, i2 below; all wrap-padded) into `out`. `tmax` / `tmin` are padded
  /// scratch rows.
  void (*label_row)(const float* i0, const float* i1, const float* i2, int w, float* tmax,
                    float* tmin, std::uint8_t* out);
  /// Initial planes of both extremum images for one row: p0[c] / p1[c] (c < np) take the
  /// texel's channel c where the label has bit 1 / bit 2, else 0; p0[np] / p1[np] the flag.
  void (*init_rows)(int np, const std::uint8_t* lab, const std::uint8_t* src, int w,
                    std::uint8_t* const* p0, std::uint8_t* const* p1);
  /// One 3x3 dilation pass for one row: in[k][c] is plane c (c <= np) of rows r-1, r, r+1
  /// (k = 0, 1, 2); `out` gets row r, where empty texels next to filled ones take the rounded
  /// mean of the filled neighbours. Scratch: `vf` one padded u8 row, `vs` np padded u16 rows
  /// `vstride` elements apart (vstride >= w + 2 * kDilationPad).
  void (*dilate_row)(int np, int w, const std::uint8_t* const (*in)[5], std::uint8_t* const* out,
                     std::uint8_t* vf, std::uint16_t* vs, std::size_t vstride);
  /// Adds plane k (`stride` apart from `row`) to the u16 column sums acc + k * astride
  /// (astride >= w + kDilationPad) for k < planes; `first` starts the sums instead.
  void (*accumulate_row)(int planes, int w, const std::uint8_t* row, std::size_t stride,
                         std::uint16_t* acc, std::size_t astride, bool first);
  /// The brightest and darkest texel of each of the `nbx` blocks (bw = 4 or 8 texels wide) of
  /// a block row, the first in raster order on ties: `rows` holds the block row's 4 intensity
  /// rows (integers below 2^24), W apart and unpadded; y0 is its first texel row.
  void (*block_extremes)(const float* rows, std::size_t W, int nbx, int bw, int y0,
                         DilationExtremes* ext);
  /// Per-block sums (blocks bw = 4 or 8 columns wide) of the u16 column sums of `planes`
  /// planes acc + k * astride (padded rows of w elements) into out + k * ostride (w / bw each).
  void (*block_sums)(const std::uint16_t* acc, std::size_t astride, int planes, int w, int bw,
                     std::uint32_t* out, std::size_t ostride);
};

/// Fills `k` with the AVX2 kernels (defined only when TESSERA_HAVE_AVX2_KERNELS; the caller
/// checks that the CPU has AVX2).
void fill_dilation_kernels_avx2(DilationKernels* k);

/// The baseline kernels (SSE2 or scalar; any x86-64 or other CPU).
const DilationKernels* dilation_kernels_baseline();
/// The AVX2 kernels, or nullptr where they are not built or the CPU lacks AVX2.
const DilationKernels* dilation_kernels_avx2();
/// Testing hook: `true` makes dilation_endpoints use the baseline kernels from its next call
/// on (whatever the CPU); `false` restores the run-time choice. Not thread-safe against
/// concurrent encodes.
void dilation_force_baseline(bool force);

}  // namespace tessera::pvrtc::detail
