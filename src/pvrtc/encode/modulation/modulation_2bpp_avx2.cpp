// modulation_2bpp_avx2.cpp — the three 2 bpp modulation passes of modulation_2bpp.cpp on AVX2:
// two blocks a step (block bx in the low 128 bits, bx + 1 in the high), the same operations
// lane for lane as the baseline's one block row per SSE2 vector, so the same maps, bits, modes
// and errors (ties included). The 128-bit halves never mix until the per-block sums.
//
// Compiled with -mavx2 (src/CMakeLists.txt) and called only after the run-time CPU check in
// modulation_2bpp.cpp. So that no AVX2 code can stand in for baseline code elsewhere, this file
// includes no header with inline functions or templates of external linkage (avx2_common.h's
// and modulation_2bpp_bits.h's helpers have internal linkage; not simd.h,
// encode_internal.h or the standard containers) and keeps its helpers in an anonymous
// namespace; it exports the three `mod2_pass*_row_avx2` functions only.
#include "pvrtc/encode/modulation/modulation_2bpp_avx2.h"

#if defined(TESSERA_HAVE_AVX2_KERNELS) && !defined(__AVX2__)
#error "modulation_2bpp_avx2.cpp needs -mavx2 where TESSERA_HAVE_AVX2_KERNELS is set"
#endif

#if defined(__AVX2__)

#include <immintrin.h>

#include <cstring>

#include "pvrtc/encode/avx2_common.h"
#include "pvrtc/encode/modulation/modulation_2bpp_bits.h"

