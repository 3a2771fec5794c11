// Initial PVRTC endpoints by intensity dilation (Krajcevski & Manocha 2014, §2-3).
//
// 1. Intensity: Rec.709 luma (CIE Y) with alpha premultiplied when alpha is meaningful.
// 2. Labelling: a texel is a local maximum (minimum) when no 8-neighbour (wrapping) is brighter
//    (darker) and not all of them have its intensity. The paper (§4.3) names both ways a
//    uniform area can go: no extremum at all, or every texel both. Its authors' code (FasTC)
//    takes the first: a texel is an extremum only where its neighbours are not all level with
//    it, which measured better than marking uniform areas as both
//    (docs/benchmarks/pvrtc_history.md): a uniform area next to a brighter one does not
//    spread its colour into the bright side's high image (or a dark side's low image), and a
//    uniform block falls back to its own extremes, which are its colour.
// 3. Dilation: each extremum image is dilated three times with a 3x3 kernel; an empty texel
//    next to several filled ones takes their average (rounded).
// 4. Block colours: the mean over the block's texels of the dilated image, where texels still
//    empty take the block's own extreme (brightest / darkest) texel colour; in a block of one
//    intensity, the brightest / darkest by the colours' own luma.
//
// The stages run as a row pipeline over a band of block rows: each new intensity row lets the
// labelling produce the row above it, which lets dilation pass 1 produce the row above that, and
// so on; every stage keeps only its last three rows (a ring), so the working set is a few rows
// whatever the image size and each row is computed once per stage (plus a 4-row halo per band).
// Bands write only their own blocks and the halo makes each band exact, so the output does not
// depend on the band size or the thread count. Rows are stored with a wrap-around pad on both
// sides, so the 3x3 kernels need no edge cases.
//
// The row kernels (dilation_kernels.h) are written once (dilation_rows.h) and come from a table
// chosen once at run time: compiled here over the 4-lane types (SSE2, NEON or scalar through
// simd.h), or in dilation_avx2.cpp over the 8-lane ones where the CPU has AVX2; the driver
// (dilate_band) is the same for both.
#include <algorithm>
#include <atomic>
#include <cstring>

#include "core/simd.h"
#include "core/simd_dispatch.h"
#include "pvrtc/encode/encode_internal.h"
#include "pvrtc/encode/start/dilation_kernels.h"
#include "pvrtc/encode/start/dilation_rows.h"

