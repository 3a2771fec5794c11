// tessera seams: the experiment of Toth 2013 — Clamp, Discard, Traverse and Traverse+corners
// at every MSAA rate along a camera orbit; Table 1 (median ms per frame, side by side) and
// Figure 5 (CDFs of per-pixel linear-RGB 2-norm errors) as JSON, Markdown, CSV and SVG.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli.h"
#include "report.h"
#include "seams.h"
#include "tessera/io.h"
#include "tessera/ptex.h"

namespace tessera::cli {

namespace {
namespace fs = std::filesystem;

// CDF thresholds: 0, 0.001, ..., 0.3 (linear-RGB 2-norm).
constexpr int kBins = 301;
constexpr double kStep = 0.001;

struct Cdf {
  std::vector<std::uint64_t> hist = std::vector<std::uint64_t>(kBins, 0);
  std::uint64_t counted = 0;
  double sum = 0;

  void add(float e) {
    const int k = std::min(kBins - 1, int(double(e) / kStep));
    ++hist[std::size_t(std::max(k, 0))];
    ++counted;
    sum += double(e);
  }
  /// Fraction of counted pixels with error >= threshold i * kStep.
  std::vector<double> fractions() const {
    std::vector<double> f(kBins, 0.0);
    std::uint64_t acc = 0;
    for (int i = kBins - 1; i >= 0; --i) {
      acc += hist[std::size_t(i)];
      f[std::size_t(i)] = counted ? double(acc) / double(counted) : 0.0;
    }
    return f;
  }
  double mean() const { return counted ? sum / double(counted) : 0.0; }
  double at(double x) const { return fractions()[std::size_t(std::lround(x / kStep))]; }
};

float norm_rgb(const float* a, const float* b) {
  const float d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
  return std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
}

/// Counted pixels: the reference's (Mitchell-filtered) coverage exceeds 1 %: geometry only.
std::vector<std::uint8_t> geometry_mask(const ImageRGBAF& ref) {
  std::vector<std::uint8_t> m(ref.pixel_count());
  for (std::size_t i = 0; i < m.size(); ++i) m[i] = ref.pixels[i * 4 + 3] > 0.01f ? 1 : 0;
  return m;
}

void accumulate(Cdf& cdf, const ImageRGBAF& a, const ImageRGBAF& b,
                const std::vector<std::uint8_t>& mask) {
  for (std::size_t i = 0; i < mask.size(); ++i) {
    if (mask[i]) cdf.add(norm_rgb(&a.pixels[i * 4], &b.pixels[i * 4]));
  }
}

ImageRGBA8 to_png_image(const ImageRGBAF& img, int threads) {
  ImageRGBAF c = img;
  for (std::size_t i = 0; i < c.pixel_count(); ++i) c.pixels[i * 4 + 3] = 1.0f;
  ImageRGBA8 out = to_srgb8(c, threads);
  out.has_alpha = false;
  return out;
}

ImageRGBA8 zoom(const ImageRGBA8& img, int x0, int y0, int w, int h, int s) {
  ImageRGBA8 out(w * s, h * s);
  for (int y = 0; y < h * s; ++y) {
    for (int x = 0; x < w * s; ++x) {
      const std::uint8_t* p = img.at(x0 + x / s, y0 + y / s);
      std::copy(p, p + 4, out.at(x, y));
    }
  }
  return out;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Curve {
  std::string label;
  std::string color;
  std::string dash;
  std::vector<double> y;
};

/// A log-y CDF plot: x = 2-norm threshold (linear, 0..xmax), y = fraction >= x (1e-4..1).
std::string cdf_svg(const std::string& title, const std::vector<Curve>& curves, double xmax) {
  const int W = 640, H = 420, L = 70, R = 190, T = 40, B = 50;
  const int pw = W - L - R, ph = H - T - B;
  const double ymin = -4.0;
  auto px = [&](double x) { return L + pw * std::min(x, xmax) / xmax; };
  auto py = [&](double f) {
    const double l = f > 0 ? std::max(std::log10(f), ymin) : ymin;
    return T + ph * (l / ymin);
  };
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
    << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" "
       "fill=\"white\"/>\n";
  s << "<text x=\"" << L << "\" y=\"22\" font-size=\"14\">" << title << "</text>\n";
  for (int e = 0; e >= -4; --e) {
    const double y = py(std::pow(10.0, e));
    s << "<line x1=\"" << L << "\" x2=\"" << L + pw << "\" y1=\"" << y << "\" y2=\"" << y
      << "\" stroke=\"#ddd\"/><text x=\"" << L - 8 << "\" y=\"" << y + 4
      << "\" text-anchor=\"end\">1e" << e << "</text>\n";
  }
  for (int i = 0; i <= 6; ++i) {
    const double xv = xmax * i / 6, x = px(xv);
    s << "<line x1=\"" << x << "\" x2=\"" << x << "\" y1=\"" << T << "\" y2=\"" << T + ph
      << "\" stroke=\"#eee\"/><text x=\"" << x << "\" y=\"" << T + ph + 16
      << "\" text-anchor=\"middle\">" << std::fixed;
    s.precision(3);
    s << xv << "</text>\n";
  }
  s << "<rect x=\"" << L << "\" y=\"" << T << "\" width=\"" << pw << "\" height=\"" << ph
    << "\" fill=\"none\" stroke=\"black\"/>\n";
  s << "<text x=\"" << L + pw / 2 << "\" y=\"" << H - 10
    << "\" text-anchor=\"middle\">linear-RGB 2-norm difference x</text>\n";
  s << "<text transform=\"translate(16," << T + ph / 2
    << ") rotate(-90)\" text-anchor=\"middle\">fraction of pixels with error &#8805; x</text>\n";
  for (std::size_t c = 0; c < curves.size(); ++c) {
    s << "<polyline fill=\"none\" stroke=\"" << curves[c].color << "\" stroke-width=\"1.6\"";
    if (!curves[c].dash.empty()) s << " stroke-dasharray=\"" << curves[c].dash << "\"";
    s << " points=\"";
    for (std::size_t i = 0; i < curves[c].y.size(); ++i) {
      const double x = double(i) * kStep;
      if (x > xmax) break;
      s << px(x) << "," << py(curves[c].y[i]) << " ";
    }
    s << "\"/>\n";
    const int ly = T + 10 + int(c) * 16;
    s << "<line x1=\"" << L + pw + 10 << "\" x2=\"" << L + pw + 40 << "\" y1=\"" << ly << "\" y2=\""
      << ly << "\" stroke=\"" << curves[c].color << "\" stroke-width=\"2\"";
    if (!curves[c].dash.empty()) s << " stroke-dasharray=\"" << curves[c].dash << "\"";
    s << "/><text x=\"" << L + pw + 46 << "\" y=\"" << ly + 4 << "\">" << curves[c].label
      << "</text>\n";
  }
  s << "</svg>\n";
  return s.str();
}

/// The same plot as `cdf_svg`, rasterised to a PNG image (same axes, grid, colours and dash
/// patterns; the legend swatches are in the same order as the SVG's labelled legend, which
/// carries the text). Pure code: no font or SVG library needed.
ImageRGBA8 cdf_png(const std::vector<Curve>& curves, double xmax) {
  const int W = 640, H = 420, L = 70, R = 190, T = 40, B = 50;
  const int pw = W - L - R, ph = H - T - B;
  const double ymin = -4.0;
  auto px = [&](double x) { return L + pw * std::min(x, xmax) / xmax; };
  auto py = [&](double f) {
    const double l = f > 0 ? std::max(std::log10(f), ymin) : ymin;
    return T + ph * (l / ymin);
  };
  ImageRGBA8 img(W, H);
  std::fill(img.pixels.begin(), img.pixels.end(), std::uint8_t(255));
  auto dot = [&](int x, int y, const std::uint8_t rgb[3], int size) {
    for (int dy = 0; dy < size; ++dy) {
      for (int dx = 0; dx < size; ++dx) {
        const int xx = x + dx, yy = y + dy;
        if (xx < 0 || yy < 0 || xx >= W || yy >= H) continue;
        std::copy(rgb, rgb + 3, img.at(xx, yy));
      }
    }
  };
  // A line from (x0, y0) to (x1, y1) walked in half-pixel steps; `dash` alternates on/off
  // lengths in pixels (empty = solid), continuing its phase across segments via `phase`.
  auto line = [&](double x0, double y0, double x1, double y1, const std::uint8_t rgb[3],
                  const std::vector<double>& dash, double& phase, int size) {
    const double len = std::hypot(x1 - x0, y1 - y0);
    const int steps = std::max(1, int(len * 2.0));
    double period = 0;
    for (double d : dash) period += d;
    for (int i = 0; i <= steps; ++i) {
      const double t = double(i) / steps;
      bool on = true;
      if (period > 0) {
        double q = std::fmod(phase + t * len, period);
        for (std::size_t k = 0; k < dash.size(); ++k) {
          if (q < dash[k]) {
            on = (k % 2) == 0;
            break;
          }
          q -= dash[k];
        }
      }
      if (on) dot(int(std::lround(x0 + t * (x1 - x0))), int(std::lround(y0 + t * (y1 - y0))), rgb, size);
    }
    phase += len;
  };
  auto parse_rgb = [](const std::string& hex, std::uint8_t rgb[3]) {
    const unsigned v = unsigned(std::stoul(hex.substr(1), nullptr, 16));
    rgb[0] = std::uint8_t(v >> 16);
    rgb[1] = std::uint8_t(v >> 8);
    rgb[2] = std::uint8_t(v);
  };
  auto parse_dash = [](const std::string& text) {
    std::vector<double> d;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) d.push_back(std::stod(item));
    return d;
  };
  const std::uint8_t grid[3] = {221, 221, 221}, black[3] = {0, 0, 0};
  double phase = 0;
  for (int e = 0; e >= -4; --e) {
    const double y = py(std::pow(10.0, e));
    line(L, y, L + pw, y, grid, {}, phase, 1);
  }
  for (int i = 0; i <= 6; ++i) {
    const double x = px(xmax * i / 6);
    line(x, T, x, T + ph, grid, {}, phase, 1);
  }
  line(L, T, L + pw, T, black, {}, phase, 1);
  line(L, T + ph, L + pw, T + ph, black, {}, phase, 1);
  line(L, T, L, T + ph, black, {}, phase, 1);
  line(L + pw, T, L + pw, T + ph, black, {}, phase, 1);
  for (std::size_t c = 0; c < curves.size(); ++c) {
    std::uint8_t rgb[3];
    parse_rgb(curves[c].color, rgb);
    const std::vector<double> dash = parse_dash(curves[c].dash);
    phase = 0;
    for (std::size_t i = 1; i < curves[c].y.size(); ++i) {
      const double x0 = double(i - 1) * kStep, x1 = double(i) * kStep;
      if (x1 > xmax) break;
      line(px(x0), py(curves[c].y[i - 1]), px(x1), py(curves[c].y[i]), rgb, dash, phase, 2);
    }
    const int ly = T + 10 + int(c) * 16;
    phase = 0;
    line(L + pw + 10, ly, L + pw + 40, ly, rgb, dash, phase, 2);
  }
  return img;
}

Status write_text(const std::string& path, const std::string& text) {
  return write_file_atomic(
      path, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()),
                                          text.size()));
}

