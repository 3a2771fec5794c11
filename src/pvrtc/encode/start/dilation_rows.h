// dilation_rows.h — the row kernels of the intensity dilation (dilation_kernels.h), written once
// over the SIMD wrapper's types and compiled per instruction set: with the 4-lane types in
// dilation.cpp (the baseline kernels) and with the 8-lane ones in dilation_avx2.cpp. Same
// operations lane for lane, so the same rows whichever width runs.
//
// Rows narrower than a vector (w = 8, 16 with 32 lanes of bytes) are processed a whole vector at
// a time: the extra lanes read and write the rows' padding (kDilationPad = 32 elements), except
// in the texel rows, which have none, where a scalar tail takes over.
//
// Included by the -mavx2 translation unit: everything here is a template in an anonymous
// namespace (internal linkage), so no AVX2-compiled copy can stand in for a baseline one.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/simd.h"
#include "pvrtc/encode/start/dilation_kernels.h"

namespace tessera::pvrtc::detail {
namespace {

/// Sets the wrap-around pad elements next to a row of w elements (x = -1 and x = w).
template <typename T>
inline void wrap_pad(T* row, int w) {
  row[-1] = row[w - 1];
  row[w] = row[0];
}

/// DilationKernels::intensity_row over float vectors VF (simd::vf32x4 or vf32x8).
template <class VF>
void intensity_row_t(const std::uint8_t* src, int w, bool alpha, float* out) {
  using namespace simd;
  using VI = decltype(to_int_trunc(VF()));
  constexpr int n = kLanes<VF>;
  const VI m8(0xff);
  const VF kr(13933.0f), kg(46871.0f), kb(4732.0f);
  for (int x = 0; x < w; x += n) {
    const VI t = load_texels_as<VI>(src + std::size_t(x) * 4);
    VF y = to_float(t & m8) * kr + to_float(srl<8>(t) & m8) * kg + to_float(srl<16>(t) & m8) * kb;
    // floor(y * a / 255) with y * a <= 255 * 65536 * 255 < 2^32 (exact in u32).
    if (alpha) y = to_float(div255_u32(to_int_trunc(y) * srl<24>(t)));
    store(y, out + x);
  }
  wrap_pad(out, w);
}

/// DilationKernels::label_row over float vectors VF (simd::vf32x4 or vf32x8): the vertical 3-max /
/// 3-min of each column into `mx` / `mn`, then each texel's label from the horizontal ones.
template <class VF>
void label_row_t(const float* i0, const float* i1, const float* i2, int w, float* mx, float* mn,
                 std::uint8_t* out) {
  using namespace simd;
  using VI = decltype(cmpeq(VF(), VF()));
  constexpr int n = kLanes<VF>;
  for (int x = 0; x < w; x += n) {
    const VF a = load_as<VF>(i0 + x), c = load_as<VF>(i1 + x), d = load_as<VF>(i2 + x);
    store(max(max(a, c), d), mx + x);
    store(min(min(a, c), d), mn + x);
  }
  wrap_pad(mx, w);
  wrap_pad(mn, w);
  const VI one(1), two(2);
  for (int x = 0; x < w; x += n) {
    const VF v = load_as<VF>(i1 + x);
    const VF m = max(max(load_as<VF>(mx + x - 1), load_as<VF>(mx + x)), load_as<VF>(mx + x + 1));
    const VF s = min(min(load_as<VF>(mn + x - 1), load_as<VF>(mn + x)), load_as<VF>(mn + x + 1));
    // A texel whose 3x3 neighbourhood has one intensity (m == s) is neither.
    const VI l = (cmpeq(m, v) & one) | (cmpeq(s, v) & two);
    store_bytes(andnot(cmpeq(m, s), l), out + x);
  }
}

/// DilationKernels::init_rows over byte vectors VU8 (simd::vu8x16 or vu8x32), np colour planes.
template <class VU8, int np>
void init_rows_t(const std::uint8_t* lab, const std::uint8_t* src, int w, std::uint8_t* const* p0s,
                 std::uint8_t* const* p1s) {
  using namespace simd;
  constexpr int n = kLanes<VU8>;
  // Local copies: the byte stores below could alias the caller's pointer arrays.
  std::uint8_t *p0[np + 1], *p1[np + 1];
  for (int c = 0; c <= np; ++c) {
    p0[c] = p0s[c];
    p1[c] = p1s[c];
  }
  const VU8 bit1(std::uint8_t{1}), bit2(std::uint8_t{2});
  int x = 0;
  for (; x + n <= w; x += n) {
    VU8 ch[4];
    load_planes(src + std::size_t(x) * 4, ch);
    const VU8 l = load_as<VU8>(lab + x);
    const VU8 k0 = cmpeq(l & bit1, bit1), k1 = cmpeq(l & bit2, bit2);
    for (int c = 0; c < np; ++c) {
      store(ch[c] & k0, p0[c] + x);
      store(ch[c] & k1, p1[c] + x);
    }
    store(k0 & bit1, p0[np] + x);
    store(k1 & bit1, p1[np] + x);
  }
  for (; x < w; ++x) {  // rows narrower than a vector
    const bool f0 = lab[x] & 1, f1 = lab[x] & 2;
    for (int c = 0; c < np; ++c) {
      p0[c][x] = f0 ? src[std::size_t(x) * 4 + std::size_t(c)] : 0;
      p1[c][x] = f1 ? src[std::size_t(x) * 4 + std::size_t(c)] : 0;
    }
    p0[np][x] = f0;
    p1[np][x] = f1;
  }
}

/// DilationKernels::dilate_row over byte vectors VU8 (simd::vu8x16 or vu8x32), np colour planes.
/// The rounded mean of n filled neighbours: floor(x / n) for x < 2400 and 2 <= n <= 9 equals
/// mulhi(x, ceil(65536 / n)) (the error term stays below 1 / 9); n == 1 is passed through.
template <class VU8, int np>
void dilate_row_t(int w, const std::uint8_t* const (*rows)[5], std::uint8_t* const* outp,
                  std::uint8_t* vf, std::uint16_t* vs, std::size_t vstride) {
  using namespace simd;
  using VU16 = decltype(widen_lo(VU8()));
  constexpr int n = kLanes<VU8>, h = n / 2;
  // Local copies: the byte stores below could alias the caller's pointer arrays.
  const std::uint8_t* in[3][np + 1];
  std::uint8_t* out[np + 1];
  for (int c = 0; c <= np; ++c) {
    for (int d = 0; d < 3; ++d) in[d][c] = rows[d][c];
    out[c] = outp[c];
  }
  // Vertical sums of the flags (u8) and of each colour plane (u16).
  for (int x = 0; x < w; x += n) {
    store(load_as<VU8>(in[0][np] + x) + load_as<VU8>(in[1][np] + x) + load_as<VU8>(in[2][np] + x),
          vf + x);
    for (int c = 0; c < np; ++c) {
      std::uint16_t* v = vs + std::size_t(c) * vstride + x;
      for (int k = 0; k < n; k += h) {
        store(load_widen_as<VU16>(in[0][c] + x + k) + load_widen_as<VU16>(in[1][c] + x + k) +
                  load_widen_as<VU16>(in[2][c] + x + k),
              v + k);
      }
    }
  }
  wrap_pad(vf, w);
  for (int c = 0; c < np; ++c) wrap_pad(vs + std::size_t(c) * vstride, w);
  // ceil(65536 / n) for n = 2..9, indexed by n - 2 (n = 0, 1 give -2, -1: 0).
  static constexpr std::uint16_t kRecip[8] = {32768, 21846, 16384, 13108, 10923, 9363, 8192, 7282};
  const VU16 one16(std::uint16_t{1}), two16(std::uint16_t{2});
  const VU8 zero(std::uint8_t{0}), one8(std::uint8_t{1});
  for (int x = 0; x < w; x += n) {
    const VU8 nb = load_as<VU8>(vf + x - 1) + load_as<VU8>(vf + x) + load_as<VU8>(vf + x + 1);
    const VU8 f = load_as<VU8>(in[1][np] + x);
    const VU8 need = andnot(cmpeq(nb, zero), cmpeq(f, zero));
    store(f | (need & one8), out[np] + x);
    if (!any(need)) {
      for (int c = 0; c < np; ++c) store(load_as<VU8>(in[1][c] + x), out[c] + x);
      continue;
    }
    VU16 rcv[2], hv[2], single[2];
    for (int k = 0; k < 2; ++k) {
      const VU16 nn = k ? widen_hi(nb) : widen_lo(nb);
      rcv[k] = lookup8(kRecip, nn - two16);
      hv[k] = srl<1>(nn);
      single[k] = cmpeq(nn, one16);
    }
    for (int c = 0; c < np; ++c) {
      const std::uint16_t* v = vs + std::size_t(c) * vstride + x;
      VU16 avg[2];
      for (int k = 0; k < 2; ++k) {
        const VU16 sum =
            load_as<VU16>(v + h * k - 1) + load_as<VU16>(v + h * k) + load_as<VU16>(v + h * k + 1);
        avg[k] = select(single[k], sum, mulhi(sum + hv[k], rcv[k]));
      }
      store(select(need, narrow(avg[0], avg[1]), load_as<VU8>(in[1][c] + x)), out[c] + x);
    }
  }
}

/// DilationKernels::accumulate_row over byte vectors VU8 (simd::vu8x16 or vu8x32).
template <class VU8>
void accumulate_row_t(int planes, int w, const std::uint8_t* row, std::size_t stride,
                      std::uint16_t* acc, std::size_t astride, bool first) {
  using namespace simd;
  using VU16 = decltype(widen_lo(VU8()));
  constexpr int n = kLanes<VU8>, h = n / 2;
  for (int k = 0; k < planes; ++k) {
    const std::uint8_t* p = row + std::size_t(k) * stride;
    std::uint16_t* a = acc + std::size_t(k) * astride;
    for (int x = 0; x < w; x += n) {
      const VU8 v = load_as<VU8>(p + x);
      if (first) {
        store(widen_lo(v), a + x);
        store(widen_hi(v), a + x + h);
      } else {
        store(load_as<VU16>(a + x) + widen_lo(v), a + x);
        store(load_as<VU16>(a + x + h) + widen_hi(v), a + x + h);
      }
    }
  }
}

/// DilationKernels::block_extremes over float vectors VF (simd::vf32x4 or vf32x8), by keys:
/// intensity
/// * 32 plus the texel's raster index in the block (31 minus it for the maximum), so one integer
/// maximum (minimum) finds the brightest (darkest) texel and the first of equal ones.
/// Intensities are integers below 2^24: keys stay below 2^29.
template <class VF>
void block_extremes_t(const float* rows, std::size_t W, int nbx, int bw, int y0,
                      DilationExtremes* ext) {
  using namespace simd;
  using VI = decltype(to_int_trunc(VF()));
  constexpr int n = kLanes<VF>;
  const int w = nbx * bw, step = bw > n ? bw : n;  // whole blocks and whole vectors
  static constexpr std::int32_t kIota[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  const VI col0 = load_as<VI>(kIota) & VI(bw - 1), k31(31);
  std::int32_t kmax[n], kmin[n];
  for (int x = 0; x < w; x += step) {
    VI mx(-1), mn(0x7fffffff);
    for (int q = 0; q < step; q += n) {  // two vectors a block where bw = 8 > n
      for (int j = 0; j < 4; ++j) {
        const VI v =
            sll<5>(to_int_trunc(load_as<VF>(rows + std::size_t(j) * W + std::size_t(x + q))));
        const VI idx = col0 + VI(q + j * bw);
        mx = max(mx, v + (k31 - idx));
        mn = min(mn, v + idx);
      }
    }
    // Reduce within each block's lanes (4, or all 8).
    mx = max(mx, swap_pairs64(mx));
    mn = min(mn, swap_pairs64(mn));
    mx = max(mx, swap_pairs(mx));
    mn = min(mn, swap_pairs(mn));
    if constexpr (n == 8) {
      if (bw == 8) {
        mx = max(mx, swap_halves(mx));
        mn = min(mn, swap_halves(mn));
      }
    }
    store(mx, kmax);
    store(mn, kmin);
    for (int l = 0; l < n; l += bw) {
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

/// DilationKernels::block_sums over 16-bit vectors VU16 (simd::vu16x8 or vu16x16), blocks BW
/// columns wide: column pairs by one multiply-add, then the pairs of each block.
template <class VU16, int BW>
void block_sums_t(const std::uint16_t* acc, std::size_t astride, int planes, int w,
                  std::uint32_t* out, std::size_t ostride) {
  using namespace simd;
  constexpr int n = kLanes<VU16>, m = n / 2;
  const VU16 ones(std::uint16_t{1});
  for (int c = 0; c < planes; ++c) {
    const std::uint16_t* a = acc + std::size_t(c) * astride;
    std::uint32_t* o = out + std::size_t(c) * ostride;
    for (int x = 0; x < w; x += n) {
      std::int32_t p[m];
      store(madd(load_as<VU16>(a + x), ones), p);           // column pairs (sums below 2^15)
      const int pairs = (w - x) / 2 < m ? (w - x) / 2 : m;  // lanes past w: the row's pad
      for (int i = 0; i < pairs; i += BW / 2) {
        std::int32_t sum = 0;
        for (int k = 0; k < BW / 2; ++k) sum += p[i + k];
        o[(x + 2 * i) / BW] = std::uint32_t(sum);
      }
    }
  }
}

/// The kernel table of one width: VF float lanes, VU8 byte lanes (vf32x4 / vu8x16 or vf32x8 /
/// vu8x32).
template <class VF, class VU8>
struct RowKernels {
  using VU16 = decltype(simd::widen_lo(VU8()));
  static void init_rows(int np, const std::uint8_t* lab, const std::uint8_t* src, int w,
                        std::uint8_t* const* p0, std::uint8_t* const* p1) {
    if (np == 4) {
      init_rows_t<VU8, 4>(lab, src, w, p0, p1);
    } else {
      init_rows_t<VU8, 3>(lab, src, w, p0, p1);
    }
  }
  static void dilate_row(int np, int w, const std::uint8_t* const (*in)[5],
                         std::uint8_t* const* out, std::uint8_t* vf, std::uint16_t* vs,
                         std::size_t vstride) {
    if (np == 4) {
      dilate_row_t<VU8, 4>(w, in, out, vf, vs, vstride);
    } else {
      dilate_row_t<VU8, 3>(w, in, out, vf, vs, vstride);
    }
  }
  static void block_sums(const std::uint16_t* acc, std::size_t astride, int planes, int w, int bw,
                         std::uint32_t* out, std::size_t ostride) {
    if (bw == 4) {
      block_sums_t<VU16, 4>(acc, astride, planes, w, out, ostride);
    } else {
      block_sums_t<VU16, 8>(acc, astride, planes, w, out, ostride);
    }
  }
  static constexpr DilationKernels kTable = {
      intensity_row_t<VF>,   label_row_t<VF>,      init_rows, dilate_row,
      accumulate_row_t<VU8>, block_extremes_t<VF>, block_sums};
};

}  // namespace
}  // namespace tessera::pvrtc::detail
