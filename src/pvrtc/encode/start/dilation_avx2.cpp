// AVX2 row kernels of the intensity dilation (dilation_kernels.h), 32 texels per step where the
// baseline kernels (dilation.cpp, through simd.h) take 16, and block extremes by integer keys
// instead of a search; bit-identical to them. This file alone
// is compiled with -mavx2 (src/CMakeLists.txt: every */*_avx2.cpp, with TESSERA_HAVE_AVX2_KERNELS
// defined for the library), and dilation.cpp calls it only on CPUs with AVX2. Compiled without
// -mavx2 it is empty.
//
// ODR safety: an inline function or template with external linkage compiled here could be the
// copy the linker keeps for the whole program, and then run on a CPU without AVX2. So this file
// includes only <immintrin.h>, C headers and dilation_kernels.h (plain declarations), keeps every
// helper in an anonymous namespace, and exports one function that fills the kernel table.
//
// Rows narrower than a vector (w = 8, 16) are processed a whole vector at a time: the extra
// lanes read and write the rows' padding (kDilationPad = 32 elements), except in the texel rows,
// which have none, where a scalar tail takes over.
#include "pvrtc/encode/start/dilation_kernels.h"

#if defined(TESSERA_HAVE_AVX2_KERNELS) && !defined(__AVX2__)
#error "dilation_avx2.cpp must be compiled with -mavx2 where TESSERA_HAVE_AVX2_KERNELS is set"
#endif

#if defined(__AVX2__)

#include <immintrin.h>

#include <cstddef>
#include <cstdint>

namespace tessera::pvrtc::detail {

namespace {

using u8 = std::uint8_t;
using u16 = std::uint16_t;

__m256i load(const void* p) { return _mm256_loadu_si256(static_cast<const __m256i*>(p)); }
void store(void* p, __m256i v) { _mm256_storeu_si256(static_cast<__m256i*>(p), v); }
// 16 bytes at p zero-extended to 16 u16 lanes, in order.
__m256i load_widen(const u8* p) {
  return _mm256_cvtepu8_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
}

template <typename T>
void wrap_pad(T* row, int w) {
  row[-1] = row[w - 1];
  row[w] = row[0];
}

void intensity_row(const u8* src, int w, bool alpha, float* out) {
  const __m256i m8 = _mm256_set1_epi32(0xff);
  const __m256 kr = _mm256_set1_ps(13933.0f), kg = _mm256_set1_ps(46871.0f),
               kb = _mm256_set1_ps(4732.0f);
  const __m256i kDiv255 = _mm256_set1_epi32(std::int32_t(0x80808081u));  // ceil(2^39 / 255)
  for (int x = 0; x < w; x += 8) {
    const __m256i t = load(src + std::size_t(x) * 4);
    const __m256 r = _mm256_cvtepi32_ps(_mm256_and_si256(t, m8));
    const __m256 g = _mm256_cvtepi32_ps(_mm256_and_si256(_mm256_srli_epi32(t, 8), m8));
    const __m256 b = _mm256_cvtepi32_ps(_mm256_and_si256(_mm256_srli_epi32(t, 16), m8));
    __m256 y = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(r, kr), _mm256_mul_ps(g, kg)),
                             _mm256_mul_ps(b, kb));
    if (alpha) {
      // floor(y * a / 255) with y * a < 2^32 (exact in u32): x / 255 == (x * 0x80808081) >> 39
      // for every u32 x (the compilers' own division by 255), on the even and odd lanes.
      const __m256i ya = _mm256_mullo_epi32(_mm256_cvttps_epi32(y), _mm256_srli_epi32(t, 24));
      const __m256i even = _mm256_srli_epi64(_mm256_mul_epu32(ya, kDiv255), 39);
      const __m256i odd =
          _mm256_srli_epi64(_mm256_mul_epu32(_mm256_srli_epi64(ya, 32), kDiv255), 7);
      y = _mm256_cvtepi32_ps(_mm256_blend_epi32(even, odd, 0xaa));
    }
    _mm256_storeu_ps(out + x, y);
  }
  wrap_pad(out, w);
}

