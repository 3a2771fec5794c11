// The seam experiment of Toth 2013 (Table 1 and Figure 5): every sampling method at every MSAA
// rate along a camera orbit, timed side by side, compared against the Mitchell-Netravali-
// downsampled supersampled Traverse reference with the error CDF of metrics.h.
#include "tessera/experiments/seams.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>

#include "gpu_factory.h"
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

namespace {

/// The configuration errors run_seams reports before anything is loaded.
Status check_config(const SeamsConfig& c) {
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
  return detail::gpu_factory("seams", c.backend, c.gl_factory, c.vk_factory).status();
}

/// What a quality frame is measured with: the reference and the masks of the counted pixels.
struct QualityFrame {
  ImageRGBAF ref;
  std::vector<std::uint8_t> mask, char_mask, near_mask;
};

/// One run of the experiment: the steps of run_seams and the state they share.
class SeamsRun {
 public:
  explicit SeamsRun(const SeamsConfig& c) : c_(c) {}

  /// Loads the content and makes the renderers and backends; the rates each backend draws.
  Status make_backends();
  /// Logs the scene, calls on_ready, fills the result's fixed fields and the accumulators.
  Status start();
  /// Draws every GL variant once, untimed, so that no timed frame compiles or allocates.
  Status warm_up();
  /// Frame `f` of the orbit at every rate: timed, and measured on quality frames.
  Status frame(int f);
  /// The pooled errors and agreements into the result.
  SeamsResult finish();

 private:
  void log(const std::string& s) const {
    if (c_.progress) c_.progress(s);
  }
  Status quality_inputs(const scene::Camera& cam, int f, QualityFrame& q);
  Status render_rate(std::size_t ri, int f, const scene::Camera& cam, bool quality,
                     const QualityFrame& q);
  Status render_gl_rate(std::size_t ri, int f, const scene::Camera& cam, bool quality,
                        const std::vector<ImageRGBAF>& imgs);
  Status accumulate(std::size_t ri, const std::vector<ImageRGBAF>& imgs, const QualityFrame& q);

  const SeamsConfig& c_;
  std::optional<detail::SeamsContent> loaded_;
  std::string load_ms_;
  // The CPU renderer draws the face ids and the character mask whatever the backend (the
  // geometry is the same on GL); `primary_` renders `rates_`, `gl_side_` the GL frames of both.
  std::unique_ptr<faces::FaceRenderer> renderer_;
  std::unique_ptr<SeamsBackend> gl_, cpu_;
  SeamsBackend* primary_ = nullptr;
  SeamsBackend* gl_side_ = nullptr;
  bool compare_gl_ = false;

