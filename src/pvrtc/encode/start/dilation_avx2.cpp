// The row kernels of the intensity dilation (dilation_kernels.h) over the SIMD wrapper's 8-lane
// types (core/simd_wide.h), 32 texels per step where the baseline kernels (dilation.cpp, over
// the 4-lane types) take 16, and block extremes by integer keys instead of a search;
// bit-identical to them. This file alone is compiled with -mavx2 (src/CMakeLists.txt: every
// */*_avx2.cpp, with TESSERA_HAVE_AVX2_KERNELS defined for the library), which gives the
// wrapper its AVX2 backend, and dilation.cpp calls it only on CPUs with AVX2. Compiled without
// -mavx2 it is empty.
//
// ODR safety: an inline function or template with external linkage compiled here could be the
// copy the linker keeps for the whole program, and then run on a CPU without AVX2. The wrapper's
// functions compiled here live in their own inline namespace (simd_int.h); otherwise this file
// includes only C headers, dilation_kernels.h (plain declarations) and dilation_rows.h (templates
// with internal linkage), keeps every helper in an anonymous namespace, and exports one function
// that fills the kernel table.
//
// Rows narrower than a vector (w = 8, 16) are processed a whole vector at a time: the extra
// lanes read and write the rows' padding (kDilationPad = 32 elements), except in the texel rows,
// which have none, where a scalar tail takes over.
#include "pvrtc/encode/start/dilation_kernels.h"

#if defined(TESSERA_HAVE_AVX2_KERNELS) && !defined(__AVX2__)
#error "dilation_avx2.cpp must be compiled with -mavx2 where TESSERA_HAVE_AVX2_KERNELS is set"
#endif

#if defined(__AVX2__)

#include <cstddef>
#include <cstdint>

#include "core/simd.h"
#include "pvrtc/encode/start/dilation_rows.h"

