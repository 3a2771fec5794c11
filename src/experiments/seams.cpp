// The seam experiment of Toth 2013 (Table 1 and Figure 5): every sampling method at every MSAA
// rate along a camera orbit, timed side by side, compared against the Mitchell-Netravali-
// downsampled supersampled Traverse reference with the error CDF of metrics.h.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "seams_content.h"
#include "tessera/experiments.h"
#include "tessera/metrics.h"

namespace tessera::experiments {

namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// Counted pixels: the reference's (Mitchell-filtered) coverage exceeds 1 %: geometry only.
std::vector<std::uint8_t> geometry_mask(const ImageRGBAF& ref) {
  std::vector<std::uint8_t> m(ref.pixel_count());
  for (std::size_t i = 0; i < m.size(); ++i) m[i] = ref.pixels[i * 4 + 3] > 0.01f ? 1 : 0;
  return m;
}

ErrorStats stats(const ErrorCdfAccumulator& a) { return {a.fractions(), a.mean(), a.counted()}; }

std::uint64_t nan_pixels(const ImageRGBAF& img) {
  std::uint64_t n = 0;
  for (std::size_t i = 0; i < img.pixel_count(); ++i) {
    const float* p = &img.pixels[i * 4];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) ++n;
  }
  return n;
}

/// Geometry pixels (`geometry`) within `k` pixels (Chebyshev) of a covered pixel of another
/// face, from a face-id frame (R = face + 1, alpha = coverage; FaceRenderOptions::face_ids).
std::vector<std::uint8_t> near_seam_mask(const ImageRGBAF& ids,
                                         const std::vector<std::uint8_t>& geometry, int k) {
  const int w = ids.width, h = ids.height;
  auto id = [&](int x, int y) -> float {
    const float* p = ids.at(x, y);
    return p[3] > 0.5f ? p[0] : 0.0f;
  };
  std::vector<std::uint8_t> m(geometry.size(), 0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
      const float own = id(x, y);
      if (!geometry[i] || own == 0.0f) continue;
      bool near = false;
      for (int dy = -k; dy <= k && !near; ++dy) {
        for (int dx = -k; dx <= k && !near; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= w || yy >= h) continue;
          const float other = id(xx, yy);
          near = other != 0.0f && other != own;
        }
      }
      m[i] = near ? 1 : 0;
    }
  }
  return m;
}

/// Error accumulators of one rate, named as the result's fields.
struct RateAccumulators {
  std::array<ErrorCdfAccumulator, 4> vs_ref, vs_ref_char, vs_ref_near;
  ErrorCdfAccumulator traverse_vs_discard;
};

}  // namespace