const char* rate_color(std::size_t i) {
  static const char* c[] = {"#d62728", "#ff7f0e", "#2ca02c", "#1f77b4", "#9467bd"};
  return c[std::min<std::size_t>(i, 4)];
}
const char* method_dash(faces::Method m) {
  switch (m) {
    case faces::Method::clamp:
      return "2,3";
    case faces::Method::discard:
      return "";
    case faces::Method::traverse:
      return "8,4";
    case faces::Method::traverse_corners:
      return "12,3,2,3";
  }
  return "";
}

struct Loaded {
  faces::FaceScene scene;
  faces::FaceTextureSet set;
  std::string description;
};

Result<Loaded> load_content(const SeamsConfig& c) {
  Loaded l;
  if (c.scene == "figure1") {
    faces::Figure1Options fo = c.figure1;
    if (!c.character.empty()) {
      Result<faces::PolygonMesh> poly = faces::load_obj_polygons(c.character);
      if (!poly) return poly.status();
      // Non-quad faces are split into quads (a triangle mesh: 3 quads per triangle).
      fo.character_mesh = faces::ptex_face_layout(*poly);
      for (int i = 0; i < c.subdivide; ++i) fo.character_mesh = faces::subdivide(fo.character_mesh);
    }
    l.scene = faces::figure1_scene(fo);
    Result<std::vector<faces::FaceAdjacency>> adj = faces::build_adjacency(l.scene.mesh);
    if (!adj) return adj.status();
    Result<faces::FaceTextureSet> set =
        faces::FaceTextureSet::create(faces::bake_faces(l.scene, 1.0f, c.threads), *adj, c.threads);
    if (!set) return set.status();
    l.set = std::move(*set);
    l.description = "built-in Figure-1 scene: ground plane of " +
                    std::to_string(l.scene.ground_faces) + " faces and " +
                    (c.character.empty() ? std::string("a cube-sphere character")
                                         : c.character + " (" + std::to_string(c.subdivide) +
                                               " subdivision step(s))") +
                    " of " + std::to_string(l.scene.mesh.face_count() - l.scene.ground_faces) +
                    " faces, textures baked from a procedural 3D function";
    return l;
  }
  Result<faces::PolygonMesh> poly = faces::load_obj_polygons(c.scene);
  if (!poly) return poly.status();
  // Quads stay faces; other polygons are split into Ptex subfaces (triangles into 3 quads).
  std::vector<bool> subface;
  l.scene.mesh = faces::ptex_face_layout(*poly, &subface);
  const bool split = std::count(subface.begin(), subface.end(), true) > 0;
  l.scene.name = fs::path(c.scene).stem().string();
  Result<std::vector<faces::FaceAdjacency>> adj = faces::build_adjacency(l.scene.mesh);
  if (!adj) return Status::error(adj.status().code, c.scene + ": " + adj.status().message);
  if (!c.ptex.empty()) {
    Result<ptex::PtexFile> file = ptex::read_ptex(c.ptex);
    if (!file) return file.status();
    // Refuses triangle-mesh files before any comparison with the mesh.
    Result<faces::FaceTextureSet> set = faces::FaceTextureSet::from_ptex(*file, c.ptex, c.threads);
    if (!set) return set.status();
    if (file->face_count() != l.scene.mesh.face_count()) {
      return Status::error(ErrorCode::size_mismatch,
                           c.ptex + ": " + std::to_string(file->face_count()) + " faces, but " +
                               c.scene + " has " + std::to_string(l.scene.mesh.face_count()));
    }
    for (const ptex::FaceInfo& fi : file->faces) {
      l.scene.ulog2.push_back(fi.ulog2);
      l.scene.vlog2.push_back(fi.vlog2);
    }
    l.set = std::move(*set);
    l.description = c.scene + " with its Ptex file " + c.ptex + " (adjacency from the file" +
                    (split ? std::string(", non-quad faces split into subfaces)") : ")");
    return l;
  }
  // Procedural textures, resolution from edge lengths, pattern scaled to the mesh size.
  Vec3 lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};
  for (const Vec3& p : l.scene.mesh.positions) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  const float diag = std::max(length(hi - lo), 1e-6f);
  faces::assign_resolutions(l.scene, 400.0f / diag, 2, 7);
  Result<faces::FaceTextureSet> set = faces::FaceTextureSet::create(
      faces::bake_faces(l.scene, 4.0f / diag, c.threads), *adj, c.threads);
  if (!set) return set.status();
  l.set = std::move(*set);
  l.description = c.scene + (split ? " (non-quad faces split into quads)" : "") +
                  " with procedural per-face textures";
  return l;
}