  SeamsResult res_;
  std::vector<int> rates_;     // those `primary_` renders
  std::vector<bool> gl_rate_;  // per entry of c.msaa: GL draws it
  const std::vector<faces::SeamMethod>& methods_ = faces::all_methods();
  std::size_t nm_ = 0, nr_ = 0, nv_ = 0, traverse_ = 0, discard_ = 0;
  std::vector<RateAccumulators> acc_;
  // both: gl_index_[ri] = the rate's entry in res.gl_rates, or -1 where GL refuses it.
  std::vector<int> gl_index_;
  std::vector<std::array<Agreement, 4>> agree_;
  std::vector<SeamsSamplePattern> gl_patterns_;  // per entry of res.gl_rates
  Agreement ref_agree_;
  faces::FaceRenderOptions o_;  // the CPU's face-id and mask frames
  FaceFrameOptions fo_;         // the frames of the experiment (kept from frame to frame)
};

Status SeamsRun::make_backends() {
  const auto t_load = std::chrono::steady_clock::now();
  Result<detail::SeamsContent> loaded = detail::load_seams_content(c_);
  if (!loaded) return loaded.status();
  loaded_ = std::move(*loaded);
  const faces::FaceScene& scene = loaded_->scene;
  const faces::FaceTextureSet& set = loaded_->set;
  char load_ms[32];
  std::snprintf(load_ms, sizeof load_ms, "%.0f", ms_since(t_load));
  load_ms_ = load_ms;
  Result<std::unique_ptr<faces::FaceRenderer>> renderer = faces::FaceRenderer::create(scene, set);
  if (!renderer) return renderer.status();
  renderer_ = std::move(*renderer);
  const GpuBackendFactory* factory =
      *detail::gpu_factory("seams", c_.backend, c_.gl_factory, c_.vk_factory);
  if (factory != nullptr) {
    Result<std::unique_ptr<SeamsBackend>> made = factory->create_seams(scene, set);
    if (!made) return made.status();
    if (!*made) {
      return Status::error(ErrorCode::unsupported, "seams: the GPU renderer factory made nothing");
    }
    gl_ = std::move(*made);
  }
  if (uses_cpu(c_.backend)) {
    Result<std::unique_ptr<SeamsBackend>> made = create_cpu_seams_backend(scene, set);
    if (!made) return made.status();
    cpu_ = std::move(*made);
  }
  compare_gl_ = c_.backend == Backend::both;
  primary_ = cpu_ ? cpu_.get() : gl_.get();
  gl_side_ = compare_gl_ ? gl_.get() : nullptr;

  res_.backend = c_.backend;
  rates_ = c_.msaa;
  gl_rate_.assign(c_.msaa.size(), false);
  if (gl_) {
    res_.gpu_renderer = gl_->device_name();
    res_.gpu_version = gl_->device_version();
    if (gpu_primary(c_.backend)) rates_.clear();
    for (std::size_t i = 0; i < c_.msaa.size(); ++i) {
      const int r = c_.msaa[i];
      gl_rate_[i] = gl_->msaa_supported(r);
      if (!gl_rate_[i]) {
        if (std::find(res_.msaa_unsupported.begin(), res_.msaa_unsupported.end(), r) ==
            res_.msaa_unsupported.end()) {
          res_.msaa_unsupported.push_back(r);
        }
      } else {
        res_.gpu_sample_patterns.push_back(gl_->sample_pattern(r));
        if (gpu_primary(c_.backend)) rates_.push_back(r);
      }
    }
    if (rates_.empty() ||
        (compare_gl_ && std::count(gl_rate_.begin(), gl_rate_.end(), true) == 0)) {
      return Status::error(ErrorCode::unsupported, "seams: the GPU driver (" + res_.gpu_renderer +
                                                       ") refuses every MSAA rate asked for (" +
                                                       rates_text(res_.msaa_unsupported) + ")");
    }
  }
  return Status::success();
}

Status SeamsRun::start() {
  const faces::FaceScene& scene = loaded_->scene;
  const faces::FaceTextureSet& set = loaded_->set;
  // Logged once every renderer exists, so that a failing GL start is the only line.
  log(loaded_->description + ", built in " + load_ms_ + " ms");
  if (c_.on_ready) {
    if (Status s = c_.on_ready(); !s.ok()) return s;
  }
  res_.scene_description = loaded_->description;
  res_.faces = set.face_count();
  res_.ground_faces = scene.ground_faces;
  res_.texels_level0 = set.texel_count();
  res_.edge_pairings = faces::edge_pairing_histogram(set.adjacency());
  res_.linked_corners = set.linked_corner_count();
  // The character-only breakdown (Figure-1 scenes): curved geometry, where Traverse's
  // extrapolation is approximate.
  res_.has_character = scene.ground_faces > 0 && scene.ground_faces < set.face_count();
  res_.quality_frames = c_.quality_frames > 0 ? std::min(c_.quality_frames, c_.frames) : c_.frames;
  res_.near_seam_pixels = c_.near_seam_pixels;
  res_.threads = c_.threads > 0 ? c_.threads : default_thread_count();
  for (int i = 0; i < kSeamsCdfBins; ++i) res_.thresholds.push_back(double(i) * kSeamsCdfStep);

  nm_ = methods_.size();
  nr_ = rates_.size();
  res_.rates.resize(nr_);
  acc_.resize(nr_);
  gl_index_.assign(nr_, -1);
  if (gl_side_) {
    for (std::size_t ri = 0; ri < nr_; ++ri) {
      if (!gl_rate_[ri]) continue;
      gl_index_[ri] = int(res_.gl_rates.size());
      SeamsGlRateResult g;
      g.msaa = rates_[ri];
      gl_patterns_.push_back(gl_side_->sample_pattern(rates_[ri]));
      g.compared_with = seams_gl_comparison(gl_patterns_.back());
      for (std::size_t m = 0; m < nm_; ++m) {
        g.methods[std::size_t(methods_[m])].method = methods_[m];
      }
      res_.gl_rates.push_back(g);
    }
    agree_.resize(res_.gl_rates.size());
  }
  for (std::size_t ri = 0; ri < nr_; ++ri) {
    res_.rates[ri].msaa = rates_[ri];
    for (std::size_t m = 0; m < nm_; ++m) {
      res_.rates[ri].method(methods_[m]).method = methods_[m];
      acc_[ri].vs_ref[m] = metrics::ErrorCdfAccumulator(res_.thresholds);
      acc_[ri].vs_ref_char[m] = metrics::ErrorCdfAccumulator(res_.thresholds);
      acc_[ri].vs_ref_near[m] = metrics::ErrorCdfAccumulator(res_.thresholds);
    }
    acc_[ri].traverse_vs_discard = metrics::ErrorCdfAccumulator(res_.thresholds);
  }
  // imgs[] and the accumulators follow the order of `methods_`.
  const auto index_of = [&](faces::SeamMethod m) {
    return std::size_t(std::find(methods_.begin(), methods_.end(), m) - methods_.begin());
  };
  traverse_ = index_of(faces::SeamMethod::traverse);
  discard_ = index_of(faces::SeamMethod::discard);

  o_.width = c_.width;
  o_.height = c_.height;
  o_.threads = c_.threads;
  o_.sampling.filter = texture::TextureFilter::anisotropic;
  o_.sampling.max_aniso = 16;
  fo_.width = c_.width;
  fo_.height = c_.height;
  fo_.threads = c_.threads;
  fo_.filter = c_.filter;
  fo_.max_aniso = 16;
  // Variants timed side by side: the methods, then shading only where the backend has it (and
  // times it: not on an untimed CPU side).
  nv_ = nm_ + (primary_->has_shading_only() && c_.time_cpu ? 1 : 0);
  return Status::success();
}

Status SeamsRun::warm_up() {
  // GL compiles a program per variant on first use and sizes its targets per rate: draw every
  // variant once (untimed) so that no timed frame pays for it. The CPU needs no warm-up.
  if (!gl_) return Status::success();
  const scene::Camera cam = faces::face_orbit_camera(loaded_->scene, 0, c_.frames);
  FaceFrameOptions wo = fo_;
  wo.keep_image = false;
  for (std::size_t ri = 0; ri < nr_; ++ri) {
    if (compare_gl_ && gl_index_[ri] < 0) continue;
    wo.msaa = rates_[ri];
    for (faces::SeamMethod m : methods_) {
      for (bool fallback : {true, false}) {
        if (!fallback && (m != faces::SeamMethod::discard || compare_gl_)) continue;
        wo.method = m;
        wo.clamp_fallback = fallback;
        if (Result<SeamsBackendFrame> fr = gl_->render(cam, wo); !fr) return fr.status();
      }
    }
  }
  return Status::success();
}

Status SeamsRun::quality_inputs(const scene::Camera& cam, int f, QualityFrame& q) {
  const auto t0 = std::chrono::steady_clock::now();
  Result<ImageRGBAF> r = primary_->render_reference(
      cam, c_.width, c_.height, {.factor = c_.reference_factor, .threads = c_.threads});
  if (!r) return r.status();
  res_.reference_ms_total += ms_since(t0);
  q.ref = std::move(*r);
  q.mask = geometry_mask(q.ref);
  if (f == 0 && c_.keep_images) res_.reference_frame0 = q.ref;
  if (c_.compare_references) {
    Result<ImageRGBAF> g = gl_side_->render_reference(
        cam, c_.width, c_.height, {.factor = c_.reference_factor, .threads = c_.threads});
    if (!g) return g.status();
    if (Status s = ref_agree_.add(*g, q.ref, c_.threads); !s.ok()) return s;
  }
  if (c_.near_seam_pixels > 0) {
    faces::FaceRenderOptions io = o_;
    io.msaa = 1;
    io.face_ids = true;
    Result<faces::FaceFrame> ids = renderer_->render(cam, io);
    if (!ids) return ids.status();
    q.near_mask = near_seam_mask(ids->image, q.mask, c_.near_seam_pixels);
  }
  if (res_.has_character) {
    faces::FaceRenderOptions mo = o_;
    mo.msaa = 8;
    mo.shading_only = true;
    mo.mask_faces_from = loaded_->scene.ground_faces;
    Result<faces::FaceFrame> mf = renderer_->render(cam, mo);
    if (!mf) return mf.status();
    q.char_mask.assign(q.mask.size(), 0);
    for (std::size_t i = 0; i < q.mask.size(); ++i) {
      q.char_mask[i] = q.mask[i] && mf->image.pixels[i * 4] >= 0.5f ? 1 : 0;
    }
  }
  return Status::success();
}

Status SeamsRun::frame(int f) {
  const scene::Camera cam = faces::face_orbit_camera(loaded_->scene, f, c_.frames);
  // Quality frames are spread evenly over the orbit (frame 0 always included).
  const int q = res_.quality_frames;
  const bool quality = f == 0 || (f * q) / c_.frames != ((f - 1) * q) / c_.frames;
  QualityFrame inputs;
  if (quality) {
    if (Status s = quality_inputs(cam, f, inputs); !s.ok()) return s;
  }
  for (std::size_t ri = 0; ri < nr_; ++ri) {
    if (Status s = render_rate(ri, f, cam, quality, inputs); !s.ok()) return s;
  }
  log("frame " + std::to_string(f + 1) + "/" + std::to_string(c_.frames) + " done");
  return Status::success();
}

Status SeamsRun::render_rate(std::size_t ri, int f, const scene::Camera& cam, bool quality,
                             const QualityFrame& q) {
  SeamsRateResult& rate = res_.rates[ri];
  fo_.msaa = rates_[ri];
  std::vector<ImageRGBAF> imgs(nm_);
  // Alternate: the order of the variants (the methods, then shading only) rotates with the
  // frame and the repetition. An untimed CPU side renders the quality frames once.
  const int primary_reps = c_.time_cpu ? c_.repetitions : quality ? 1 : 0;
  for (int rep = 0; rep < primary_reps; ++rep) {
    fo_.keep_image = quality && rep == 0;  // frame 0 is always a quality frame
    for (std::size_t k = 0; k < nv_; ++k) {
      const std::size_t v = (k + std::size_t(f) + std::size_t(rep)) % nv_;
      fo_.shading_only = v == nm_;
      fo_.method = v == nm_ ? faces::SeamMethod::clamp : methods_[v];
      fo_.clamp_fallback = true;
      Result<SeamsBackendFrame> fr = primary_->render(cam, fo_);
      if (!fr) return fr.status();
      if (v == nm_) {
        rate.shading_only.frame_ms.push_back(fr->ms);
        continue;
      }
      if (c_.time_cpu) {
        rate.method(methods_[v]).timing.frame_ms.push_back(fr->ms);
        if (primary_->backend() != Backend::cpu) {
          rate.method(methods_[v]).wall.frame_ms.push_back(fr->wall_ms);
        }
      }
      if (rep == 0) imgs[v] = std::move(fr->image);
    }
  }
  if (gl_side_ && gl_index_[ri] >= 0) {
    if (Status s = render_gl_rate(ri, f, cam, quality, imgs); !s.ok()) return s;
  }
  if (quality) {
    if (Status s = accumulate(ri, imgs, q); !s.ok()) return s;
  }
  if (f == 0) {
    // Discard without the zero-coverage fallback: count the NaN pixels it produces.
    fo_.shading_only = false;
    fo_.keep_image = true;
    fo_.method = faces::SeamMethod::discard;
    fo_.clamp_fallback = false;
    Result<SeamsBackendFrame> fr = primary_->render(cam, fo_);
    if (!fr) return fr.status();
    rate.nan_pixels_without_fallback = nan_pixels(fr->image);
    if (c_.keep_images) {
      for (std::size_t m = 0; m < nm_; ++m) rate.method(methods_[m]).frame0 = std::move(imgs[m]);
    }
  }
  return Status::success();
}

Status SeamsRun::render_gl_rate(std::size_t ri, int f, const scene::Camera& cam, bool quality,
                                const std::vector<ImageRGBAF>& imgs) {
  // The same frame by GL, methods rotating likewise; read back on quality frames only.
  const std::size_t gi = std::size_t(gl_index_[ri]);
  SeamsGlRateResult& g = res_.gl_rates[gi];
  FaceFrameOptions go = fo_;
  go.shading_only = false;
  for (std::size_t n = 0; n < nm_ * std::size_t(c_.repetitions); ++n) {
    const std::size_t rep = n / nm_, v = (n % nm_ + std::size_t(f) + rep) % nm_;
    go.method = methods_[v];
    go.keep_image = quality && rep == 0;
    Result<SeamsBackendFrame> fr = gl_side_->render(cam, go);
    if (!fr) return fr.status();
    SeamsGlMethodResult& gm = g.methods[std::size_t(methods_[v])];
    gm.gpu.frame_ms.push_back(fr->ms);
    gm.wall.frame_ms.push_back(fr->wall_ms);
    const SeamsSamplePattern& pattern = gl_patterns_[gi];
    if (!go.keep_image || g.compared_with == SeamsGlComparison::none) continue;
    Agreement& a = agree_[gi][std::size_t(methods_[v])];
    const bool driver = g.compared_with == SeamsGlComparison::driver_positions;
    if (driver || pattern.cpu_msaa != rates_[ri]) {
      // The driver draws this rate with the samples of another CPU rate (llvmpipe: 2x
      // with its 4x samples), or at positions no CPU rate has: compare like for like,
      // with the CPU frame at that rate, or drawn at the driver's own positions.
      FaceFrameOptions co = go;
      co.msaa = driver ? int(pattern.positions.size()) : pattern.cpu_msaa;
      if (driver) co.sample_pattern = pattern.positions;
      co.keep_image = true;
      Result<SeamsBackendFrame> cf = primary_->render(cam, co);
      if (!cf) return cf.status();
      if (Status s = a.add(fr->image, cf->image, c_.threads); !s.ok()) return s;
    } else if (Status s = a.add(fr->image, imgs[v], c_.threads); !s.ok()) {
      return s;
    }
  }
  return Status::success();
}

Status SeamsRun::accumulate(std::size_t ri, const std::vector<ImageRGBAF>& imgs,
                            const QualityFrame& q) {
  RateAccumulators& a = acc_[ri];
  for (std::size_t m = 0; m < nm_; ++m) {
    if (Status s = a.vs_ref[m].add(imgs[m], q.ref, q.mask); !s.ok()) return s;
    if (res_.has_character) {
      if (Status s = a.vs_ref_char[m].add(imgs[m], q.ref, q.char_mask); !s.ok()) return s;
    }
    if (!q.near_mask.empty()) {
      if (Status s = a.vs_ref_near[m].add(imgs[m], q.ref, q.near_mask); !s.ok()) return s;
    }
  }
  return a.traverse_vs_discard.add(imgs[traverse_], imgs[discard_], q.mask);
}

SeamsResult SeamsRun::finish() {
  for (std::size_t ri = 0; ri < nr_; ++ri) {
    for (std::size_t m = 0; m < nm_; ++m) {
      SeamsMethodResult& mr = res_.rates[ri].method(methods_[m]);
      mr.vs_reference = stats(acc_[ri].vs_ref[m]);
      if (res_.has_character) {
        mr.vs_reference_character = stats(acc_[ri].vs_ref_char[m]);
      }
      if (c_.near_seam_pixels > 0) mr.vs_reference_near_seams = stats(acc_[ri].vs_ref_near[m]);
    }
    res_.rates[ri].traverse_vs_discard = stats(acc_[ri].traverse_vs_discard);
  }
  for (std::size_t gi = 0; gi < agree_.size(); ++gi) {
    // An uncompared rate has no agreement: NaN, not the "identical" of an empty pool.
    const bool compared = res_.gl_rates[gi].compared_with != SeamsGlComparison::none;
    for (faces::SeamMethod m : methods_) {
      SeamsGlMethodResult& gm = res_.gl_rates[gi].methods[std::size_t(m)];
      const Agreement& a = agree_[gi][std::size_t(m)];
      gm.psnr_db = compared ? a.psnr() : std::nan("");
      gm.fraction_ge_001 = compared ? a.fraction() : std::nan("");
      gm.worst_psnr_db = compared ? a.worst_psnr : std::nan("");
      gm.worst_fraction_ge_001 = compared ? a.worst_fraction : std::nan("");
    }
  }
  if (c_.compare_references) {
    res_.gl_reference_vs_cpu = {true, ref_agree_.psnr(), ref_agree_.fraction(),
                                ref_agree_.worst_psnr, ref_agree_.worst_fraction};
  }
  return std::move(res_);
}

}  // namespace

namespace {

Result<SeamsResult> run_steps(const SeamsConfig& c) {
  SeamsRun run(c);
  if (Status s = run.make_backends(); !s.ok()) return s;
  if (Status s = run.start(); !s.ok()) return s;
  if (Status s = run.warm_up(); !s.ok()) return s;
  for (int f = 0; f < c.frames; ++f) {
    if (Status s = run.frame(f); !s.ok()) return s;
  }
  return run.finish();
}

}  // namespace

Result<SeamsResult> run_seams(const SeamsConfig& c) {
  if (Status s = check_config(c); !s.ok()) return s;
  Result<SeamsResult> res = run_steps(c);  // the backends are gone when it returns
  const GpuBackendFactory* factory =
      *detail::gpu_factory("seams", c.backend, c.gl_factory, c.vk_factory);
  if (factory != nullptr) {
    if (Status s = factory->device_status(); !s.ok()) return s;
  }
  return res;
}

}  // namespace tessera::experiments
