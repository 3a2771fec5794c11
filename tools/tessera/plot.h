// SVG plots for the report and the docs, drawn by tessera itself (no plotting library): line
// and scatter plots with linear or logarithmic axes, units in the axis titles and a legend, and
// colour bars for heatmaps and categorical maps.
#pragma once

#include <string>
#include <vector>

#include "tessera/metrics.h"

namespace tessera::cli {

/// One series of a plot.
struct PlotSeries {
  std::string label;
  std::vector<double> x, y;
  std::string colour = "#1f77b4";  ///< Any SVG colour.
  bool line = true;                ///< Join the points.
  bool markers = false;            ///< Draw a marker at each point.
  bool dashed = false;
  std::vector<std::string> point_labels;  ///< Optional text beside each point.
};

/// A plot: axes, series, legend.
struct Plot {
  std::string title;
  std::string x_title, y_title;  ///< With units, e.g. "time per image (ms)".
  bool log_x = false;
  bool log_y = false;  ///< Logarithmic y (set y_min > 0 and y_max, e.g. 1e-4 and 1).
  double x_min = 0, x_max = 0, y_min = 0, y_max = 0;  ///< Equal min and max: from the data.
  int width = 640, height = 400;
  std::vector<PlotSeries> series;
};

/// The plot as a standalone SVG document.
std::string plot_svg(const Plot& plot);

/// A horizontal colour bar for `map` from `min` to `max` with `ticks` labelled values and the
/// title (with units) below, e.g. "max abs channel difference (8-bit levels; saturates at 64)".
std::string colour_bar_svg(metrics::ColourMap map, double min, double max, int ticks,
                           const std::string& title, int width = 320);

/// A legend for a categorical map: one swatch per entry (colour as "#rrggbb"), in a row.
std::string category_legend_svg(const std::vector<std::pair<std::string, std::string>>& entries,
                                const std::string& title);

/// The colours of successive series (matplotlib's tab10).
const char* series_colour(std::size_t i);

}  // namespace tessera::cli
