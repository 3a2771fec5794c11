// Internal to the plot engine (plot.cpp: SVG, plot_png.cpp: PNG): where a plot's axes, ticks and
// legend go, computed once so that both outputs of one plot have the same geometry.
#pragma once

#include <cstddef>
#include <vector>

#include "plot.h"

namespace tessera::cli::plot_layout {

/// The axes' box in pixels and the data-to-pixel mapping of one plot.
struct Layout {
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;  ///< Axis ranges (data units).
  bool log_x = false, log_y = false;
  int left = 0, top = 0;                 ///< Top-left corner of the axes' box.
  double pw = 0, ph = 0;                 ///< Size of the axes' box.
  std::vector<double> x_ticks, y_ticks;  ///< Tick values inside the ranges.

  /// Pixel column of data x.
  double px(double x) const;
  /// Pixel row of data y (values below y0 on a log axis sit on the axis).
  double py(double y) const;
  /// Where legend entry `i` goes: its swatch is the line (lx, ly - 4) to (lx + 24, ly - 4),
  /// its text starts at (lx + 30, ly).
  void legend_entry(std::size_t i, double& lx, double& ly) const;

  int legend_column = 0;  ///< As Plot::legend_column.
};

/// The layout of `plot` (ranges from the data where the plot leaves them open).
Layout layout(const Plot& plot);

/// True when point `i` of `series` can be drawn on these axes: both coordinates finite and, on
/// a logarithmic x axis, x > 0.
bool drawable(const Layout& l, const PlotSeries& series, std::size_t i);

}  // namespace tessera::cli::plot_layout