namespace tessera::pvrtc::detail {

namespace {

constexpr int kDilations = 3;
constexpr int kHalo = kDilations + 1;  // rows of intensity needed above/below a band
constexpr int kPad = kDilationPad;     // elements of padding on each side of a stored row

/// Ring of the last three rows of `planes` planes of element type T, rows padded by kPad.
template <typename T>
struct Ring {
  int planes = 0;
  std::size_t stride = 0;
  std::vector<T> buf;
  void init(int nplanes, int w) {
    planes = nplanes;
    stride = std::size_t(w) + 2 * kPad;
    buf.assign(3 * std::size_t(planes) * stride, T(0));
  }
  /// Row `r` (any integer >= 0 in band-local numbering) of plane `k`, pointing at texel 0.
  T* row(int k, int r) {
    return &buf[(std::size_t(r % 3) * std::size_t(planes) + std::size_t(k)) * stride + kPad];
  }
};

// Plane layout of one extremum image: colour planes 0..nplanes-1, then the filled flag (0/1).
struct Band {
  Ring<float> inten;                  // intensity
  Ring<std::uint8_t> lab;             // 1 = local maximum, 2 = local minimum
  Ring<std::uint8_t> img[2][3];       // [max/min][initial, pass 1, pass 2]
  std::vector<std::uint8_t> last[2];  // pass 3 rows (consumed at once), nplanes + 1 planes
  std::vector<float> tmax, tmin;      // vertical 3-max / 3-min of one row (padded)
  std::vector<std::uint8_t> vf;       // vertical flag sums of one row (padded)
  std::vector<std::uint16_t> vs;      // vertical colour sums of one row, per plane (padded)
  std::vector<std::uint16_t> acc[2];  // per column, per plane: sums over the block row so far
};

using Extremes = DilationExtremes;

// The baseline kernels: dilation_rows.h over the 4-lane types.
constexpr DilationKernels kBaseline = RowKernels<simd::vf32x4, simd::vu8x16>::kTable;

std::atomic<bool> g_force_baseline{false};

// The kernels of this CPU, chosen once.
const DilationKernels* native_kernels() {
  static const DilationKernels* const k = [] {
#if defined(TESSERA_NO_SIMD)
    return &kBaseline;  // the scalar backend everywhere (the AVX2 kernels stay testable)
#else
    const DilationKernels* avx2 = dilation_kernels_avx2();
    return avx2 ? avx2 : &kBaseline;
#endif
  }();
  return k;
}

// Block rows [by0, by1) with `nplanes` colour planes (3, or 4 in alpha mode).
template <int nplanes>
void dilate_band(const DilationKernels& kern, const EncoderState& s, int by0, int by1,
                 std::vector<float>& low, std::vector<float>& high, std::uint8_t* flat) {
  const Grid& g = s.g;
  const std::uint8_t* t = s.target.data();
  const int w = g.pw, hm = g.ph - 1, bw = g.bw;
  const std::size_t W = std::size_t(w);
  const int Y0 = int(by0) * 4, Y1 = int(by1) * 4;
  // Band-local row numbering: texel row y is local row y - Y0 + 8 (>= 0).
  auto local = [&](int y) { return y - Y0 + 8; };
  Band b;
  constexpr int np1 = nplanes + 1;
  b.inten.init(1, w);
  b.lab.init(1, w);
  for (auto& img : b.img) {
    for (auto& r : img) r.init(np1, w);
  }
  const std::size_t rstride = W + 2 * kPad;
  for (auto& l : b.last) l.assign(std::size_t(np1) * rstride, 0);
  b.tmax.assign(rstride, 0.0f);
  b.tmin.assign(rstride, 0.0f);
  b.vf.assign(rstride, 0);
  b.vs.assign(std::size_t(nplanes) * rstride, 0);
  const std::size_t astride = W + kPad;
  for (auto& a : b.acc) a.assign(std::size_t(np1) * astride, 0);
  // Block extremes of two block rows: the pipeline finishes a block row 4 rows after its
  // intensity, while the next block row's extremes are being found.
  std::vector<Extremes> ext_rows[2];
  for (auto& e : ext_rows) e.resize(std::size_t(g.nbx));
  std::vector<float> brow(4 * W);      // intensity of the current block row
  std::vector<std::uint32_t> bsum[2];  // per image: block sums of each plane
  for (auto& v : bsum) v.resize(std::size_t(np1) * std::size_t(g.nbx));

  auto planes_of = [&](Ring<std::uint8_t>& r, int y, std::uint8_t** p) {
    for (int k = 0; k < np1; ++k) p[k] = r.row(k, local(y));
  };
  for (int L = Y0 - kHalo; L < Y1 + kHalo; ++L) {
    // Intensity row L, and the block extremes of the band's own rows.
    const std::uint8_t* srcL = t + std::size_t(L & hm) * W * 4;
    float* il = b.inten.row(0, local(L));
    kern.intensity_row(srcL, w, s.alpha_mode, il);
    if (L >= Y0 && L < Y1) {
      std::memcpy(&brow[std::size_t(L & 3) * W], il, W * sizeof(float));
      if ((L & 3) == 3) {
        Extremes* ext = ext_rows[(L >> 2) & 1].data();
        kern.block_extremes(brow.data(), W, g.nbx, bw, L - 3, ext);
      }
    }
    // Labels and initial planes of row L - 1.
    const int yl = L - 1;
    if (yl < Y0 - kDilations) continue;
    std::uint8_t* lab = b.lab.row(0, local(yl));
    kern.label_row(b.inten.row(0, local(yl - 1)), b.inten.row(0, local(yl)), il, w,
                   b.tmax.data() + kPad, b.tmin.data() + kPad, lab);
    {
      std::uint8_t *p0[5], *p1[5];
      planes_of(b.img[0][0], yl, p0);
      planes_of(b.img[1][0], yl, p1);
      kern.init_rows(nplanes, lab, t + std::size_t(yl & hm) * W * 4, w, p0, p1);
    }
    // Dilation passes: pass p produces row L - 1 - p from rows L - 2 - p .. L - p.
    for (int pass = 1; pass <= kDilations; ++pass) {
      const int y = L - 1 - pass;
      if (y < Y0 - kDilations + pass) break;
      for (int k = 0; k < 2; ++k) {
        const std::uint8_t* in[3][5];
        for (int d = 0; d < 3; ++d) {
          for (int c = 0; c < np1; ++c) in[d][c] = b.img[k][pass - 1].row(c, local(y - 1 + d));
        }
        std::uint8_t* out[5];
        if (pass < kDilations) {
          planes_of(b.img[k][pass], y, out);
        } else {
          for (int c = 0; c < np1; ++c) out[c] = b.last[k].data() + std::size_t(c) * rstride + kPad;
        }
        kern.dilate_row(nplanes, w, in, out, b.vf.data() + kPad, b.vs.data() + kPad, rstride);
        if (pass == kDilations) {
          kern.accumulate_row(np1, w, out[0], rstride, b.acc[k].data(), astride, (y & 3) == 0);
        }
      }
    }
    // A finished block row: block means, empty texels taking the block's extreme colour.
    const int yf = L - 1 - kDilations;
    if (yf < Y0 || (yf & 3) != 3) continue;
    const int by = yf >> 2;
    const std::uint32_t n = std::uint32_t(4 * bw);
    const float inv = 1.0f / float(n);
    for (int k = 0; k < 2; ++k) {
      kern.block_sums(b.acc[k].data(), astride, np1, w, bw, bsum[k].data(), std::size_t(g.nbx));
    }
    for (int bx = 0; bx < g.nbx; ++bx) {
      const Extremes& e = ext_rows[by & 1][std::size_t(bx)];
      const std::uint8_t* fill_c[2] = {t + (std::size_t(e.ymax) * W + std::size_t(e.xmax)) * 4,
                                       t + (std::size_t(e.ymin) * W + std::size_t(e.xmin)) * 4};
      const std::size_t bi = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
      // Ties go to the first texel in raster order for both, so the brightest and the
      // darkest texel are the same one exactly when all intensities are equal.
      const bool one_intensity = e.xmax == e.xmin && e.ymax == e.ymin;
      if (flat != nullptr) flat[bi] = one_intensity;
      // A block of one intensity (uniform, or fully transparent with alpha premultiplied
      // into the intensity, or equally bright hues) has every texel as its brightest and
      // darkest: there the colours' own Rec.709 luma breaks the tie, so the texels the
      // dilation left empty take the block's brightest and darkest colour (first in
      // raster order on ties) instead of its first texel for both.
      if (one_intensity) {
        int lmax = -1, lmin = 1 << 30;
        for (int yy = 0; yy < 4; ++yy) {
          const std::uint8_t* row = t + (std::size_t(by * 4 + yy) * W + std::size_t(bx * bw)) * 4;
          for (int xx = 0; xx < bw; ++xx) {
            const std::uint8_t* p = row + std::size_t(xx) * 4;
            const int l = 2126 * p[0] + 7152 * p[1] + 722 * p[2];
            if (l > lmax) {
              lmax = l;
              fill_c[0] = p;
            }
            if (l < lmin) {
              lmin = l;
              fill_c[1] = p;
            }
          }
        }
      }
      float* dst[2] = {&high[bi * 4], &low[bi * 4]};
      for (int k = 0; k < 2; ++k) {
        std::uint32_t sum[5] = {};
        for (int c = 0; c < np1; ++c) {
          sum[c] = bsum[k][std::size_t(c) * std::size_t(g.nbx) + std::size_t(bx)];
        }
        const std::uint32_t empty = n - sum[nplanes];
        for (int c = 0; c < 4; ++c) {
          const std::uint32_t v = c < nplanes ? sum[c] + empty * fill_c[k][c] : 255u * n;
          dst[k][c] = float(v) * inv;
        }
      }
    }
  }
}

}  // namespace

void dilation_endpoints(const EncoderState& s, std::vector<float>& low, std::vector<float>& high,
                        std::vector<std::uint8_t>* flat) {
  const Grid& g = s.g;
  low.assign(g.blocks() * 4, 0.0f);
  high.assign(g.blocks() * 4, 0.0f);
  if (flat != nullptr) flat->assign(g.blocks(), 0);
  std::uint8_t* const flat_out = flat != nullptr ? flat->data() : nullptr;
  // Bands of block rows: long enough that the 8-row halo is cheap (at most 1/8 of the work),
  // at least 4 per image for threads; one band (no inner halos) on one thread. Every band
  // computes its rows exactly, so the banding never changes the result.
  const bool serial = s.threads == 1 || default_thread_count() == 1;
  const int band = serial ? g.nby : std::clamp(g.nby / 4, 1, 32);
  const DilationKernels& kern =
      g_force_baseline.load(std::memory_order_relaxed) ? kBaseline : *native_kernels();
  parallel_for(0, g.nby, band,
               [&](std::int64_t by0, std::int64_t by1) {
                 // Alpha is 255 everywhere unless alpha_mode: three colour planes.
                 if (s.alpha_mode) {
                   dilate_band<4>(kern, s, int(by0), int(by1), low, high, flat_out);
                 } else {
                   dilate_band<3>(kern, s, int(by0), int(by1), low, high, flat_out);
                 }
               },
               {s.threads});
}

const DilationKernels* dilation_kernels_baseline() { return &kBaseline; }

bool avx2_kernels_usable() {
#if defined(TESSERA_HAVE_AVX2_KERNELS)
  return simd::cpu_has_avx2();
#else
  return false;
#endif
}

const DilationKernels* dilation_kernels_avx2() {
#if defined(TESSERA_HAVE_AVX2_KERNELS)
  static const DilationKernels* const k = []() -> const DilationKernels* {
    if (!avx2_kernels_usable()) return nullptr;
    static DilationKernels table;
    fill_dilation_kernels_avx2(&table);
    return &table;
  }();
  return k;
#else
  return nullptr;
#endif
}

void dilation_force_baseline(bool force) {
  g_force_baseline.store(force, std::memory_order_relaxed);
}

}  // namespace tessera::pvrtc::detail
