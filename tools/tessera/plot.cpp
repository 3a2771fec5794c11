// The plot engine (plot.h): layout, SVG plots and colour bars; plot_png.cpp rasterises.
#include "plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "plot_layout.h"
#include "report.h"

namespace tessera::cli {

namespace {

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f", v);
  return b;
}

/// A short label for a tick value.
std::string tick_text(double v) {
  char b[32];
  const double a = std::fabs(v);
  if (a != 0 && (a >= 1e5 || a < 1e-3)) {
    std::snprintf(b, sizeof b, "%.0e", v);
  } else if (a >= 100 || std::fabs(v - std::round(v)) < 1e-9) {
    std::snprintf(b, sizeof b, "%.0f", v);
  } else if (a >= 1) {
    std::snprintf(b, sizeof b, "%.1f", v);
  } else {
    std::snprintf(b, sizeof b, "%.3g", v);
  }
  return b;
}

/// "Nice" tick values covering [lo, hi] on a linear axis.
std::vector<double> linear_ticks(double lo, double hi, int target = 6) {
  const double span = hi - lo;
  if (!(span > 0)) return {lo};
  const double raw = span / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double norm = raw / mag;
  const double step = (norm < 1.5 ? 1 : norm < 3 ? 2 : norm < 7 ? 5 : 10) * mag;
  std::vector<double> t;
  for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + step * 1e-6; v += step) {
    t.push_back(std::fabs(v) < step * 1e-9 ? 0.0 : v);
  }
  return t;
}

/// Ticks at 1, 2, 5 x powers of ten inside [lo, hi] (lo > 0).
std::vector<double> log_ticks(double lo, double hi) {
  std::vector<double> t;
  const bool decades = std::log10(hi / lo) > 2.5;  // many decades: label powers of ten only
  for (double p = std::pow(10.0, std::floor(std::log10(lo))); p <= hi * 1.0001; p *= 10) {
    for (double m : {1.0, 2.0, 5.0}) {
      if (decades && m != 1.0) continue;
      const double v = p * m;
      if (v >= lo * 0.9999 && v <= hi * 1.0001) t.push_back(v);
    }
  }
  return t;
}

std::string dash_attribute(const PlotSeries& series) {
  return series.dash.empty() ? "" : " stroke-dasharray=\"" + series.dash + "\"";
}

}  // namespace

namespace plot_layout {

double Layout::px(double x) const {
  const double t = log_x ? (std::log10(x) - std::log10(x0)) / (std::log10(x1) - std::log10(x0))
                         : (x - x0) / (x1 - x0);
  return left + t * pw;
}

double Layout::py(double y) const {
  const double t =
      log_y ? (std::log10(std::max(y, y0)) - std::log10(y0)) / (std::log10(y1) - std::log10(y0))
            : (y - y0) / (y1 - y0);
  return top + (1 - t) * ph;
}

void Layout::legend_entry(std::size_t i, double& lx, double& ly) const {
  if (legend_column > 0) {
    lx = left + pw + 12;
    ly = top + 14 + 18 * double(i);
  } else {
    lx = left + double(i % 2) * pw / 2;
    ly = top + ph + 52 + 18 * double(i / 2);
  }
}

Layout layout(const Plot& plot) {
  // Data range.
  double x0 = plot.x_min, x1 = plot.x_max, y0 = plot.y_min, y1 = plot.y_max;
  if (x0 == x1 || y0 == y1) {
    double dx0 = 1e300, dx1 = -1e300, dy0 = 1e300, dy1 = -1e300;
    for (const PlotSeries& s : plot.series) {
      for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
        if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
        if (plot.log_x && s.x[i] <= 0) continue;
        dx0 = std::min(dx0, s.x[i]);
        dx1 = std::max(dx1, s.x[i]);
        dy0 = std::min(dy0, s.y[i]);
        dy1 = std::max(dy1, s.y[i]);
      }
    }
    if (dx0 > dx1) dx0 = 0, dx1 = 1, dy0 = 0, dy1 = 1;
    if (x0 == x1) {
      if (plot.log_x) {
        x0 = std::pow(10.0, std::floor(std::log10(dx0)));
        x1 = std::pow(10.0, std::ceil(std::log10(dx1)));
        if (x0 == x1) x1 = x0 * 10;
      } else {
        const double pad = (dx1 - dx0) * 0.05 + (dx1 == dx0 ? 1 : 0);
        x0 = dx0 - pad, x1 = dx1 + pad;
      }
    }
    if (y0 == y1) {
      const double pad = (dy1 - dy0) * 0.08 + (dy1 == dy0 ? 1 : 0);
      y0 = dy0 - pad, y1 = dy1 + pad;
    }
  }
  Layout l;
  l.x0 = x0, l.x1 = x1, l.y0 = y0, l.y1 = y1;
  l.log_x = plot.log_x, l.log_y = plot.log_y;
  l.legend_column = plot.legend_column;
  const int legend_rows = plot.legend_column > 0 ? 0 : int(plot.series.size());
  const int right = 16 + plot.legend_column;
  const int bottom = 52 + 18 * ((legend_rows + 1) / 2);
  l.left = 64;
  l.top = plot.title.empty() ? 16 : 36;
  l.pw = plot.width - l.left - right;
  l.ph = plot.height - l.top - bottom;
  for (double v : plot.log_x ? log_ticks(x0, x1) : linear_ticks(x0, x1)) {
    if (v >= x0 && v <= x1) l.x_ticks.push_back(v);
  }
  for (double v : plot.log_y ? log_ticks(y0, y1) : linear_ticks(y0, y1)) {
    if (v >= y0 && v <= y1) l.y_ticks.push_back(v);
  }
  return l;
}

