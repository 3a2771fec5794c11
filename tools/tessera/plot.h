// The one plot engine of the report, the docs and `tessera seams`, drawn by tessera itself (no
// plotting library): line and scatter plots with linear or logarithmic axes, units in the axis
// titles and a legend (below the axes or in a column beside them), as SVG or rasterised to a
// PNG image of the same layout; and colour bars for heatmaps and categorical maps.
#pragma once

#include <string>
#include <vector>

#include "tessera/core.h"
#include "tessera/metrics.h"

namespace tessera::cli {

/// One series of a plot.
struct PlotSeries {
  std::string label;
  std::vector<double> x, y;
  std::string colour = "#1f77b4";  ///< Any SVG colour.
  bool line = true;                ///< Join the points.
  bool markers = false;            ///< Draw a marker at each point.
  /// SVG stroke-dasharray of the line, lengths in pixels ("6 4", "2,3"); "" = solid.
  std::string dash;
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
  /// > 0: the legend is a column this wide (pixels) right of the axes; 0: two columns below.
  int legend_column = 0;
  std::vector<PlotSeries> series;
};

/// The plot as a standalone SVG document. On a logarithmic axis, points at or below zero are
/// left out; values below the axis minimum sit on it.
std::string plot_svg(const Plot& plot);

/// The same plot rasterised to an RGB PNG-ready image of `plot.width` x `plot.height`: same
/// axes, grid, colours (series colours must be "#rrggbb"), dash patterns and markers, and the
/// legend's swatches in the same order; no text (the SVG carries it). Pure code: no font or SVG
/// library needed.
ImageRGBA8 plot_png(const Plot& plot);

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