Result<SeamsResult> run_seams(const SeamsConfig& c) {
  auto log = [&](const std::string& s) {
    if (c.progress) c.progress(s);
  };
  if (c.msaa.empty() || c.frames < 1 || c.width < 8 || c.height < 8 || c.reference_factor < 1 ||
      c.quality_frames < 0 || c.near_seam_pixels < 0) {
    return Status::error(ErrorCode::invalid_argument, "seams: bad configuration");
  }
  for (int r : c.msaa) {
    if (!raster::valid_msaa(r)) {
      return Status::error(ErrorCode::invalid_argument,
                           "seams: MSAA rate " + std::to_string(r) + " not in 1,2,4,8,16");
    }
  }
  if (c.backend != Backend::cpu) {
    return Status::error(ErrorCode::unsupported, std::string("seams: backend '") +
                                                     backend_name(c.backend) +
                                                     "' is not yet implemented for this "
                                                     "experiment (only 'cpu')");
  }
  const auto t_load = std::chrono::steady_clock::now();
  Result<detail::SeamsContent> loaded = detail::load_seams_content(c);
  if (!loaded) return loaded.status();
  const faces::FaceScene& scene = loaded->scene;
  const faces::FaceTextureSet& set = loaded->set;
  {
    char ms[32];
    std::snprintf(ms, sizeof ms, "%.0f", ms_since(t_load));
    log(loaded->description + ", built in " + ms + " ms");
  }
  Result<std::unique_ptr<faces::FaceRenderer>> renderer = faces::FaceRenderer::create(scene, set);
  if (!renderer) return renderer.status();
  if (c.on_ready) {
    if (Status s = c.on_ready(); !s.ok()) return s;
  }

  SeamsResult res;
  res.scene_description = loaded->description;
  res.faces = set.face_count();
  res.ground_faces = scene.ground_faces;
  res.texels_level0 = set.texel_count();
  res.edge_pairings = faces::edge_pairing_histogram(set.adjacency());
  res.linked_corners = set.linked_corner_count();
  // The character-only breakdown (Figure-1 scenes): curved geometry, where Traverse's
  // extrapolation is approximate.
  res.has_character = scene.ground_faces > 0 && scene.ground_faces < set.face_count();
  res.quality_frames = c.quality_frames > 0 ? std::min(c.quality_frames, c.frames) : c.frames;
  res.near_seam_pixels = c.near_seam_pixels;
  res.threads = c.threads > 0 ? c.threads : default_thread_count();
  for (int i = 0; i < kSeamsCdfBins; ++i) res.thresholds.push_back(double(i) * kSeamsCdfStep);

  const std::vector<faces::Method>& methods = faces::all_methods();
  const std::size_t nm = methods.size(), nr = c.msaa.size();
  res.rates.resize(nr);
  std::vector<RateAccumulators> acc(nr);
  for (std::size_t ri = 0; ri < nr; ++ri) {
    res.rates[ri].msaa = c.msaa[ri];
    for (std::size_t m = 0; m < nm; ++m) {
      res.rates[ri].method(methods[m]).method = methods[m];
      acc[ri].vs_ref[m] = ErrorCdfAccumulator(res.thresholds);
      acc[ri].vs_ref_char[m] = ErrorCdfAccumulator(res.thresholds);
      acc[ri].vs_ref_near[m] = ErrorCdfAccumulator(res.thresholds);
    }
    acc[ri].traverse_vs_discard = ErrorCdfAccumulator(res.thresholds);
  }
  // imgs[] and the accumulators follow the order of `methods`.
  const auto index_of = [&](faces::Method m) {
    return std::size_t(std::find(methods.begin(), methods.end(), m) - methods.begin());
  };
  const std::size_t traverse = index_of(faces::Method::traverse);
  const std::size_t discard = index_of(faces::Method::discard);

  faces::FaceRenderOptions o;
  o.width = c.width;
  o.height = c.height;
  o.threads = c.threads;
  o.sampling.filter = TextureFilter::anisotropic;
  o.sampling.max_aniso = 16;

  for (int f = 0; f < c.frames; ++f) {
    const scene::Camera cam = faces::face_orbit_camera(scene, f, c.frames);
    // Quality frames are spread evenly over the orbit (frame 0 always included).
    const int q = res.quality_frames;
    const bool quality = f == 0 || (f * q) / c.frames != ((f - 1) * q) / c.frames;
    ImageRGBAF ref;
    std::vector<std::uint8_t> mask, char_mask, near_mask;
    if (quality) {
      const auto t0 = std::chrono::steady_clock::now();
      Result<ImageRGBAF> r =
          (*renderer)->render_reference(cam, c.width, c.height, c.reference_factor, c.threads);
      if (!r) return r.status();
      res.reference_ms_total += ms_since(t0);
      ref = std::move(*r);
      mask = geometry_mask(ref);
      if (f == 0 && c.keep_images) res.reference_frame0 = ref;
      if (c.near_seam_pixels > 0) {
        faces::FaceRenderOptions io = o;
        io.msaa = 1;
        io.face_ids = true;
        Result<faces::FaceFrame> ids = (*renderer)->render(cam, io);
        if (!ids) return ids.status();
        near_mask = near_seam_mask(ids->image, mask, c.near_seam_pixels);
      }
      if (res.has_character) {
        faces::FaceRenderOptions mo = o;
        mo.msaa = 8;
        mo.shading_only = true;
        mo.mask_faces_from = scene.ground_faces;
        Result<faces::FaceFrame> mf = (*renderer)->render(cam, mo);
        if (!mf) return mf.status();
        char_mask.assign(mask.size(), 0);
        for (std::size_t i = 0; i < mask.size(); ++i) {
          char_mask[i] = mask[i] && mf->image.pixels[i * 4] >= 0.5f ? 1 : 0;
        }
      }
    }
    for (std::size_t ri = 0; ri < nr; ++ri) {
      SeamsRateResult& rate = res.rates[ri];
      o.msaa = c.msaa[ri];
      std::vector<ImageRGBAF> imgs(nm);
      // Alternate: the order of the variants (the methods, then shading only) rotates with the
      // frame.
      for (std::size_t k = 0; k <= nm; ++k) {
        const std::size_t v = (k + std::size_t(f)) % (nm + 1);
        o.shading_only = v == nm;
        o.sampling.method = v == nm ? faces::Method::clamp : methods[v];
        o.sampling.clamp_fallback = true;
        Result<faces::FaceFrame> fr = (*renderer)->render(cam, o);
        if (!fr) return fr.status();
        (v == nm ? rate.shading_only : rate.method(methods[v]).timing).frame_ms.push_back(fr->ms());
        if (v < nm) imgs[v] = std::move(fr->image);
      }
      if (quality) {
        for (std::size_t m = 0; m < nm; ++m) {
          if (Status s = acc[ri].vs_ref[m].add(imgs[m], ref, mask); !s.ok()) return s;
          if (res.has_character) {
            if (Status s = acc[ri].vs_ref_char[m].add(imgs[m], ref, char_mask); !s.ok()) return s;
          }
          if (!near_mask.empty()) {
            if (Status s = acc[ri].vs_ref_near[m].add(imgs[m], ref, near_mask); !s.ok()) return s;
          }
        }
        if (Status s = acc[ri].traverse_vs_discard.add(imgs[traverse], imgs[discard], mask);
            !s.ok()) {
          return s;
        }
      }
      if (f == 0) {
        // Discard without the zero-coverage fallback: count the NaN pixels it produces.
        o.shading_only = false;
        o.sampling.method = faces::Method::discard;
        o.sampling.clamp_fallback = false;
        Result<faces::FaceFrame> fr = (*renderer)->render(cam, o);
        if (!fr) return fr.status();
        rate.nan_pixels_without_fallback = nan_pixels(fr->image);
        if (c.keep_images) {
          for (std::size_t m = 0; m < nm; ++m) rate.method(methods[m]).frame0 = std::move(imgs[m]);
        }
      }
    }
    log("frame " + std::to_string(f + 1) + "/" + std::to_string(c.frames) + " done");
  }
  for (std::size_t ri = 0; ri < nr; ++ri) {
    for (std::size_t m = 0; m < nm; ++m) {
      SeamsMethodResult& mr = res.rates[ri].method(methods[m]);
      mr.vs_reference = stats(acc[ri].vs_ref[m]);
      if (res.has_character) {
        mr.vs_reference_character = stats(acc[ri].vs_ref_char[m]);
      }
      if (c.near_seam_pixels > 0) mr.vs_reference_near_seams = stats(acc[ri].vs_ref_near[m]);
    }
    res.rates[ri].traverse_vs_discard = stats(acc[ri].traverse_vs_discard);
  }
  return res;
}

}  // namespace tessera::experiments
