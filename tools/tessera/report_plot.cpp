// CDF plots of the seam experiment: SVG and the same plot rasterised to PNG.
#include "report_plot.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "tessera/experiments.h"

namespace tessera::cli {

namespace {
constexpr double kStep = experiments::kSeamsCdfStep;
}  // namespace

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
    s << "<polyline fill=\"none\" stroke=\"" << curves[c].colour << "\" stroke-width=\"1.6\"";
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
      << ly << "\" stroke=\"" << curves[c].colour << "\" stroke-width=\"2\"";
    if (!curves[c].dash.empty()) s << " stroke-dasharray=\"" << curves[c].dash << "\"";
    s << "/><text x=\"" << L + pw + 46 << "\" y=\"" << ly + 4 << "\">" << curves[c].label
      << "</text>\n";
  }
  s << "</svg>\n";
  return s.str();
}

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
      if (on)
        dot(int(std::lround(x0 + t * (x1 - x0))), int(std::lround(y0 + t * (y1 - y0))), rgb, size);
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
    parse_rgb(curves[c].colour, rgb);
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

}  // namespace tessera::cli