namespace tessera::pvrtc::detail {

namespace {

/// Sixteen 16-bit lanes, the pattern `l` (8 lanes) in both halves.
__m256i twice(const short l[8]) {
  return _mm256_setr_epi16(l[0], l[1], l[2], l[3], l[4], l[5], l[6], l[7],  //
                           l[0], l[1], l[2], l[3], l[4], l[5], l[6], l[7]);
}

/// Mask of up to two lanes (lane < 0: none) in both halves, as modulation_2bpp.cpp's
/// lane_mask / lane_mask2.
__m256i lane_mask2(int lane0, int lane1) {
  short l[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  if (lane0 >= 0) l[lane0] = -1;
  if (lane1 >= 0) l[lane1] = -1;
  return twice(l);
}

/// Constants shared by the passes (those of modulation_2bpp.cpp, in both halves).
struct Consts {
  __m256i wl, wr, even[2], lanebit, k1, k2, k3, k4, k5, k8;
  __m256i tap_l, tap_r;  // column-sum element shuffles: left / right taps of both blocks
  __m256i c0[4], l0[4], u0[4], c12[4], l12[4], r12[4], u12[4], d12[4];
  Consts() {
    const short wl8[8] = {4, 3, 2, 1, 8, 7, 6, 5}, wr8[8] = {4, 5, 6, 7, 0, 1, 2, 3};
    const short ev0[8] = {-1, 0, -1, 0, -1, 0, -1, 0}, ev1[8] = {0, -1, 0, -1, 0, -1, 0, -1};
    const short bit8[8] = {1, 2, 4, 8, 16, 32, 64, 128};
    wl = twice(wl8);
    wr = twice(wr8);
    even[0] = twice(ev0);
    even[1] = twice(ev1);
    lanebit = twice(bit8);
    k1 = _mm256_set1_epi16(1);
    k2 = _mm256_set1_epi16(2);
    k3 = _mm256_set1_epi16(3);
    k4 = _mm256_set1_epi16(4);
    k5 = _mm256_set1_epi16(5);
    k8 = _mm256_set1_epi16(8);
    // From the 4 elements p[0..3] (in both halves): block 0 takes p0 x4 p1 x4 (left) and
    // p1 x4 p2 x4 (right), block 1 the same one element on.
    tap_l = _mm256_setr_epi8(0, 1, 0, 1, 0, 1, 0, 1, 2, 3, 2, 3, 2, 3, 2, 3,  //
                             2, 3, 2, 3, 2, 3, 2, 3, 4, 5, 4, 5, 4, 5, 4, 5);
    tap_r = _mm256_setr_epi8(2, 3, 2, 3, 2, 3, 2, 3, 4, 5, 4, 5, 4, 5, 4, 5,  //
                             4, 5, 4, 5, 4, 5, 4, 5, 6, 7, 6, 7, 6, 7, 6, 7);
    for (int j = 0; j < 4; ++j) {
      c0[j] = lane_mask2(j == 0 ? 0 : -1, -1);
      l0[j] = lane_mask2(j == 0 ? 1 : -1, -1);
      u0[j] = lane_mask2(j == 1 ? 0 : -1, -1);
      c12[j] = lane_mask2(j == 0 ? 0 : j == 2 ? 4 : -1, -1);
      l12[j] = lane_mask2(j == 0 ? 1 : j == 2 ? 5 : -1, -1);
      r12[j] = lane_mask2(j == 2 ? 3 : -1, -1);
      u12[j] = lane_mask2(j == 1 ? 0 : -1, j == 3 ? 4 : -1);
      d12[j] = lane_mask2(j == 1 ? 4 : -1, -1);
    }
  }
};

inline __m256i add16(__m256i a, __m256i b) { return _mm256_add_epi16(a, b); }
inline __m256i mul16(__m256i a, __m256i b) { return _mm256_mullo_epi16(a, b); }
/// Lanes of `a` where `mask` is all ones, else lanes of `b` (simd::select).
inline __m256i select(__m256i mask, __m256i a, __m256i b) { return _mm256_blendv_epi8(b, a, mask); }

/// Per 128-bit half, the sum of its four 32-bit lanes (wrapping, as the baseline's hsum).
inline void hsum2(__m256i x, std::uint32_t& h0, std::uint32_t& h1) {
  x = _mm256_add_epi32(x, _mm256_shuffle_epi32(x, _MM_SHUFFLE(1, 0, 3, 2)));
  x = _mm256_add_epi32(x, _mm256_shuffle_epi32(x, _MM_SHUFFLE(2, 3, 0, 1)));
  h0 = std::uint32_t(_mm256_cvtsi256_si32(x));
  h1 = std::uint32_t(_mm_cvtsi128_si32(_mm256_extracti128_si256(x, 1)));
}

/// 16 bytes at p, zero-extended: texels 0-7 of block bx | block bx + 1.
inline __m256i load_u8x16(const std::uint8_t* p) {
  return _mm256_cvtepu8_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
}

/// Stores the low bytes of both halves' lanes (lanes <= 255): 16 bytes, block bx then bx + 1.
inline void store_u8x16(__m256i a, std::uint8_t* p) {
  const __m256i b = _mm256_permute4x64_epi64(_mm256_packus_epi16(a, a), _MM_SHUFFLE(3, 1, 2, 0));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(p), _mm256_castsi256_si128(b));
}

/// Stores the low bytes of half h's lanes (8 bytes: one block).
inline void store_half(__m256i a, int h, std::uint8_t* p) {
  const __m128i x = h ? _mm256_extracti128_si256(a, 1) : _mm256_castsi256_si128(a);
  _mm_storel_epi64(reinterpret_cast<__m128i*>(p), _mm_packus_epi16(x, x));
}

/// Upscaled A (a) and B (b) and the target (t) of texel row j of blocks bx and bx + 1.
template <bool kAlpha>
inline void load_row(const Consts& k, const Mod2RowAvx2& r, int bx, int j, __m256i a[4],
                     __m256i b[4], __m256i t[4]) {
  constexpr int nch = kAlpha ? 4 : 3;
  load_channels(r.t[j] + std::size_t(bx) * 32, t);
  for (int c = 0; c < nch; ++c) {
    for (int img = 0; img < 2; ++img) {
      const std::uint16_t* p = r.v[j] + std::size_t(img * 4 + c) * r.vstride + bx;
      long long e;
      std::memcpy(&e, p, 8);
      const __m256i q = _mm256_set1_epi64x(e);
      const __m256i L = _mm256_shuffle_epi8(q, k.tap_l), R = _mm256_shuffle_epi8(q, k.tap_r);
      const __m256i w = add16(mul16(L, k.wl), mul16(R, k.wr));
      const __m256i u = c < 3 ? add16(_mm256_srli_epi16(w, 7), _mm256_srli_epi16(w, 2))
                              : add16(_mm256_srli_epi16(w, 5), _mm256_srli_epi16(w, 1));
      (img == 0 ? a : b)[c] = u;
    }
  }
}

/// Squared error of (v[c] - t[c]) summed over the channels: texels 0-3 (lo) and 4-7 (hi) of
/// each block.
template <bool kAlpha>
inline void sq_err(const __m256i v[4], const __m256i t[4], __m256i& lo, __m256i& hi) {
  const __m256i dr = _mm256_sub_epi16(v[0], t[0]), dg = _mm256_sub_epi16(v[1], t[1]),
                db = _mm256_sub_epi16(v[2], t[2]);
  __m256i da = _mm256_setzero_si256();
  if constexpr (kAlpha) da = _mm256_sub_epi16(v[3], t[3]);
  const __m256i rg0 = _mm256_unpacklo_epi16(dr, dg), rg1 = _mm256_unpackhi_epi16(dr, dg);
  const __m256i ba0 = _mm256_unpacklo_epi16(db, da), ba1 = _mm256_unpackhi_epi16(db, da);
  lo = _mm256_add_epi32(_mm256_madd_epi16(rg0, rg0), _mm256_madd_epi16(ba0, ba0));
  hi = _mm256_add_epi32(_mm256_madd_epi16(rg1, rg1), _mm256_madd_epi16(ba1, ba1));
}

/// Error of blend (a (8 - m) + b m) / 8 with per-lane weights m, lanes 0-3 and 4-7 summed.
template <bool kAlpha>
inline __m256i blend_err(const Consts& k, const __m256i a[4], const __m256i b[4],
                         const __m256i t[4], __m256i m) {
  constexpr int nch = kAlpha ? 4 : 3;
  const __m256i im = _mm256_sub_epi16(k.k8, m);
  __m256i v[4];
  for (int c = 0; c < nch; ++c) v[c] = _mm256_srli_epi16(add16(mul16(a[c], im), mul16(b[c], m)), 3);
  __m256i lo, hi;
  sq_err<kAlpha>(v, t, lo, hi);
  return _mm256_add_epi32(lo, hi);
}

/// Map byte -> weight of its greedy code (0, 3, 5, 8) and of its A/B choice (0 or 8).
inline __m256i greedy_weight(const Consts& k, __m256i bytes) {
  const __m256i c = _mm256_and_si256(bytes, k.k3);
  return _mm256_sub_epi16(mul16(c, k.k3), _mm256_srli_epi16(c, 1));
}
inline __m256i ab_weight(const Consts& k, __m256i bytes) {
  const __m256i f = _mm256_and_si256(bytes, k.k4);
  return add16(f, f);
}

inline __m256i key(__m256i e, int rank) {
  return _mm256_or_si256(_mm256_slli_epi32(e, 2), _mm256_set1_epi32(rank));
}

template <bool kAlpha>
void pass1(const Mod2RowAvx2& r) {
  const Consts k;
  const __m256i one = _mm256_set1_epi32(1), three = _mm256_set1_epi32(3);
  for (int bx = 0; bx < r.nbx; bx += 2) {
    __m256i acc_err = _mm256_setzero_si256(), acc_bits = _mm256_setzero_si256();
    for (int j = 0; j < 4; ++j) {
      __m256i a[4], b[4], t[4], v3[4], v5[4];
      load_row<kAlpha>(k, r, bx, j, a, b, t);
      for (int c = 0; c < (kAlpha ? 4 : 3); ++c) {
        v3[c] = _mm256_srli_epi16(add16(mul16(a[c], k.k5), mul16(b[c], k.k3)), 3);
        v5[c] = _mm256_srli_epi16(add16(mul16(a[c], k.k3), mul16(b[c], k.k5)), 3);
      }
      __m256i e0[2], e3[2], e5[2], e8[2];
      sq_err<kAlpha>(a, t, e0[0], e0[1]);
      sq_err<kAlpha>(v3, t, e3[0], e3[1]);
      sq_err<kAlpha>(v5, t, e5[0], e5[1]);
      sq_err<kAlpha>(b, t, e8[0], e8[1]);
      __m256i code[2], bit[2];
      for (int h = 0; h < 2; ++h) {
        // First minimum via (error * 4 + rank), as the scalar scan.
        __m256i q = _mm256_slli_epi32(e0[h], 2);
        q = _mm256_min_epi32(q, key(e3[h], 1));
        q = _mm256_min_epi32(q, key(e5[h], 2));
        q = _mm256_min_epi32(q, key(e8[h], 3));
        code[h] = _mm256_and_si256(q, three);
        const __m256i q0 = _mm256_min_epi32(
            _mm256_slli_epi32(e0[h], 1), _mm256_or_si256(_mm256_slli_epi32(e8[h], 1), one));
        bit[h] = _mm256_and_si256(q0, one);
        acc_err = _mm256_add_epi32(acc_err, _mm256_srli_epi32(q0, 1));
      }
      const __m256i bytes =
          _mm256_packs_epi32(_mm256_or_si256(code[0], _mm256_slli_epi32(bit[0], 2)),
                             _mm256_or_si256(code[1], _mm256_slli_epi32(bit[1], 2)));
      store_u8x16(bytes, r.out[j] + std::size_t(bx) * 8);
      // Row j's 8 bits into byte j (the baseline's byte shift: each sum is below 256).
      const __m256i bits = _mm256_madd_epi16(_mm256_packs_epi32(bit[0], bit[1]), k.lanebit);
      acc_bits = _mm256_add_epi32(acc_bits, _mm256_sll_epi32(bits, _mm_cvtsi32_si128(8 * j)));
    }
    hsum2(acc_err, r.err0[bx], r.err0[bx + 1]);
    hsum2(acc_bits, r.mod[bx], r.mod[bx + 1]);
  }
}

template <bool kAlpha>
void pass2(const Mod2RowAvx2& r) {
  const Consts k;
  for (int bx = 0; bx < r.nbx; bx += 2) {
    const std::size_t x0 = std::size_t(bx) * 8;
    __m256i acc[3] = {_mm256_setzero_si256(), _mm256_setzero_si256(), _mm256_setzero_si256()};
    __m256i c0[4], c12[4], cab[4];
    for (int j = 0; j < 4; ++j) {
      const std::uint8_t* cur = r.in[j + 1] + x0;
      const __m256i bc = load_u8x16(cur), bl = load_u8x16(cur - 1), br = load_u8x16(cur + 1),
                    bu = load_u8x16(r.in[j] + x0), bd = load_u8x16(r.in[j + 2] + x0);
      const __m256i cg = greedy_weight(k, bc), lg = greedy_weight(k, bl),
                    rg = greedy_weight(k, br), ug = greedy_weight(k, bu),
                    dg = greedy_weight(k, bd);
      const __m256i ca = ab_weight(k, bc), la = ab_weight(k, bl), ra = ab_weight(k, br),
                    ua = ab_weight(k, bu), da = ab_weight(k, bd);
      cab[j] = ca;
      c0[j] = select(k.c0[j], ca, cg);
      c12[j] = select(k.c12[j], ca, cg);
      const __m256i l0 = select(k.l0[j], la, lg), u0 = select(k.u0[j], ua, ug);
      const __m256i l12 = select(k.l12[j], la, lg), r12 = select(k.r12[j], ra, rg),
                    u12 = select(k.u12[j], ua, ug), d12 = select(k.d12[j], da, dg);
      const __m256i ev = k.even[j & 1];
      const __m256i m0 =
          select(ev, c0[j], _mm256_srli_epi16(add16(add16(add16(u0, dg), add16(l0, rg)), k.k2), 2));
      const __m256i m1 = select(ev, c12[j], _mm256_srli_epi16(add16(add16(l12, r12), k.k1), 1));
      const __m256i m2 = select(ev, c12[j], _mm256_srli_epi16(add16(add16(u12, d12), k.k1), 1));
      __m256i a[4], b[4], t[4];
      load_row<kAlpha>(k, r, bx, j, a, b, t);
      acc[0] = _mm256_add_epi32(acc[0], blend_err<kAlpha>(k, a, b, t, m0));
      acc[1] = _mm256_add_epi32(acc[1], blend_err<kAlpha>(k, a, b, t, m1));
      acc[2] = _mm256_add_epi32(acc[2], blend_err<kAlpha>(k, a, b, t, m2));
    }
    std::uint32_t e[3][2];
    for (int v = 0; v < 3; ++v) hsum2(acc[v], e[v][0], e[v][1]);
    for (int h = 0; h < 2; ++h) {
      const int bi = bx + h;
      const std::size_t xh = x0 + std::size_t(h) * 8;
      std::uint32_t best = r.err0[bi];
      int variant = -1;
      for (int v = 0; v < 3; ++v) {
        if (e[v][h] < best) {
          best = e[v][h];
          variant = v;
        }
      }
      if (variant < 0) {
        r.mode[bi] = 0;  // r.mod[bi]: the mode-0 bits from pass 1
        for (int j = 0; j < 4; ++j) store_half(cab[j], h, r.out[j] + xh);
        continue;
      }
      // Stored values as modulation_2bpp.cpp's pass 2 (modulation_2bpp_bits.h).
      const std::uint32_t bits = interpolated_bits(r.in, xh, variant);
      const std::uint8_t* row2 = r.in[3] + xh;
      r.mode[bi] = 1;
      r.mod[bi] = bits;
      for (int j = 0; j < 4; ++j) store_half(variant == 0 ? c0[j] : c12[j], h, r.out[j] + xh);
      if (variant == 0) r.out[2][xh + 4] = (row2[4] & 2) ? 5 : 0;
    }
  }
}

/// Variant of a mode-1 block from its bits: 0 H+V, 1 H only, 2 V only.
inline int variant_of(std::uint32_t bits) { return (bits & 1) ? ((bits & (1u << 20)) ? 2 : 1) : 0; }

template <bool kAlpha>
std::uint64_t pass3(const Mod2RowAvx2& r) {
  const Consts k;
  const __m256i lo_half = _mm256_setr_epi64x(-1, -1, 0, 0);
  std::uint64_t total = 0;
  for (int bx = 0; bx < r.nbx; bx += 2) {
    const bool m0 = r.mode[bx] != 0, m1 = r.mode[bx + 1] != 0;
    if (!m0 && !m1) {
      total += r.err0[bx];
      total += r.err0[bx + 1];
      continue;
    }
    // A mode-0 block is scored as its neighbour's variant, and its score dropped.
    int v0 = m0 ? variant_of(r.mod[bx]) : -1, v1 = m1 ? variant_of(r.mod[bx + 1]) : -1;
    if (v0 < 0) v0 = v1;
    if (v1 < 0) v1 = v0;
    const std::size_t x0 = std::size_t(bx) * 8;
    __m256i acc = _mm256_setzero_si256();
    for (int j = 0; j < 4; ++j) {
      const std::uint8_t* cur = r.in[j + 1] + x0;
      const __m256i wc = load_u8x16(cur);
      const auto interp_of = [&](int variant) {
        if (variant == 0) {
          return _mm256_srli_epi16(
              add16(add16(add16(load_u8x16(cur - 1), load_u8x16(cur + 1)),
                          add16(load_u8x16(r.in[j] + x0), load_u8x16(r.in[j + 2] + x0))),
                    k.k2),
              2);
        }
        if (variant == 1) {
          return _mm256_srli_epi16(add16(add16(load_u8x16(cur - 1), load_u8x16(cur + 1)), k.k1), 1);
        }
        return _mm256_srli_epi16(
            add16(add16(load_u8x16(r.in[j] + x0), load_u8x16(r.in[j + 2] + x0)), k.k1), 1);
      };
      const __m256i interp =
          v0 == v1 ? interp_of(v0) : select(lo_half, interp_of(v0), interp_of(v1));
      const __m256i m = select(k.even[j & 1], wc, interp);
      __m256i a[4], b[4], t[4];
      load_row<kAlpha>(k, r, bx, j, a, b, t);
      acc = _mm256_add_epi32(acc, blend_err<kAlpha>(k, a, b, t, m));
    }
    std::uint32_t e0, e1;
    hsum2(acc, e0, e1);
    total += m0 ? e0 : r.err0[bx];
    total += m1 ? e1 : r.err0[bx + 1];
  }
  return total;
}

}  // namespace

void mod2_pass1_row_avx2(const Mod2RowAvx2& r, bool alpha) {
  alpha ? pass1<true>(r) : pass1<false>(r);
}

void mod2_pass2_row_avx2(const Mod2RowAvx2& r, bool alpha) {
  alpha ? pass2<true>(r) : pass2<false>(r);
}

std::uint64_t mod2_pass3_row_avx2(const Mod2RowAvx2& r, bool alpha) {
  return alpha ? pass3<true>(r) : pass3<false>(r);
}

}  // namespace tessera::pvrtc::detail

#else  // no AVX2 in this build: never called (the dispatch checks TESSERA_HAVE_AVX2_KERNELS)

namespace tessera::pvrtc::detail {

void mod2_pass1_row_avx2(const Mod2RowAvx2&, bool) {}
void mod2_pass2_row_avx2(const Mod2RowAvx2&, bool) {}
std::uint64_t mod2_pass3_row_avx2(const Mod2RowAvx2&, bool) { return 0; }

}  // namespace tessera::pvrtc::detail

#endif
