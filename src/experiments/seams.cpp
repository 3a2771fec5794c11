// The seam experiment of Toth 2013 (Table 1 and Figure 5): every sampling method at every MSAA
// rate along a camera orbit, timed side by side, compared against the Mitchell-Netravali-
// downsampled supersampled Traverse reference with the error CDF of metrics.h.
#include "tessera/experiments/seams.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "seams_content.h"
#include "tessera/metrics.h"

namespace tessera::experiments {

namespace {

/// Counted pixels: the reference's (Mitchell-filtered) coverage exceeds 1 %: geometry only.
std::vector<std::uint8_t> geometry_mask(const ImageRGBAF& ref) {
  std::vector<std::uint8_t> m(ref.pixel_count());
  for (std::size_t i = 0; i < m.size(); ++i) m[i] = ref.pixels[i * 4 + 3] > 0.01f ? 1 : 0;
  return m;
}

ErrorStats stats(const metrics::ErrorCdfAccumulator& a) {
  return {a.fractions(), a.mean(), a.counted()};
}

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
  std::array<metrics::ErrorCdfAccumulator, 4> vs_ref, vs_ref_char, vs_ref_near;
  metrics::ErrorCdfAccumulator traverse_vs_discard;
};

/// GL against CPU, pooled over the quality frames and of the worst frame (SeamsGlMethodResult).
struct Agreement {
  double sse = 0;  ///< Sum over frames of the 8-bit RGB MSE times the pixel count.
  std::uint64_t pixels = 0, over = 0;
  double worst_psnr = std::numeric_limits<double>::infinity(), worst_fraction = 0;
  Status add(const ImageRGBAF& gl, const ImageRGBAF& cpu, int threads) {
    Result<metrics::ImageComparison> c = metrics::compare_images(
        to_srgb8(gl, {threads}), to_srgb8(cpu, {threads}), metrics::CompareOptions{false, threads});
    if (!c) return c.status();
    Result<std::vector<float>> n = metrics::error_norms(gl, cpu);
    if (!n) return n.status();
    std::uint64_t frame_over = 0;
    for (float e : *n) frame_over += !(e < 0.01f);  // NaN counts as different
    over += frame_over;
    sse += c->mse_rgb * double(n->size());
    pixels += n->size();
    worst_psnr = std::min(worst_psnr, metrics::psnr_from_mse(c->mse_rgb));
    worst_fraction =
        std::max(worst_fraction, n->empty() ? 0.0 : double(frame_over) / double(n->size()));
    return Status::success();
  }
  double psnr() const { return metrics::psnr_from_mse(pixels ? sse / double(pixels) : 0.0); }
  double fraction() const { return pixels ? double(over) / double(pixels) : 0.0; }
};

std::string rates_text(const std::vector<int>& rates) {
  std::string t;
  for (int r : rates) t += (t.empty() ? "" : ", ") + std::to_string(r) + "x";
  return t;
}

}  // namespace

SeamsGlComparison seams_gl_comparison(const SeamsSamplePattern& pattern) {
  if (pattern.cpu_msaa > 0) return SeamsGlComparison::cpu_rate;
  // The CPU can draw at the positions only when every sample has one inside the pixel on the
  // 1/16 grid (raster::FrameBufferDesc::sample_pattern); anything less would not be like for
  // like, so such a rate is better left uncompared than compared with the wrong frame.
  const std::vector<raster::SampleOffset>& p = pattern.positions;
  bool ok = !p.empty() && p.size() == std::size_t(pattern.samples) &&
            p.size() <= std::size_t(raster::kMaxSamples);
  for (const raster::SampleOffset& s : p) {
    ok = ok && s.x >= -8 && s.x <= 7 && s.y >= -8 && s.y <= 7;
  }
  return ok ? SeamsGlComparison::driver_positions : SeamsGlComparison::none;
}