namespace tessera::pvrtc::detail {

namespace {

using u8 = std::uint8_t;
using u16 = std::uint16_t;
using namespace simd;


void intensity_row(const u8* src, int w, bool alpha, float* out) {
  const vint8 m8(0xff);
  const vf8 kr(13933.0f), kg(46871.0f), kb(4732.0f);
  for (int x = 0; x < w; x += 8) {
    const vint8 t = load_texels8(src + std::size_t(x) * 4);
    const vf8 r = to_float(t & m8), g = to_float(srl<8>(t) & m8), b = to_float(srl<16>(t) & m8);
    vf8 y = r * kr + g * kg + b * kb;
    // floor(y * a / 255) with y * a < 2^32 (exact in u32).
    if (alpha) y = to_float(div255_u32(to_int_trunc(y) * srl<24>(t)));
    storef8(y, out + x);
  }
  wrap_pad(out, w);
}

// Written once for both widths (dilation_rows.h).
void label_row(const float* i0, const float* i1, const float* i2, int w, float* mx, float* mn,
               u8* out) {
  label_row_t<vf8>(i0, i1, i2, w, mx, mn, out);
}

template <int np>
void init_rows(const u8* lab, const u8* src, int w, u8* const* p0, u8* const* p1) {
  const vu8x32 bit1(std::uint8_t{1}), bit2(std::uint8_t{2});
  int x = 0;
  for (; x + 32 <= w; x += 32) {
    vu8x32 ch[4];
    load_planes(src + std::size_t(x) * 4, ch);
    const vu8x32 l = load_u8x32(lab + x);
    const vu8x32 k0 = cmpeq(l & bit1, bit1), k1 = cmpeq(l & bit2, bit2);
    for (int i = 0; i < np; ++i) {
      store_u8x32(ch[i] & k0, p0[i] + x);
      store_u8x32(ch[i] & k1, p1[i] + x);
    }
    store_u8x32(k0 & bit1, p0[np] + x);
    store_u8x32(k1 & bit1, p1[np] + x);
  }
  for (; x < w; ++x) {  // rows narrower than 32 texels
    const bool f0 = lab[x] & 1, f1 = lab[x] & 2;
    for (int i = 0; i < np; ++i) {
      p0[i][x] = f0 ? src[std::size_t(x) * 4 + std::size_t(i)] : 0;
      p1[i][x] = f1 ? src[std::size_t(x) * 4 + std::size_t(i)] : 0;
    }
    p0[np][x] = f0;
    p1[np][x] = f1;
  }
}

void init_rows_any(int np, const u8* lab, const u8* src, int w, u8* const* p0, u8* const* p1) {
  if (np == 4) {
    init_rows<4>(lab, src, w, p0, p1);
  } else {
    init_rows<3>(lab, src, w, p0, p1);
  }
}

template <int np>
void dilate_row(int w, const u8* const (*rows)[5], u8* const* outp, u8* vf, u16* vs,
                std::size_t vstride) {
  // Local copies: the byte stores below could alias the caller's pointer arrays.
  const u8* in[3][np + 1];
  u8* out[np + 1];
  for (int c = 0; c <= np; ++c) {
    for (int d = 0; d < 3; ++d) in[d][c] = rows[d][c];
    out[c] = outp[c];
  }
  // Vertical sums of the flags (u8) and of each colour plane (u16), 32 texels at a time.
  for (int x = 0; x < w; x += 32) {
    store_u8x32(load_u8x32(in[0][np] + x) + load_u8x32(in[1][np] + x) + load_u8x32(in[2][np] + x),
                vf + x);
    for (int c = 0; c < np; ++c) {
      u16* v = vs + std::size_t(c) * vstride + x;
      for (int h = 0; h < 32; h += 16) {
        store_u16x16(load_u8x16_u16(in[0][c] + x + h) + load_u8x16_u16(in[1][c] + x + h) +
                         load_u8x16_u16(in[2][c] + x + h),
                     v + h);
      }
    }
  }
  wrap_pad(vf, w);
  for (int c = 0; c < np; ++c) wrap_pad(vs + std::size_t(c) * vstride, w);
  // Reciprocals of n = 2..9 (as dilation.cpp's kRecip16), in both halves; a u16 lane n indexes
  // them through the byte shuffle with bytes (2n - 4, 2n - 3) = n * 514 - 772, which for
  // n = 0, 1 has both high bits set and so gives 0.
  static constexpr std::uint16_t kRecip[16] = {32768, 21846, 16384, 13108, 10923, 9363, 8192, 7282,
                                               32768, 21846, 16384, 13108, 10923, 9363, 8192, 7282};
  const vu16x16 recip = load_u16x16(kRecip);
  const vu16x16 k514(std::uint16_t{514}), k772(std::uint16_t{772}), one16(std::uint16_t{1});
  const vu8x32 zero, one8(std::uint8_t{1});
  for (int x = 0; x < w; x += 32) {
    const vu8x32 n = load_u8x32(vf + x - 1) + load_u8x32(vf + x) + load_u8x32(vf + x + 1);
    const vu8x32 f = load_u8x32(in[1][np] + x);
    const vu8x32 need = andnot(cmpeq(n, zero), cmpeq(f, zero));
    store_u8x32(f | (need & one8), out[np] + x);
    if (!any(need)) {
      for (int c = 0; c < np; ++c) store_u8x32(load_u8x32(in[1][c] + x), out[c] + x);
      continue;
    }
    vu16x16 rcv[2], hv[2], single[2];
    for (int h = 0; h < 2; ++h) {
      const vu16x16 nn = h ? widen_hi(n) : widen_lo(n);
      rcv[h] = shuffle_bytes(recip, mullo(nn, k514) - k772);
      hv[h] = srl<1>(nn);
      single[h] = cmpeq(nn, one16);
    }
    for (int c = 0; c < np; ++c) {
      const u16* v = vs + std::size_t(c) * vstride + x;
      vu16x16 avg[2];
      for (int h = 0; h < 2; ++h) {
        const vu16x16 sum =
            load_u16x16(v + 16 * h - 1) + load_u16x16(v + 16 * h) + load_u16x16(v + 16 * h + 1);
        avg[h] = select(single[h], sum, mulhi(sum + hv[h], rcv[h]));
      }
      store_u8x32(select(need, narrow(avg[0], avg[1]), load_u8x32(in[1][c] + x)), out[c] + x);
    }
  }
}

void dilate_row_any(int np, int w, const u8* const (*in)[5], u8* const* out, u8* vf, u16* vs,
                    std::size_t vstride) {
  if (np == 4) {
    dilate_row<4>(w, in, out, vf, vs, vstride);
  } else {
    dilate_row<3>(w, in, out, vf, vs, vstride);
  }
}

void accumulate_row(int planes, int w, const u8* row, std::size_t stride, u16* acc,
                    std::size_t astride, bool first) {
  accumulate_row_t<vu8x32>(planes, w, row, stride, acc, astride, first);
}

// Extremes by keys: intensity * 32 plus the texel's raster index in the block (31 minus it for
// the maximum), so one integer maximum (minimum) finds the brightest (darkest) texel and the
// first of equal ones. Intensities are integers below 2^24: keys stay below 2^29.
void block_extremes(const float* rows, std::size_t W, int nbx, int bw, int y0,
                    DilationExtremes* ext) {
  const int w = nbx * bw;
  // Raster index of lane l in row 0: l & 3 (bw 4) or l (bw 8).
  const vint8 col(vint4(0, 1, 2, 3), bw == 4 ? vint4(0, 1, 2, 3) : vint4(4, 5, 6, 7));
  const vint8 k31(31);
  std::int32_t kmax[8], kmin[8];
  for (int x = 0; x < w; x += 8) {
    vint8 mx(-1), mn(0x7fffffff);
    for (int j = 0; j < 4; ++j) {
      const vint8 v = sll<5>(to_int_trunc(loadf8(rows + std::size_t(j) * W + std::size_t(x))));
      const vint8 idx = col + vint8(j * bw);
      mx = max(mx, v + (k31 - idx));
      mn = min(mn, v + idx);
    }
    // Reduce within each block's lanes (4, or all 8).
    mx = max(mx, swap_pairs64(mx));
    mn = min(mn, swap_pairs64(mn));
    mx = max(mx, swap_pairs(mx));
    mn = min(mn, swap_pairs(mn));
    if (bw == 8) {
      mx = max(mx, swap_halves(mx));
      mn = min(mn, swap_halves(mn));
    }
    store8(mx, kmax);
    store8(mn, kmin);
    for (int l = 0; l < 8; l += bw) {
      const int bx = (x + l) / bw;
      const int imax = 31 - (kmax[l] & 31), imin = kmin[l] & 31;
      DilationExtremes& e = ext[bx];
      e.xmax = bx * bw + (imax & (bw - 1));
      e.ymax = y0 + imax / bw;
      e.xmin = bx * bw + (imin & (bw - 1));
      e.ymin = y0 + imin / bw;
    }
  }
}

void block_sums(const u16* acc, std::size_t astride, int planes, int w, int bw,
                std::uint32_t* out, std::size_t ostride) {
  const vu16x16 ones(std::uint16_t{1});
  for (int c = 0; c < planes; ++c) {
    const u16* a = acc + std::size_t(c) * astride;
    std::int32_t* o = reinterpret_cast<std::int32_t*>(out + std::size_t(c) * ostride);
    int x = 0;
    for (; x + 32 <= w; x += 32) {
      // Column pairs, then quads: pair_sums works per half (quads 0, 1, 4, 5 | 2, 3, 6, 7),
      // which the permute puts back in order. Sums stay below 2^15.
      const vint8 p0 = madd(load_u16x16(a + x), ones), p1 = madd(load_u16x16(a + x + 16), ones);
      const vint8 q = permute64<0, 2, 1, 3>(pair_sums(p0, p1));
      if (bw == 4) {
        store8(q, o + x / 4);
      } else {
        store4(low(permute64<0, 2, 0, 0>(pair_sums(q, q))), o + x / 8);
      }
    }
    for (; x < w; x += bw) {  // rows narrower than 32 columns
      std::uint32_t sum = 0;
      for (int i = 0; i < bw; ++i) sum += a[x + i];
      out[std::size_t(c) * ostride + std::size_t(x / bw)] = sum;
    }
  }
}

}  // namespace

void fill_dilation_kernels_avx2(DilationKernels* k) {
  k->intensity_row = intensity_row;
  k->label_row = label_row;
  k->init_rows = init_rows_any;
  k->dilate_row = dilate_row_any;
  k->accumulate_row = accumulate_row;
  k->block_extremes = block_extremes;
  k->block_sums = block_sums;
}

}  // namespace tessera::pvrtc::detail

#endif  // __AVX2__
