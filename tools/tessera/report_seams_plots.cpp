// The plots and images of `tessera seams`: cdf.csv and Figure 5 (CDFs of per-pixel linear-RGB
// 2-norm errors) as SVG and PNG, the frame-0 images of every method and rate, zooms on the
// worst seam and the Clamp-minus-Traverse heatmaps. (JSON and Markdown: report_seams.cpp.)
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "plot.h"
#include "report.h"
#include "report_seams_internal.h"
#include "tessera/io.h"
#include "tessera/metrics.h"

namespace tessera::cli::seams_report {

namespace {

using experiments::ErrorStats;
using experiments::SeamsRateResult;
using faces::SeamMethod;

constexpr float kDiffScale = 0.05f;  // heatmap saturation of the clamp-minus-traverse images

float norm_rgb(const float* a, const float* b) {
  const float d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
  return std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
}

ImageRGBA8 to_png_image(const ImageRGBAF& img, int threads) {
  ImageRGBAF c = img;
  for (std::size_t i = 0; i < c.pixel_count(); ++i) c.pixels[i * 4 + 3] = 1.0f;
  ImageRGBA8 out = to_srgb8(c, {threads});
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

const char* rate_colour(std::size_t i) {
  static const char* c[] = {"#d62728", "#ff7f0e", "#2ca02c", "#1f77b4", "#9467bd"};
  return c[std::min<std::size_t>(i, 4)];
}

const char* method_dash(SeamMethod m) {
  switch (m) {
    case SeamMethod::clamp:
      return "2,3";
    case SeamMethod::discard:
      return "";
    case SeamMethod::traverse:
      return "8,4";
    case SeamMethod::traverse_corners:
      return "12,3,2,3";
  }
  return "";
}

/// One CDF curve: y[i] is the fraction of pixels with error >= i * kStep.
PlotSeries cdf_series(std::string label, std::string colour, std::string dash,
                      const std::vector<double>& cdf) {
  PlotSeries ser;
  ser.label = std::move(label);
  ser.colour = std::move(colour);
  ser.dash = std::move(dash);
  for (int i = 0; i < kBins && i < int(cdf.size()); ++i) {
    ser.x.push_back(double(i) * kStep);
    ser.y.push_back(cdf[std::size_t(i)]);
  }
  return ser;
}

/// The axes of Figure 5: the error threshold x (0 to 0.15, linear) against the fraction of
/// pixels with error >= x (1e-4 to 1, logarithmic).
Plot cdf_axes(std::string title, std::string x_title, std::string y_title) {
  Plot plot;
  plot.title = std::move(title);
  plot.x_title = std::move(x_title);
  plot.y_title = std::move(y_title);
  plot.log_y = true;
  plot.x_min = 0;
  plot.x_max = 0.15;
  plot.y_min = 1e-4;
  plot.y_max = 1;
  return plot;
}

}  // namespace

/// Frame 0 of every method and rate, the reference, and a zoom on the worst seam: the window
/// where Clamp and Traverse differ most at the first rate.
Status write_images(const experiments::SeamsConfig& c, const experiments::SeamsResult& res,
                    const std::string& dir) {
  const ImageRGBA8 ref8 = to_png_image(res.reference_frame0, c.threads);
  if (Status s = io::write_png(dir + "/images/reference.png", ref8); !s.ok()) return s;
  const experiments::SeamsZoomWindow z = experiments::seams_zoom_window(c, res);
  const int bx = z.x, by = z.y, zw = z.w, zh = z.h;
  const int zs = z.scale;
  if (Status s = io::write_png(dir + "/images/zoom_reference.png", zoom(ref8, bx, by, zw, zh, zs));
      !s.ok()) {
    return s;
  }
  for (const SeamsRateResult& rate : res.rates) {
    for (const experiments::SeamsMethodResult& mr : rate.methods) {
      const std::string stem =
          std::string(faces::method_name(mr.method)) + "_" + rate_key(rate.msaa);
      const ImageRGBA8 img = to_png_image(mr.frame0, c.threads);
      if (Status s = io::write_png(dir + "/images/" + stem + ".png", img); !s.ok()) return s;
      if (Status s =
              io::write_png(dir + "/images/zoom_" + stem + ".png", zoom(img, bx, by, zw, zh, zs));
          !s.ok()) {
        return s;
      }
    }
  }
  // Clamp minus Traverse (frame 0): the seam artefact, per-pixel linear-RGB 2-norm.
  for (const SeamsRateResult* rate : {&res.rates.front(), &res.rates.back()}) {
    const ImageRGBAF& ca = rate->method(SeamMethod::clamp).frame0;
    const ImageRGBAF& tr = rate->method(SeamMethod::traverse).frame0;
    std::vector<float> d(ca.pixel_count());
    for (std::size_t i = 0; i < d.size(); ++i) {
      d[i] = norm_rgb(&ca.pixels[i * 4], &tr.pixels[i * 4]);
    }
    const std::string name = "clamp_minus_traverse_" + rate_key(rate->msaa);
    if (Status s = io::write_png(dir + "/images/" + name + ".png",
                                 metrics::heatmap(d, ca.width, ca.height, kDiffScale));
        !s.ok()) {
      return s;
    }
  }
  return write_text(dir + "/images/clamp_minus_traverse_colourbar.svg",
                    colour_bar_svg(metrics::ColourMap::inferno, 0, kDiffScale, 6,
                                   "|Clamp - Traverse|: linear-RGB 2-norm (0.05 and above "
                                   "saturate)"));
}

/// cdf.csv and the Figure-5 plots.
Status write_plots(const experiments::SeamsResult& res, const std::string& dir) {
  std::ostringstream csv;
  csv << "threshold";
  for (const SeamsRateResult& rate : res.rates) {
    csv << ",traverse_vs_discard_" << rate_key(rate.msaa);
  }
  const std::vector<SeamMethod>& methods = faces::all_methods();
  for (SeamMethod m : methods) {
    for (const SeamsRateResult& rate : res.rates) {
      csv << "," << faces::method_name(m) << "_vs_ref_" << rate_key(rate.msaa);
    }
  }
  csv << "\n";
  std::vector<const std::vector<double>*> cols;
  for (const SeamsRateResult& rate : res.rates) cols.push_back(&rate.traverse_vs_discard.cdf);
  for (SeamMethod m : methods) {
    for (const SeamsRateResult& rate : res.rates) cols.push_back(&rate.method(m).vs_reference.cdf);
  }
  for (int i = 0; i < kBins; ++i) {
    csv << double(i) * kStep;
    for (const std::vector<double>* col : cols) csv << "," << (*col)[std::size_t(i)];
    csv << "\n";
  }
  if (Status s = write_text(dir + "/cdf.csv", csv.str()); !s.ok()) return s;
  // Left: Traverse against Discard, one curve per rate; right: each method against the
  // reference (line style: method, colour: rate). The PNGs are the same plots without text.
  Plot left = cdf_axes("Traverse vs Discard", "linear-RGB 2-norm difference x",
                       "fraction of pixels with error \u2265 x");
  Plot right = cdf_axes(
      "Deviation from the reference (solid Discard, dashed Traverse, dotted "
      "Clamp)",
      left.x_title, left.y_title);
  left.height = right.height = 420;
  left.legend_column = right.legend_column = 180;
  for (std::size_t ri = 0; ri < res.rates.size(); ++ri) {
    left.series.push_back(cdf_series(rate_key(res.rates[ri].msaa), rate_colour(ri), "",
                                     res.rates[ri].traverse_vs_discard.cdf));
  }
  for (SeamMethod m : methods) {
    if (m == SeamMethod::traverse_corners) continue;  // in the CSV/JSON
    for (std::size_t ri = 0; ri < res.rates.size(); ++ri) {
      right.series.push_back(
          cdf_series(std::string(faces::method_name(m)) + " " + rate_key(res.rates[ri].msaa),
                     rate_colour(ri), method_dash(m), res.rates[ri].method(m).vs_reference.cdf));
    }
  }
  // One readable panel per rate: Clamp, Discard and Traverse against the reference over all
  // geometry pixels (solid) and near the seams (dashed).
  for (std::size_t ri = 0; ri < res.rates.size(); ++ri) {
    const SeamsRateResult& rate = res.rates[ri];
    Plot plot =
        cdf_axes("Figure 5, " + rate_key(rate.msaa) + " MSAA: error against the reference",
                 "x: per-pixel linear-RGB error (2-norm)", "fraction of pixels with error >= x");
    std::size_t colour = 0;
    for (SeamMethod m : {SeamMethod::clamp, SeamMethod::discard, SeamMethod::traverse}) {
      for (bool near : {false, true}) {
        if (near && res.near_seam_pixels == 0) continue;
        const ErrorStats& q =
            near ? rate.method(m).vs_reference_near_seams : rate.method(m).vs_reference;
        PlotSeries ser =
            cdf_series(std::string(faces::method_name(m)) +
                           (near ? ", near seams" : ", all pixels") + fmt(" (mean %.4f)", q.mean),
                       series_colour(colour), near ? "6 4" : "", q.cdf);
        plot.series.push_back(std::move(ser));
      }
      ++colour;
    }
    if (Status s = write_text(dir + "/fig5_" + rate_key(rate.msaa) + ".svg", plot_svg(plot));
        !s.ok()) {
      return s;
    }
  }
  if (Status s = write_text(dir + "/fig5_left.svg", plot_svg(left)); !s.ok()) return s;
  if (Status s = io::write_png(dir + "/fig5_left.png", plot_png(left)); !s.ok()) return s;
  if (Status s = io::write_png(dir + "/fig5_right.png", plot_png(right)); !s.ok()) return s;
  return write_text(dir + "/fig5_right.svg", plot_svg(right));
}

}  // namespace tessera::cli::seams_report
