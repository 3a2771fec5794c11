// The plot engine's raster output (plot.h): a plot's layout drawn into an image, lines walked in
// half-pixel steps, without text.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "plot.h"
#include "plot_layout.h"

namespace tessera::cli {

namespace {

struct Rgb {
  std::uint8_t v[3];
};

Rgb parse_rgb(const std::string& hex) {
  const unsigned v = unsigned(std::stoul(hex.substr(1), nullptr, 16));
  return {{std::uint8_t(v >> 16), std::uint8_t(v >> 8), std::uint8_t(v)}};
}

/// The lengths of an SVG stroke-dasharray ("6 4", "2,3"); empty = solid.
std::vector<double> parse_dash(const std::string& text) {
  std::vector<double> d;
  std::string item;
  for (char c : text + ",") {
    if (c == ',' || c == ' ') {
      if (!item.empty()) d.push_back(std::stod(item));
      item.clear();
    } else {
      item += c;
    }
  }
  return d;
}

class Canvas {
 public:
  Canvas(int w, int h) : img_(w, h) {
    std::fill(img_.pixels.begin(), img_.pixels.end(), std::uint8_t(255));
  }

  /// A `size` x `size` square with its top-left corner at (x, y), clipped to the image.
  void dot(int x, int y, const Rgb& c, int size) {
    for (int dy = 0; dy < size; ++dy) {
      for (int dx = 0; dx < size; ++dx) {
        const int xx = x + dx, yy = y + dy;
        if (xx < 0 || yy < 0 || xx >= img_.width || yy >= img_.height) continue;
        std::copy(c.v, c.v + 3, img_.at(xx, yy));
      }
    }
  }

  /// A line from (x0, y0) to (x1, y1) in half-pixel steps; `dash` alternates on/off lengths in
  /// pixels (empty = solid), its phase continuing across the segments of one polyline.
  void line(double x0, double y0, double x1, double y1, const Rgb& c, int size,
            const std::vector<double>& dash = {}, double* phase = nullptr) {
    const double len = std::hypot(x1 - x0, y1 - y0);
    const int steps = std::max(1, int(len * 2.0));
    double period = 0;
    for (double d : dash) period += d;
    const double start = phase ? *phase : 0;
    for (int i = 0; i <= steps; ++i) {
      const double t = double(i) / steps;
      bool on = true;
      if (period > 0) {
        double q = std::fmod(start + t * len, period);
        for (std::size_t k = 0; k < dash.size(); ++k) {
          if (q < dash[k]) {
            on = (k % 2) == 0;
            break;
          }
          q -= dash[k];
        }
      }
      if (on) {
        dot(int(std::lround(x0 + t * (x1 - x0))), int(std::lround(y0 + t * (y1 - y0))), c, size);
      }
    }
    if (phase) *phase += len;
  }

  /// A filled disc of radius `r` centred on (cx, cy).
  void disc(double cx, double cy, double r, const Rgb& c) {
    for (int y = int(std::floor(cy - r)); y <= int(std::ceil(cy + r)); ++y) {
      for (int x = int(std::floor(cx - r)); x <= int(std::ceil(cx + r)); ++x) {
        if ((x + 0.5 - cx) * (x + 0.5 - cx) + (y + 0.5 - cy) * (y + 0.5 - cy) <= r * r) {
          dot(x, y, c, 1);
        }
      }
    }
  }

  ImageRGBA8 take() { return std::move(img_); }

 private:
  ImageRGBA8 img_;
};

}  // namespace

ImageRGBA8 plot_png(const Plot& plot) {
  const plot_layout::Layout l = plot_layout::layout(plot);
  Canvas canvas(plot.width, plot.height);
  const Rgb grid = parse_rgb("#e4e4e4"), frame = parse_rgb("#444444");
  for (double v : l.x_ticks) canvas.line(l.px(v), l.top, l.px(v), l.top + l.ph, grid, 1);
  for (double v : l.y_ticks) canvas.line(l.left, l.py(v), l.left + l.pw, l.py(v), grid, 1);
  const double r = l.left + l.pw, b = l.top + l.ph;
  canvas.line(l.left, l.top, r, l.top, frame, 1);
  canvas.line(l.left, b, r, b, frame, 1);
  canvas.line(l.left, l.top, l.left, b, frame, 1);
  canvas.line(r, l.top, r, b, frame, 1);
  for (const PlotSeries& ser : plot.series) {
    const Rgb c = parse_rgb(ser.colour);
    const std::vector<double> dash = parse_dash(ser.dash);
    // The SVG's points: drawable, and above zero on a logarithmic y axis; lines are clipped to
    // the axes' box as the SVG's clip path does (points past it are left out).
    std::vector<std::pair<double, double>> pts;
    for (std::size_t i = 0; i < ser.x.size() && i < ser.y.size(); ++i) {
      if (!plot_layout::drawable(l, ser, i) || (plot.log_y && ser.y[i] <= 0)) continue;
      const double x = l.px(ser.x[i]), y = l.py(ser.y[i]);
      if (x < l.left - 0.5 || x > r + 0.5 || y < l.top - 0.5 || y > b + 0.5) continue;
      pts.emplace_back(x, y);
    }
    double phase = 0;
    for (std::size_t i = 1; ser.line && i < pts.size(); ++i) {
      canvas.line(pts[i - 1].first, pts[i - 1].second, pts[i].first, pts[i].second, c, 2, dash,
                  &phase);
    }
    if (ser.markers) {
      for (const auto& [x, y] : pts) canvas.disc(x, y, 4, c);
    }
  }
  for (std::size_t i = 0; i < plot.series.size(); ++i) {
    const PlotSeries& ser = plot.series[i];
    const Rgb c = parse_rgb(ser.colour);
    double lx = 0, ly = 0, phase = 0;
    l.legend_entry(i, lx, ly);
    if (ser.line) canvas.line(lx, ly - 4, lx + 24, ly - 4, c, 2, parse_dash(ser.dash), &phase);
    if (ser.markers) canvas.disc(lx + 12, ly - 4, 4, c);
  }
  ImageRGBA8 img = canvas.take();
  img.has_alpha = false;
  return img;
}

}  // namespace tessera::cli