std::string rate_key(int r) { return std::to_string(r) + "x"; }

}  // namespace

Status run_seams(const SeamsConfig& c, nlohmann::json& summary, bool verbose) {
  auto log = [&](const std::string& s) {
    if (verbose) std::fprintf(stderr, "seams: %s\n", s.c_str());
  };
  if (c.msaa.empty() || c.frames < 1 || c.width < 8 || c.height < 8) {
    return Status::error(ErrorCode::invalid_argument, "seams: bad configuration");
  }
  for (int r : c.msaa) {
    if (!raster::valid_msaa(r)) {
      return Status::error(ErrorCode::invalid_argument,
                           "seams: MSAA rate " + std::to_string(r) + " not in 1,2,4,8,16");
    }
  }
  const auto t_load = std::chrono::steady_clock::now();
  Result<Loaded> loaded = load_content(c);
  if (!loaded) return loaded.status();
  const faces::FaceScene& scene = loaded->scene;
  const faces::FaceTextureSet& set = loaded->set;
  log(loaded->description + fmt(", built in %.0f ms", std::chrono::duration<double, std::milli>(
                                                          std::chrono::steady_clock::now() - t_load)
                                                          .count()));
  Result<std::unique_ptr<faces::FaceRenderer>> renderer = faces::FaceRenderer::create(scene, set);
  if (!renderer) return renderer.status();
  // The output folder is created only once the inputs are known to be good.
  std::error_code ec;
  fs::create_directories(fs::path(c.out) / "images", ec);
  if (ec) return Status::error(ErrorCode::io_error, c.out + ": cannot create: " + ec.message());

  const std::vector<faces::Method>& methods = faces::all_methods();
  const std::size_t nm = methods.size(), nr = c.msaa.size();
  const int qframes = c.quality_frames > 0 ? std::min(c.quality_frames, c.frames) : c.frames;
  // timing[r][v]: v = method index, or nm for shading only.
  std::vector<std::vector<std::vector<double>>> timing(nr,
                                                       std::vector<std::vector<double>>(nm + 1));
  std::vector<std::vector<Cdf>> vs_ref(nr, std::vector<Cdf>(nm));
  // The same, counting only character pixels (Figure-1 scenes): curved geometry, where
  // Traverse's extrapolation is approximate.
  std::vector<std::vector<Cdf>> vs_ref_char(nr, std::vector<Cdf>(nm));
  const bool has_character = scene.ground_faces > 0 && scene.ground_faces < set.face_count();
  std::vector<Cdf> t_vs_d(nr);
  std::vector<std::uint64_t> nan_pixels(nr, 0);
  std::vector<std::vector<ImageRGBAF>> frame0(nr, std::vector<ImageRGBAF>(nm));
  ImageRGBAF ref0;
  double ref_ms = 0;
  faces::FaceRenderOptions o;
  o.width = c.width;
  o.height = c.height;
  o.threads = c.threads;
  o.sampling.filter = TextureFilter::anisotropic;
  o.sampling.max_aniso = 16;

  for (int f = 0; f < c.frames; ++f) {
    const scene::Camera cam = faces::face_orbit_camera(scene, f, c.frames);
    // Quality frames are spread evenly over the orbit (frame 0 always included).
    const bool quality = f == 0 || (f * qframes) / c.frames != ((f - 1) * qframes) / c.frames;
    ImageRGBAF ref;
    std::vector<std::uint8_t> mask, char_mask;
    if (quality) {
      const auto t0 = std::chrono::steady_clock::now();
      Result<ImageRGBAF> r =
          (*renderer)->render_reference(cam, c.width, c.height, c.reference_factor, c.threads);
      if (!r) return r.status();
      ref_ms +=
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      ref = std::move(*r);
      mask = geometry_mask(ref);
      if (f == 0) ref0 = ref;
      if (has_character) {
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
      o.msaa = c.msaa[ri];
      std::vector<ImageRGBAF> imgs(nm);
      // Alternate: the order of the variants rotates with the frame.
      for (std::size_t k = 0; k <= nm; ++k) {
        const std::size_t v = (k + std::size_t(f)) % (nm + 1);
        o.shading_only = v == nm;
        o.sampling.method = v == nm ? faces::Method::clamp : methods[v];
        o.sampling.clamp_fallback = true;
        Result<faces::FaceFrame> fr = (*renderer)->render(cam, o);
        if (!fr) return fr.status();
        timing[ri][v].push_back(fr->ms());
        if (v < nm) imgs[v] = std::move(fr->image);
      }
      if (quality) {
        for (std::size_t m = 0; m < nm; ++m) {
          accumulate(vs_ref[ri][m], imgs[m], ref, mask);
          if (has_character) accumulate(vs_ref_char[ri][m], imgs[m], ref, char_mask);
        }
        accumulate(t_vs_d[ri], imgs[2], imgs[1], mask);
      }
      if (f == 0) {
        // Discard without the zero-coverage fallback: count the NaN pixels it produces.
        o.shading_only = false;
        o.sampling.method = faces::Method::discard;
        o.sampling.clamp_fallback = false;
        Result<faces::FaceFrame> fr = (*renderer)->render(cam, o);
        if (!fr) return fr.status();
        for (std::size_t i = 0; i < fr->image.pixel_count(); ++i) {
          const float* p = &fr->image.pixels[i * 4];
          if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
            ++nan_pixels[ri];
          }
        }
        frame0[ri] = std::move(imgs);
      }
    }
    log(fmt("frame %.0f", double(f + 1)) + "/" + std::to_string(c.frames) + " done");
  }

  // ---- Images: frame 0 per method and rate, the reference, and a zoom on the worst seam.
  const std::string dir = c.out;
  if (c.write_images) {
    const ImageRGBA8 ref8 = to_png_image(ref0, c.threads);
    if (Status s = write_png(dir + "/images/reference.png", ref8); !s.ok()) return s;
    // Zoom window: where Clamp and Traverse differ most at the lowest rate (a seam).
    const int zw = std::min(40, c.width), zh = std::min(40, c.height);
    int bx = 0, by = 0;
    double best = -1;
    const ImageRGBAF& a = frame0[0][0];
    const ImageRGBAF& b = frame0[0][2];
    for (int y = 0; y + zh <= c.height; y += 4) {
      for (int x = 0; x + zw <= c.width; x += 4) {
        double s = 0;
        for (int yy = y; yy < y + zh; yy += 2) {
          for (int xx = x; xx < x + zw; xx += 2) s += norm_rgb(a.at(xx, yy), b.at(xx, yy));
        }
        if (s > best) {
          best = s;
          bx = x;
          by = y;
        }
      }
    }
    const int zs = 4;
    if (Status s = write_png(dir + "/images/zoom_reference.png", zoom(ref8, bx, by, zw, zh, zs));
        !s.ok()) {
      return s;
    }
    for (std::size_t ri = 0; ri < nr; ++ri) {
      for (std::size_t m = 0; m < nm; ++m) {
        const std::string stem =
            std::string(faces::method_name(methods[m])) + "_" + rate_key(c.msaa[ri]);
        const ImageRGBA8 img = to_png_image(frame0[ri][m], c.threads);
        if (Status s = write_png(dir + "/images/" + stem + ".png", img); !s.ok()) return s;
        if (Status s =
                write_png(dir + "/images/zoom_" + stem + ".png", zoom(img, bx, by, zw, zh, zs));
            !s.ok()) {
          return s;
        }
      }
    }
    summary["zoom_window"] = {{"x", bx}, {"y", by}, {"w", zw}, {"h", zh}, {"scale", zs}};
  }

  // ---- JSON.
  summary["command_config"] = {{"scene", c.scene},
                               {"ptex", c.ptex},
                               {"msaa", c.msaa},
                               {"frames", c.frames},
                               {"quality_frames", qframes},
                               {"width", c.width},
                               {"height", c.height},
                               {"reference_factor", c.reference_factor},
                               {"threads", c.threads > 0 ? c.threads : default_thread_count()},
                               {"filter", "anisotropic 16x (trilinear probes)"}};
  const std::array<int, 16> pairs = faces::edge_pairing_histogram(set.adjacency());
  summary["scene"] = {{"description", loaded->description},
                      {"faces", set.face_count()},
                      {"ground_faces", scene.ground_faces},
                      {"texels_level0", set.texel_count()},
                      {"edge_pairings", pairs},
                      {"valence4_corner_links", set.linked_corner_count()},
                      {"corners", 4 * set.face_count()}};
  nlohmann::json timing_j, quality_j, nan_j;
  for (std::size_t ri = 0; ri < nr; ++ri) {
    const std::string rk = rate_key(c.msaa[ri]);
    for (std::size_t v = 0; v <= nm; ++v) {
      const std::string name = v == nm ? "shading_only" : faces::method_name(methods[v]);
      timing_j[rk][name] = {{"median_ms", median(timing[ri][v])}, {"frame_ms", timing[ri][v]}};
    }
    for (std::size_t m = 0; m < nm; ++m) {
      quality_j["vs_reference"][faces::method_name(methods[m])][rk] = {
          {"mean", vs_ref[ri][m].mean()},
          {"fraction_ge_0.01", vs_ref[ri][m].at(0.01)},
          {"fraction_ge_0.05", vs_ref[ri][m].at(0.05)},
          {"cdf", vs_ref[ri][m].fractions()}};
    }
    if (has_character) {
      for (std::size_t m = 0; m < nm; ++m) {
        quality_j["vs_reference_character_only"][faces::method_name(methods[m])][rk] = {
            {"mean", vs_ref_char[ri][m].mean()},
            {"fraction_ge_0.01", vs_ref_char[ri][m].at(0.01)},
            {"fraction_ge_0.05", vs_ref_char[ri][m].at(0.05)},
            {"counted_pixels", vs_ref_char[ri][m].counted}};
      }
    }
    quality_j["traverse_vs_discard"][rk] = {{"mean", t_vs_d[ri].mean()},
                                            {"fraction_ge_0.01", t_vs_d[ri].at(0.01)},
                                            {"fraction_ge_0.05", t_vs_d[ri].at(0.05)},
                                            {"cdf", t_vs_d[ri].fractions()}};
    quality_j["counted_pixels"][rk] = t_vs_d[ri].counted;
    nan_j[rk] = nan_pixels[ri];
  }
  quality_j["thresholds"] = {{"start", 0.0}, {"step", kStep}, {"count", kBins}};
  quality_j["counted"] =
      "geometry only: pixels whose reference coverage (Mitchell-filtered alpha) exceeds 0.01, "
      "summed over the quality frames";
  summary["timing"] = timing_j;
  summary["quality"] = quality_j;
  summary["nan_pixels_discard_without_fallback_frame0"] = nan_j;
  summary["reference_ms_total"] = ref_ms;

  // ---- CSV and SVG plots.
  {
    std::ostringstream csv;
    csv << "threshold";
    for (std::size_t ri = 0; ri < nr; ++ri) csv << ",traverse_vs_discard_" << rate_key(c.msaa[ri]);
    for (std::size_t m = 0; m < nm; ++m) {
      for (std::size_t ri = 0; ri < nr; ++ri) {
        csv << "," << faces::method_name(methods[m]) << "_vs_ref_" << rate_key(c.msaa[ri]);
      }
    }
    csv << "\n";
    std::vector<std::vector<double>> cols;
    for (std::size_t ri = 0; ri < nr; ++ri) cols.push_back(t_vs_d[ri].fractions());
    for (std::size_t m = 0; m < nm; ++m) {
      for (std::size_t ri = 0; ri < nr; ++ri) cols.push_back(vs_ref[ri][m].fractions());
    }
    for (int i = 0; i < kBins; ++i) {
      csv << double(i) * kStep;
      for (const auto& col : cols) csv << "," << col[std::size_t(i)];
      csv << "\n";
    }
    if (Status s = write_text(dir + "/cdf.csv", csv.str()); !s.ok()) return s;
    std::vector<Curve> left, right;
    for (std::size_t ri = 0; ri < nr; ++ri) {
      left.push_back({rate_key(c.msaa[ri]), rate_color(ri), "", t_vs_d[ri].fractions()});
    }
    for (std::size_t m = 0; m < nm; ++m) {
      if (methods[m] == faces::Method::traverse_corners) continue;  // in the CSV/JSON
      for (std::size_t ri = 0; ri < nr; ++ri) {
        right.push_back({std::string(faces::method_name(methods[m])) + " " + rate_key(c.msaa[ri]),
                         rate_color(ri), method_dash(methods[m]), vs_ref[ri][m].fractions()});
      }
    }
    if (Status s = write_text(dir + "/fig5_left.svg", cdf_svg("Traverse vs Discard", left, 0.15));
        !s.ok()) {
      return s;
    }
    if (Status s = write_png(dir + "/fig5_left.png", cdf_png(left, 0.15)); !s.ok()) return s;
    if (Status s = write_png(dir + "/fig5_right.png", cdf_png(right, 0.15)); !s.ok()) return s;
    if (Status s = write_text(dir + "/fig5_right.svg",
                              cdf_svg("Deviation from the reference (solid Discard, dashed "
                                      "Traverse, dotted Clamp)",
                                      right, 0.15));
        !s.ok()) {
      return s;
    }
  }

  // ---- Markdown.
  std::ostringstream md;
  md << "# Seams experiment (Toth 2013, Table 1 and Figure 5)\n\n";
  md << "Scene: " << loaded->description << "; " << set.face_count() << " faces, "
     << set.texel_count() << " level-0 texels, " << set.linked_corner_count() << " of "
     << 4 * set.face_count() << " corners with a valence-4 diagonal face. " << c.width << "x"
     << c.height << ", " << c.frames << " orbit frames (" << qframes
     << " with a reference), 16x anisotropic filtering, "
     << (c.threads > 0 ? c.threads : default_thread_count()) << " thread(s).\n\n";
  md << "## Table 1 analogue: median ms per frame\n\n";
  md << "Raster + shading + MSAA box resolve, all variants rendered side by side in one run, "
        "alternating per frame; `shading only` is the same pass without the texture lookup.\n\n";
  md << "| method |";
  for (int r : c.msaa) md << " " << r << "x |";
  md << "\n|---|";
  for (std::size_t ri = 0; ri < nr; ++ri) md << "---:|";
  md << "\n";
  for (std::size_t v = 0; v <= nm; ++v) {
    md << "| " << (v == nm ? std::string("shading only") : faces::method_name(methods[v])) << " |";
    for (std::size_t ri = 0; ri < nr; ++ri) md << fmt(" %.1f |", median(timing[ri][v]));
    md << "\n";
  }
  md << "| **traverse / discard** |";
  bool speed_ok = true;
  for (std::size_t ri = 0; ri < nr; ++ri) {
    const double ratio = median(timing[ri][2]) / std::max(median(timing[ri][1]), 1e-9);
    speed_ok = speed_ok && ratio >= 2.0;
    md << fmt(" %.2fx |", ratio);
  }
  md << "\n\n";
  md << "## Figure 5 analogue\n\n";
  md << "Pixels counted: **geometry only** — pixels whose reference coverage (the alpha of the "
        "Mitchell-filtered supersampled reference) exceeds 0.01, over the quality frames, the "
        "same set for every method and rate. Error = per-pixel 2-norm of the linear-RGB "
        "difference. Plots: `fig5_left.svg` (Traverse vs Discard), `fig5_right.svg` (each "
        "method vs the reference: Traverse at "
     << c.reference_factor << "x" << c.reference_factor
     << " the resolution, downsampled with Mitchell-Netravali B = C = 1/3), each also as PNG "
        "(`fig5_left.png`, `fig5_right.png`: same curves and legend order, labels in the SVG); "
        "data in `cdf.csv` and `seams.json`.\n\n";
  md << "| comparison | rate | mean error | fraction >= 0.01 | fraction >= 0.05 |\n"
        "|---|---|---:|---:|---:|\n";
  for (std::size_t ri = 0; ri < nr; ++ri) {
    md << "| traverse vs discard | " << rate_key(c.msaa[ri]) << fmt(" | %.5f", t_vs_d[ri].mean())
       << fmt(" | %.4f", t_vs_d[ri].at(0.01)) << fmt(" | %.4f |\n", t_vs_d[ri].at(0.05));
  }
  for (std::size_t m = 0; m < nm; ++m) {
    for (std::size_t ri = 0; ri < nr; ++ri) {
      const Cdf& q = vs_ref[ri][m];
      md << "| " << faces::method_name(methods[m]) << " vs reference | " << rate_key(c.msaa[ri])
         << fmt(" | %.5f", q.mean()) << fmt(" | %.4f", q.at(0.01))
         << fmt(" | %.4f |\n", q.at(0.05));
    }
  }
  if (has_character) {
    md << "\nBreakdown (not the Figure-5 pixel set): the same comparison counting only the "
          "character's pixels (at least half of 8 MSAA samples on a character face), where the "
          "surface is curved and Traverse's extrapolation across edges is approximate.\n\n"
          "| method vs reference, character only | rate | mean error | fraction >= 0.01 | "
          "fraction >= 0.05 |\n|---|---|---:|---:|---:|\n";
    for (std::size_t m = 0; m < nm; ++m) {
      for (std::size_t ri = 0; ri < nr; ++ri) {
        const Cdf& q = vs_ref_char[ri][m];
        md << "| " << faces::method_name(methods[m]) << " | " << rate_key(c.msaa[ri])
           << fmt(" | %.5f", q.mean()) << fmt(" | %.4f", q.at(0.01))
           << fmt(" | %.4f |\n", q.at(0.05));
      }
    }
  }
  md << "\n## Targets\n\n";
  md << "- Discard at least 2x faster than Traverse at every rate: **"
     << (speed_ok ? "met" : "not met") << "** (ratios in the table).\n";
  for (std::size_t ri = 0; ri < nr; ++ri) {
    const double d = vs_ref[ri][1].mean(), t = vs_ref[ri][2].mean();
    md << "- " << rate_key(c.msaa[ri]) << ": mean error vs reference Discard " << fmt("%.5f", d)
       << ", Traverse " << fmt("%.5f", t) << " -> "
       << (d <= t ? "Discard no worse" : "Traverse better") << ".\n";
  }
  md << "\n## Zero-coverage fallback\n\nDiscard without the clamp fallback (frame 0): pixels "
        "with a NaN colour (0/0 where no tap of a pixel-centre lookup outside its face lands "
        "inside it; helper lanes are not shaded here):";
  for (std::size_t ri = 0; ri < nr; ++ri) {
    md << " " << rate_key(c.msaa[ri]) << ": " << nan_pixels[ri] << ";";
  }
  md << " with the fallback: 0.\n";
  if (c.write_images) {
    md << "\n## Images\n\n`images/<method>_<rate>.png` (frame 0), `images/reference.png`, and "
          "`images/zoom_*.png`: a 40x40 window at 4x where Clamp and Traverse differ most.\n";
  }
  if (Status s = write_text(dir + "/seams.md", md.str()); !s.ok()) return s;
  if (Status s = write_text(dir + "/seams.json", summary.dump(1)); !s.ok()) return s;
  return Status::success();
}