void label_row(const float* i0, const float* i1, const float* i2, int w, float* mx, float* mn,
               u8* out) {
  for (int x = 0; x < w; x += 8) {
    const __m256 a = _mm256_loadu_ps(i0 + x), c = _mm256_loadu_ps(i1 + x),
                 d = _mm256_loadu_ps(i2 + x);
    _mm256_storeu_ps(mx + x, _mm256_max_ps(_mm256_max_ps(a, c), d));
    _mm256_storeu_ps(mn + x, _mm256_min_ps(_mm256_min_ps(a, c), d));
  }
  wrap_pad(mx, w);
  wrap_pad(mn, w);
  const __m256i one = _mm256_set1_epi32(1), two = _mm256_set1_epi32(2);
  for (int x = 0; x < w; x += 8) {
    const __m256 v = _mm256_loadu_ps(i1 + x);
    const __m256 m = _mm256_max_ps(
        _mm256_max_ps(_mm256_loadu_ps(mx + x - 1), _mm256_loadu_ps(mx + x)),
        _mm256_loadu_ps(mx + x + 1));
    const __m256 n = _mm256_min_ps(
        _mm256_min_ps(_mm256_loadu_ps(mn + x - 1), _mm256_loadu_ps(mn + x)),
        _mm256_loadu_ps(mn + x + 1));
    const __m256i is_max = _mm256_castps_si256(_mm256_cmp_ps(m, v, _CMP_EQ_OQ));
    const __m256i is_min = _mm256_castps_si256(_mm256_cmp_ps(n, v, _CMP_EQ_OQ));
    const __m256i flat = _mm256_castps_si256(_mm256_cmp_ps(m, n, _CMP_EQ_OQ));
    const __m256i l = _mm256_andnot_si256(
        flat, _mm256_or_si256(_mm256_and_si256(is_max, one), _mm256_and_si256(is_min, two)));
    const __m128i p16 =
        _mm_packs_epi32(_mm256_castsi256_si128(l), _mm256_extracti128_si256(l, 1));
    _mm_storel_epi64(reinterpret_cast<__m128i*>(out + x), _mm_packus_epi16(p16, p16));
  }
}