Result<SeamsResult> run_seams(const SeamsConfig& c) {
  auto log = [&](const std::string& s) {
    if (c.progress) c.progress(s);
  };
  if (c.msaa.empty() || c.frames < 1 || c.width < 8 || c.height < 8 || c.reference_factor < 1 ||
      c.quality_frames < 0 || c.near_seam_pixels < 0 || c.repetitions < 1) {
    return Status::error(ErrorCode::invalid_argument, "seams: bad configuration");
  }
  if ((!c.time_cpu || c.compare_references) && c.backend != Backend::both) {
    return Status::error(ErrorCode::invalid_argument,
                         "seams: time_cpu = false and compare_references need backend 'both'");
  }
  for (int r : c.msaa) {
    if (!raster::valid_msaa(r)) {
      return Status::error(ErrorCode::invalid_argument,
                           "seams: MSAA rate " + std::to_string(r) + " not in 1,2,4,8,16");
    }
  }
  const bool use_gl = uses_gl(c.backend);
  const bool compare_gl = c.backend == Backend::both;
  if (use_gl && !c.gl_factory) {
    return Status::error(ErrorCode::unsupported, std::string("seams: backend '") +
                                                     backend_name(c.backend) +
                                                     "': not built with the OpenGL runtime");
  }
  const auto t_load = std::chrono::steady_clock::now();
  Result<detail::SeamsContent> loaded = detail::load_seams_content(c);
  if (!loaded) return loaded.status();
  const faces::FaceScene& scene = loaded->scene;
  const faces::FaceTextureSet& set = loaded->set;
  char load_ms[32];
  std::snprintf(load_ms, sizeof load_ms, "%.0f", ms_since(t_load));
  // The CPU renderer draws the face ids and the character mask whatever the backend (the
  // geometry is the same on GL); `primary` renders `rates`, `gl_side` the GL frames of both.
  Result<std::unique_ptr<faces::FaceRenderer>> renderer = faces::FaceRenderer::create(scene, set);
  if (!renderer) return renderer.status();
  std::unique_ptr<SeamsBackend> gl;
  if (use_gl) {
    Result<std::unique_ptr<SeamsBackend>> made = c.gl_factory->create_seams(scene, set);
    if (!made) return made.status();
    if (!*made) {
      return Status::error(ErrorCode::unsupported, "seams: the GL renderer factory made nothing");
    }
    gl = std::move(*made);
  }
  std::unique_ptr<SeamsBackend> cpu;
  if (c.backend != Backend::gl) {
    Result<std::unique_ptr<SeamsBackend>> made = create_cpu_seams_backend(scene, set);
    if (!made) return made.status();
    cpu = std::move(*made);
  }
  SeamsBackend& primary = cpu ? *cpu : *gl;
  SeamsBackend* gl_side = compare_gl ? gl.get() : nullptr;

  SeamsResult res;
  res.backend = c.backend;
  std::vector<int> rates = c.msaa;  // those `primary` renders
  std::vector<bool> gl_rate(c.msaa.size(), false);
  if (gl) {
    res.gl_renderer = gl->device_name();
    res.gl_version = gl->device_version();
    if (c.backend == Backend::gl) rates.clear();
    for (std::size_t i = 0; i < c.msaa.size(); ++i) {
      const int r = c.msaa[i];
      gl_rate[i] = gl->msaa_supported(r);
      if (!gl_rate[i]) {
        if (std::find(res.msaa_unsupported.begin(), res.msaa_unsupported.end(), r) ==
            res.msaa_unsupported.end()) {
          res.msaa_unsupported.push_back(r);
        }
      } else {
        res.gl_sample_patterns.push_back(gl->sample_pattern(r));
        if (c.backend == Backend::gl) rates.push_back(r);
      }
    }
    if (rates.empty() || (compare_gl && std::count(gl_rate.begin(), gl_rate.end(), true) == 0)) {
      return Status::error(ErrorCode::unsupported, "seams: the OpenGL driver (" + res.gl_renderer +
                                                       ") refuses every MSAA rate asked for (" +
                                                       rates_text(res.msaa_unsupported) + ")");
    }
  }
  // Logged once every renderer exists, so that a failing GL start is the only line.
  log(loaded->description + ", built in " + load_ms + " ms");
  if (c.on_ready) {
    if (Status s = c.on_ready(); !s.ok()) return s;
  }
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

  const std::vector<faces::SeamMethod>& methods = faces::all_methods();
  const std::size_t nm = methods.size(), nr = rates.size();
  res.rates.resize(nr);
  std::vector<RateAccumulators> acc(nr);
  // both: gl_index[ri] = the rate's entry in res.gl_rates, or -1 where GL refuses it.
  std::vector<int> gl_index(nr, -1);
  std::vector<std::array<Agreement, 4>> agree;
  std::vector<SeamsSamplePattern> gl_patterns;  // per entry of res.gl_rates
  if (gl_side) {
    for (std::size_t ri = 0; ri < nr; ++ri) {
      if (!gl_rate[ri]) continue;
      gl_index[ri] = int(res.gl_rates.size());
      SeamsGlRateResult g;
      g.msaa = rates[ri];
      gl_patterns.push_back(gl_side->sample_pattern(rates[ri]));
      g.compared_with = seams_gl_comparison(gl_patterns.back());
      for (std::size_t m = 0; m < nm; ++m) g.methods[std::size_t(methods[m])].method = methods[m];
      res.gl_rates.push_back(g);
    }
    agree.resize(res.gl_rates.size());
  }
  for (std::size_t ri = 0; ri < nr; ++ri) {
    res.rates[ri].msaa = rates[ri];
    for (std::size_t m = 0; m < nm; ++m) {
      res.rates[ri].method(methods[m]).method = methods[m];
      acc[ri].vs_ref[m] = metrics::ErrorCdfAccumulator(res.thresholds);
      acc[ri].vs_ref_char[m] = metrics::ErrorCdfAccumulator(res.thresholds);
      acc[ri].vs_ref_near[m] = metrics::ErrorCdfAccumulator(res.thresholds);
    }
    acc[ri].traverse_vs_discard = metrics::ErrorCdfAccumulator(res.thresholds);
  }
  // imgs[] and the accumulators follow the order of `methods`.
  const auto index_of = [&](faces::SeamMethod m) {
    return std::size_t(std::find(methods.begin(), methods.end(), m) - methods.begin());
  };
  const std::size_t traverse = index_of(faces::SeamMethod::traverse);
  const std::size_t discard = index_of(faces::SeamMethod::discard);

  faces::FaceRenderOptions o;  // the CPU's face-id and mask frames
  o.width = c.width;
  o.height = c.height;
  o.threads = c.threads;
  o.sampling.filter = texture::TextureFilter::anisotropic;
  o.sampling.max_aniso = 16;
  FaceFrameOptions fo;  // the frames of the experiment
  fo.width = c.width;
  fo.height = c.height;
  fo.threads = c.threads;
  fo.filter = c.filter;
  fo.max_aniso = 16;
  // Variants timed side by side: the methods, then shading only where the backend has it (and
  // times it: not on an untimed CPU side).
  const std::size_t nv = nm + (primary.has_shading_only() && c.time_cpu ? 1 : 0);
  Agreement ref_agree;
  // GL compiles a program per variant on first use and sizes its targets per rate: draw every
  // variant once (untimed) so that no timed frame pays for it. The CPU needs no warm-up.
  if (gl) {
    const scene::Camera cam = faces::face_orbit_camera(scene, 0, c.frames);
    FaceFrameOptions wo = fo;
    wo.keep_image = false;
    for (std::size_t ri = 0; ri < nr; ++ri) {
      if (compare_gl && gl_index[ri] < 0) continue;
      wo.msaa = rates[ri];
      for (faces::SeamMethod m : methods) {
        for (bool fallback : {true, false}) {
          if (!fallback && (m != faces::SeamMethod::discard || compare_gl)) continue;
          wo.method = m;
          wo.clamp_fallback = fallback;
          if (Result<SeamsBackendFrame> fr = gl->render(cam, wo); !fr) return fr.status();
        }
      }
    }
  }

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
          primary.render_reference(cam, c.width, c.height,
                                   {.factor = c.reference_factor, .threads = c.threads});
      if (!r) return r.status();
      res.reference_ms_total += ms_since(t0);
      ref = std::move(*r);
      mask = geometry_mask(ref);
      if (f == 0 && c.keep_images) res.reference_frame0 = ref;
      if (c.compare_references) {
        Result<ImageRGBAF> g = gl_side->render_reference(
            cam, c.width, c.height, {.factor = c.reference_factor, .threads = c.threads});
        if (!g) return g.status();
        if (Status s = ref_agree.add(*g, ref, c.threads); !s.ok()) return s;
      }
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
      fo.msaa = rates[ri];
      std::vector<ImageRGBAF> imgs(nm);
      // Alternate: the order of the variants (the methods, then shading only) rotates with the
      // frame and the repetition. An untimed CPU side renders the quality frames once.
      const int primary_reps = c.time_cpu ? c.repetitions : quality ? 1 : 0;
      for (int rep = 0; rep < primary_reps; ++rep) {
        fo.keep_image = quality && rep == 0;  // frame 0 is always a quality frame
        for (std::size_t k = 0; k < nv; ++k) {
          const std::size_t v = (k + std::size_t(f) + std::size_t(rep)) % nv;
          fo.shading_only = v == nm;
          fo.method = v == nm ? faces::SeamMethod::clamp : methods[v];
          fo.clamp_fallback = true;
          Result<SeamsBackendFrame> fr = primary.render(cam, fo);
          if (!fr) return fr.status();
          if (v == nm) {
            rate.shading_only.frame_ms.push_back(fr->ms);
            continue;
          }
          if (c.time_cpu) {
            rate.method(methods[v]).timing.frame_ms.push_back(fr->ms);
            if (primary.backend() != Backend::cpu) {
              rate.method(methods[v]).wall.frame_ms.push_back(fr->wall_ms);
            }
          }
          if (rep == 0) imgs[v] = std::move(fr->image);
        }
      }
      if (gl_side && gl_index[ri] >= 0) {
        // The same frame by GL, methods rotating likewise; read back on quality frames only.
        SeamsGlRateResult& g = res.gl_rates[std::size_t(gl_index[ri])];
        FaceFrameOptions go = fo;
        go.shading_only = false;
        for (std::size_t n = 0; n < nm * std::size_t(c.repetitions); ++n) {
          const std::size_t rep = n / nm, v = (n % nm + std::size_t(f) + rep) % nm;
          go.method = methods[v];
          go.keep_image = quality && rep == 0;
          Result<SeamsBackendFrame> fr = gl_side->render(cam, go);
          if (!fr) return fr.status();
          SeamsGlMethodResult& gm = g.methods[std::size_t(methods[v])];
          gm.gpu.frame_ms.push_back(fr->ms);
          gm.wall.frame_ms.push_back(fr->wall_ms);
          const SeamsSamplePattern& pattern = gl_patterns[std::size_t(gl_index[ri])];
          if (go.keep_image && g.compared_with != SeamsGlComparison::none) {
            Agreement& a = agree[std::size_t(gl_index[ri])][std::size_t(methods[v])];
            const bool driver = g.compared_with == SeamsGlComparison::driver_positions;
            if (driver || pattern.cpu_msaa != rates[ri]) {
              // The driver draws this rate with the samples of another CPU rate (llvmpipe: 2x
              // with its 4x samples), or at positions no CPU rate has: compare like for like,
              // with the CPU frame at that rate, or drawn at the driver's own positions.
              FaceFrameOptions co = go;
              co.msaa = driver ? int(pattern.positions.size()) : pattern.cpu_msaa;
              if (driver) co.sample_pattern = pattern.positions;
              co.keep_image = true;
              Result<SeamsBackendFrame> cf = primary.render(cam, co);
              if (!cf) return cf.status();
              if (Status s = a.add(fr->image, cf->image, c.threads); !s.ok()) return s;
            } else if (Status s = a.add(fr->image, imgs[v], c.threads); !s.ok()) {
              return s;
            }
          }
        }
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
        fo.shading_only = false;
        fo.keep_image = true;
        fo.method = faces::SeamMethod::discard;
        fo.clamp_fallback = false;
        Result<SeamsBackendFrame> fr = primary.render(cam, fo);
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
  for (std::size_t gi = 0; gi < agree.size(); ++gi) {
    // An uncompared rate has no agreement: NaN, not the "identical" of an empty pool.
    const bool compared = res.gl_rates[gi].compared_with != SeamsGlComparison::none;
    for (faces::SeamMethod m : methods) {
      SeamsGlMethodResult& gm = res.gl_rates[gi].methods[std::size_t(m)];
      gm.psnr_db = compared ? agree[gi][std::size_t(m)].psnr() : std::nan("");
      gm.fraction_ge_001 = compared ? agree[gi][std::size_t(m)].fraction() : std::nan("");
      gm.worst_psnr_db = compared ? agree[gi][std::size_t(m)].worst_psnr : std::nan("");
      gm.worst_fraction_ge_001 = compared ? agree[gi][std::size_t(m)].worst_fraction : std::nan("");
    }
  }
  if (c.compare_references) {
    res.gl_reference_vs_cpu = {true, ref_agree.psnr(), ref_agree.fraction(), ref_agree.worst_psnr,
                               ref_agree.worst_fraction};
  }
  return res;
}

}  // namespace tessera::experiments