bool drawable(const Layout& l, const PlotSeries& series, std::size_t i) {
  return std::isfinite(series.x[i]) && std::isfinite(series.y[i]) && !(l.log_x && series.x[i] <= 0);
}

}  // namespace plot_layout

const char* series_colour(std::size_t i) {
  static const char* kTab10[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                 "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
  return kTab10[i % 10];
}

std::string plot_svg(const Plot& plot) {
  const plot_layout::Layout l = plot_layout::layout(plot);
  const int W = plot.width, H = plot.height;
  const int left = l.left, top = l.top;
  const double pw = l.pw, ph = l.ph;
  auto px = [&](double x) { return l.px(x); };
  auto py = [&](double y) { return l.py(y); };

  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " << W << ' ' << H << "\" width=\""
    << W << "\" height=\"" << H
    << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" "
       "fill=\"white\"/>\n";
  if (!plot.title.empty()) {
    s << "<text x=\"" << W / 2 << "\" y=\"22\" text-anchor=\"middle\" font-size=\"14\">"
      << Report::escape(plot.title) << "</text>\n";
  }
  // Grid and ticks.
  for (double v : l.x_ticks) {
    const double x = px(v);
    s << "<line x1=\"" << num(x) << "\" y1=\"" << top << "\" x2=\"" << num(x) << "\" y2=\""
      << num(top + ph) << "\" stroke=\"#e4e4e4\"/>\n<text x=\"" << num(x) << "\" y=\""
      << num(top + ph + 16) << "\" text-anchor=\"middle\">" << tick_text(v) << "</text>\n";
  }
  for (double v : l.y_ticks) {
    const double y = py(v);
    s << "<line x1=\"" << left << "\" y1=\"" << num(y) << "\" x2=\"" << num(left + pw) << "\" y2=\""
      << num(y) << "\" stroke=\"#e4e4e4\"/>\n<text x=\"" << left - 6 << "\" y=\"" << num(y + 4)
      << "\" text-anchor=\"end\">" << tick_text(v) << "</text>\n";
  }
  s << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << num(pw) << "\" height=\""
    << num(ph) << "\" fill=\"none\" stroke=\"#444\"/>\n";
  s << "<text x=\"" << num(left + pw / 2) << "\" y=\"" << num(top + ph + 34)
    << "\" text-anchor=\"middle\">" << Report::escape(plot.x_title) << "</text>\n";
  s << "<text transform=\"translate(16 " << num(top + ph / 2)
    << ") rotate(-90)\" text-anchor=\"middle\">" << Report::escape(plot.y_title) << "</text>\n";
  // Series, clipped to the plot area.
  s << "<clipPath id=\"area\"><rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << num(pw)
    << "\" height=\"" << num(ph) << "\"/></clipPath>\n<g clip-path=\"url(#area)\">\n";
  for (const PlotSeries& ser : plot.series) {
    std::string pts;
    for (std::size_t i = 0; i < ser.x.size() && i < ser.y.size(); ++i) {
      if (!plot_layout::drawable(l, ser, i) || (plot.log_y && ser.y[i] <= 0)) continue;
      pts += num(px(ser.x[i])) + "," + num(py(ser.y[i])) + " ";
    }
    if (ser.line && !pts.empty()) {
      s << "<polyline fill=\"none\" stroke=\"" << ser.colour << "\" stroke-width=\"2\""
        << dash_attribute(ser) << " points=\"" << pts << "\"/>\n";
    }
    for (std::size_t i = 0; i < ser.x.size() && i < ser.y.size(); ++i) {
      if (!plot_layout::drawable(l, ser, i)) continue;
      if (ser.markers) {
        s << "<circle cx=\"" << num(px(ser.x[i])) << "\" cy=\"" << num(py(ser.y[i]))
          << "\" r=\"4\" fill=\"" << ser.colour << "\"/>\n";
      }
      if (i < ser.point_labels.size() && !ser.point_labels[i].empty()) {
        // Near the right edge the label goes to the left of its point, so it is not clipped.
        const double lx = px(ser.x[i]);
        const bool at_right = lx > left + pw - 8.0 * double(ser.point_labels[i].size()) - 8;
        s << "<text x=\"" << num(at_right ? lx - 6 : lx + 6) << "\" y=\"" << num(py(ser.y[i]) - 6)
          << "\" font-size=\"11\"" << (at_right ? " text-anchor=\"end\"" : "") << " fill=\""
          << ser.colour << "\">" << Report::escape(ser.point_labels[i]) << "</text>\n";
      }
    }
  }
  s << "</g>\n";
  // Legend: two columns under the axis title, or one column right of the axes.
  for (std::size_t i = 0; i < plot.series.size(); ++i) {
    const PlotSeries& ser = plot.series[i];
    double lx = 0, ly = 0;
    l.legend_entry(i, lx, ly);
    s << "<line x1=\"" << num(lx) << "\" y1=\"" << num(ly - 4) << "\" x2=\"" << num(lx + 24)
      << "\" y2=\"" << num(ly - 4) << "\" stroke=\"" << ser.colour << "\" stroke-width=\"2\""
      << dash_attribute(ser) << (ser.line ? "" : " opacity=\"0\"") << "/>\n";
    if (ser.markers) {
      s << "<circle cx=\"" << num(lx + 12) << "\" cy=\"" << num(ly - 4) << "\" r=\"4\" fill=\""
        << ser.colour << "\"/>\n";
    }
    s << "<text x=\"" << num(lx + 30) << "\" y=\"" << num(ly) << "\">" << Report::escape(ser.label)
      << "</text>\n";
  }
  s << "</svg>\n";
  return s.str();
}

std::string colour_bar_svg(metrics::ColourMap map, double min, double max, int ticks,
                           const std::string& title, int width) {
  // Room for the title (about 6.2 px a character at 11 px sans-serif).
  width = std::max(width, int(6.2 * double(title.size())) + 24);
  const int H = 58, bar_h = 14, pad = 12, top = 6;
  const double bw = width - 2 * pad;
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " << width << ' ' << H
    << "\" width=\"" << width << "\" height=\"" << H
    << "\" font-family=\"sans-serif\" font-size=\"11\">\n<defs><linearGradient id=\"cb\">";
  for (int i = 0; i <= 16; ++i) {
    std::uint8_t rgb[3];
    metrics::colour_map_rgb(map, float(i) / 16.0f, rgb);
    char c[8];
    std::snprintf(c, sizeof c, "#%02x%02x%02x", rgb[0], rgb[1], rgb[2]);
    s << "<stop offset=\"" << num(i * 6.25) << "%\" stop-color=\"" << c << "\"/>";
  }
  s << "</linearGradient></defs>\n<rect x=\"" << pad << "\" y=\"" << top << "\" width=\"" << num(bw)
    << "\" height=\"" << bar_h << "\" fill=\"url(#cb)\" stroke=\"#444\"/>\n";
  for (int i = 0; i < ticks; ++i) {
    const double t = ticks > 1 ? double(i) / (ticks - 1) : 0;
    const double x = pad + t * bw;
    s << "<line x1=\"" << num(x) << "\" y1=\"" << top + bar_h << "\" x2=\"" << num(x) << "\" y2=\""
      << top + bar_h + 4 << "\" stroke=\"#444\"/><text x=\"" << num(x) << "\" y=\""
      << top + bar_h + 16 << "\" text-anchor=\"middle\">" << tick_text(min + t * (max - min))
      << "</text>\n";
  }
  s << "<text x=\"" << width / 2 << "\" y=\"" << H - 4 << "\" text-anchor=\"middle\">"
    << Report::escape(title) << "</text>\n</svg>\n";
  return s.str();
}

std::string category_legend_svg(const std::vector<std::pair<std::string, std::string>>& entries,
                                const std::string& title) {
  const int cell = 64, H = 50;
  const int W = std::max(200, int(entries.size()) * cell + 16);
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " << W << ' ' << H << "\" width=\""
    << W << "\" height=\"" << H << "\" font-family=\"sans-serif\" font-size=\"11\">\n";
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const int x = 8 + int(i) * cell;
    s << "<rect x=\"" << x << "\" y=\"4\" width=\"18\" height=\"14\" fill=\"" << entries[i].second
      << "\" stroke=\"#444\"/><text x=\"" << x + 22 << "\" y=\"15\">"
      << Report::escape(entries[i].first) << "</text>\n";
  }
  s << "<text x=\"8\" y=\"40\">" << Report::escape(title) << "</text>\n</svg>\n";
  return s.str();
}

}  // namespace tessera::cli