namespace {
struct SeamsArgs {
  SeamsConfig config;
  bool quiet = false;
};
}  // namespace

Command add_seams_command(CLI::App& app, const GlobalOptions& global) {
  auto args = std::make_shared<SeamsArgs>();
  CLI::App* sub = app.add_subcommand(
      "seams",
      "Toth 2013 experiment: Clamp/Discard/Traverse per-face texturing at every MSAA rate "
      "(Table 1 timings, Figure 5 error CDFs)");
  SeamsConfig& c = args->config;
  sub->add_option("--scene", c.scene, "'figure1' (built in) or an all-quad .obj")
      ->capture_default_str();
  sub->add_option("--ptex", c.ptex, "Ptex file with the textures of the .obj scene");
  sub->add_option("--character", c.character,
                  "figure1: .obj to use as the character instead of the cube-sphere (non-quad "
                  "faces are split into quads)");
  sub->add_option("--subdivide", c.subdivide, "Linear subdivision steps of --character")
      ->check(CLI::Range(0, 4))
      ->capture_default_str();
  sub->add_option("--msaa", c.msaa, "MSAA rates, comma-separated")
      ->delimiter(',')
      ->check(CLI::IsMember({1, 2, 4, 8, 16}));
  sub->add_option("--frames", c.frames, "Orbit frames")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sub->add_option("--quality-frames", c.quality_frames,
                  "Frames compared against a reference, spread over the orbit (0 = all)")
      ->check(CLI::Range(0, 100000));
  sub->add_option("--width", c.width)->check(CLI::Range(8, 8192))->capture_default_str();
  sub->add_option("--height", c.height)->check(CLI::Range(8, 8192))->capture_default_str();
  sub->add_option("--reference-factor", c.reference_factor, "Reference supersampling per axis")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  sub->add_flag("--quiet", args->quiet, "No progress on stderr");
  sub->add_option("-o,--output,--out", c.out, "Output folder")->required();
  return {sub, [args, &global] {
            SeamsConfig cfg = args->config;
            if (!cfg.ptex.empty() && cfg.scene == "figure1") {
              return usage_error("--ptex needs --scene MESH.obj (the mesh of the Ptex file)");
            }
            cfg.threads = global.threads;
            nlohmann::json summary;
            if (Status s = run_seams(cfg, summary, !args->quiet); !s.ok()) return fail(s);
            std::printf("wrote %s/seams.md\n", cfg.out.c_str());
            return int(kExitOk);
          }};
}

}  // namespace tessera::cli