template <int np>
void init_rows(const u8* lab, const u8* src, int w, u8* const* p0, u8* const* p1) {
  // Per 128-bit lane: 4 RGBA texels to [R0..R3 G0..G3 B0..B3 A0..A3].
  const __m256i shuf = _mm256_setr_epi8(0, 4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15, 0,
                                        4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15);
  const __m256i order = _mm256_setr_epi32(0, 4, 1, 5, 2, 6, 3, 7);
  const __m256i bit1 = _mm256_set1_epi8(1), bit2 = _mm256_set1_epi8(2);
  int x = 0;
  for (; x + 32 <= w; x += 32) {
    const u8* s = src + std::size_t(x) * 4;
    __m256i v[4];
    for (int i = 0; i < 4; ++i) v[i] = _mm256_shuffle_epi8(load(s + 32 * i), shuf);
    // Dword transposition: texels 0-3 | 4-7 of v[0], 8-11 | 12-15 of v[1], ...
    const __m256i a = _mm256_unpacklo_epi32(v[0], v[1]), b = _mm256_unpackhi_epi32(v[0], v[1]),
                  c = _mm256_unpacklo_epi32(v[2], v[3]), d = _mm256_unpackhi_epi32(v[2], v[3]);
    __m256i ch[4];
    ch[0] = _mm256_permutevar8x32_epi32(_mm256_unpacklo_epi64(a, c), order);
    ch[1] = _mm256_permutevar8x32_epi32(_mm256_unpackhi_epi64(a, c), order);
    ch[2] = _mm256_permutevar8x32_epi32(_mm256_unpacklo_epi64(b, d), order);
    ch[3] = _mm256_permutevar8x32_epi32(_mm256_unpackhi_epi64(b, d), order);
    const __m256i l = load(lab + x);
    const __m256i k0 = _mm256_cmpeq_epi8(_mm256_and_si256(l, bit1), bit1);
    const __m256i k1 = _mm256_cmpeq_epi8(_mm256_and_si256(l, bit2), bit2);
    for (int i = 0; i < np; ++i) {
      store(p0[i] + x, _mm256_and_si256(ch[i], k0));
      store(p1[i] + x, _mm256_and_si256(ch[i], k1));
    }
    store(p0[np] + x, _mm256_and_si256(k0, bit1));
    store(p1[np] + x, _mm256_and_si256(k1, bit1));
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
    store(vf + x, _mm256_add_epi8(_mm256_add_epi8(load(in[0][np] + x), load(in[1][np] + x)),
                                  load(in[2][np] + x)));
    for (int c = 0; c < np; ++c) {
      u16* v = vs + std::size_t(c) * vstride + x;
      for (int h = 0; h < 32; h += 16) {
        store(v + h, _mm256_add_epi16(_mm256_add_epi16(load_widen(in[0][c] + x + h),
                                                       load_widen(in[1][c] + x + h)),
                                      load_widen(in[2][c] + x + h)));
      }
    }
  }
  wrap_pad(vf, w);
  for (int c = 0; c < np; ++c) wrap_pad(vs + std::size_t(c) * vstride, w);
  // Reciprocals of n = 2..9 (as dilation.cpp's kRecip16); a u16 lane n indexes them through the
  // byte shuffle with bytes (2n - 4, 2n - 3) = n * 514 - 772, which for n = 0, 1 has both high
  // bits set and so gives 0.
  const __m256i recip = _mm256_broadcastsi128_si256(
      _mm_setr_epi16(32768 - 65536, 21846, 16384, 13108, 10923, 9363, 8192, 7282));
  const __m256i k514 = _mm256_set1_epi16(514), k772 = _mm256_set1_epi16(772);
  const __m256i zero = _mm256_setzero_si256(), one8 = _mm256_set1_epi8(1),
                one16 = _mm256_set1_epi16(1);
  for (int x = 0; x < w; x += 32) {
    const __m256i n =
        _mm256_add_epi8(_mm256_add_epi8(load(vf + x - 1), load(vf + x)), load(vf + x + 1));
    const __m256i f = load(in[1][np] + x);
    const __m256i need =
        _mm256_andnot_si256(_mm256_cmpeq_epi8(n, zero), _mm256_cmpeq_epi8(f, zero));
    store(out[np] + x, _mm256_or_si256(f, _mm256_and_si256(need, one8)));
    if (_mm256_testz_si256(need, need)) {
      for (int c = 0; c < np; ++c) store(out[c] + x, load(in[1][c] + x));
      continue;
    }
    __m256i rcv[2], hv[2], single[2];
    for (int h = 0; h < 2; ++h) {
      const __m256i nn = _mm256_cvtepu8_epi16(h ? _mm256_extracti128_si256(n, 1)
                                                : _mm256_castsi256_si128(n));
      rcv[h] = _mm256_shuffle_epi8(recip, _mm256_sub_epi16(_mm256_mullo_epi16(nn, k514), k772));
      hv[h] = _mm256_srli_epi16(nn, 1);
      single[h] = _mm256_cmpeq_epi16(nn, one16);
    }
    for (int c = 0; c < np; ++c) {
      const u16* v = vs + std::size_t(c) * vstride + x;
      __m256i avg[2];
      for (int h = 0; h < 2; ++h) {
        const __m256i sum = _mm256_add_epi16(
            _mm256_add_epi16(load(v + 16 * h - 1), load(v + 16 * h)), load(v + 16 * h + 1));
        avg[h] = _mm256_blendv_epi8(
            _mm256_mulhi_epu16(_mm256_add_epi16(sum, hv[h]), rcv[h]), sum, single[h]);
      }
      // packus interleaves the 128-bit lanes: texels 0-7, 16-23, 8-15, 24-31 before the permute.
      const __m256i avg8 = _mm256_permute4x64_epi64(_mm256_packus_epi16(avg[0], avg[1]), 0xd8);
      store(out[c] + x, _mm256_blendv_epi8(load(in[1][c] + x), avg8, need));
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
  for (int k = 0; k < planes; ++k) {
    const u8* p = row + std::size_t(k) * stride;
    u16* a = acc + std::size_t(k) * astride;
    for (int x = 0; x < w; x += 32) {
      const __m256i lo = load_widen(p + x), hi = load_widen(p + x + 16);
      if (first) {
        store(a + x, lo);
        store(a + x + 16, hi);
      } else {
        store(a + x, _mm256_add_epi16(load(a + x), lo));
        store(a + x + 16, _mm256_add_epi16(load(a + x + 16), hi));
      }
    }
  }
}

// Extremes by keys: intensity * 32 plus the texel's raster index in the block (31 minus it for
// the maximum), so one integer maximum (minimum) finds the brightest (darkest) texel and the
// first of equal ones. Intensities are integers below 2^24: keys stay below 2^29.
void block_extremes(const float* rows, std::size_t W, int nbx, int bw, int y0,
                    DilationExtremes* ext) {
  const int w = nbx * bw;
  // Raster index of lane l in row 0: l & 3 (bw 4) or l (bw 8).
  const __m256i col = bw == 4 ? _mm256_setr_epi32(0, 1, 2, 3, 0, 1, 2, 3)
                              : _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256i k31 = _mm256_set1_epi32(31);
  alignas(32) std::int32_t kmax[8], kmin[8];
  for (int x = 0; x < w; x += 8) {
    __m256i mx = _mm256_set1_epi32(-1), mn = _mm256_set1_epi32(0x7fffffff);
    for (int j = 0; j < 4; ++j) {
      const __m256i v = _mm256_slli_epi32(
          _mm256_cvttps_epi32(_mm256_loadu_ps(rows + std::size_t(j) * W + std::size_t(x))), 5);
      const __m256i idx = _mm256_add_epi32(col, _mm256_set1_epi32(j * bw));
      mx = _mm256_max_epi32(mx, _mm256_add_epi32(v, _mm256_sub_epi32(k31, idx)));
      mn = _mm256_min_epi32(mn, _mm256_add_epi32(v, idx));
    }
    // Reduce within each block's lanes (4, or all 8).
    mx = _mm256_max_epi32(mx, _mm256_shuffle_epi32(mx, 0x4e));
    mn = _mm256_min_epi32(mn, _mm256_shuffle_epi32(mn, 0x4e));
    mx = _mm256_max_epi32(mx, _mm256_shuffle_epi32(mx, 0xb1));
    mn = _mm256_min_epi32(mn, _mm256_shuffle_epi32(mn, 0xb1));
    if (bw == 8) {
      mx = _mm256_max_epi32(mx, _mm256_permute2x128_si256(mx, mx, 0x01));
      mn = _mm256_min_epi32(mn, _mm256_permute2x128_si256(mn, mn, 0x01));
    }
    _mm256_store_si256(reinterpret_cast<__m256i*>(kmax), mx);
    _mm256_store_si256(reinterpret_cast<__m256i*>(kmin), mn);
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
  const __m256i ones = _mm256_set1_epi16(1);
  for (int c = 0; c < planes; ++c) {
    const u16* a = acc + std::size_t(c) * astride;
    std::uint32_t* o = out + std::size_t(c) * ostride;
    int x = 0;
    for (; x + 32 <= w; x += 32) {
      // Column pairs, then quads: hadd interleaves the 128-bit lanes (quads 0, 1, 4, 5 | 2, 3,
      // 6, 7), which the permute puts back in order. Sums stay below 2^15.
      const __m256i p0 = _mm256_madd_epi16(load(a + x), ones);
      const __m256i p1 = _mm256_madd_epi16(load(a + x + 16), ones);
      const __m256i q = _mm256_permute4x64_epi64(_mm256_hadd_epi32(p0, p1), 0xd8);
      if (bw == 4) {
        store(o + x / 4, q);
      } else {
        const __m256i e = _mm256_permute4x64_epi64(_mm256_hadd_epi32(q, q), 0x08);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(o + x / 8), _mm256_castsi256_si128(e));
      }
    }
    for (; x < w; x += bw) {  // rows narrower than 32 columns
      std::uint32_t sum = 0;
      for (int i = 0; i < bw; ++i) sum += a[x + i];
      o[x / bw] = sum;
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
