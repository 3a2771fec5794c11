// CDF plots of the seam experiment (Toth 2013, Figure 5): log-y "fraction of pixels with error
// >= x" curves as SVG (with a labelled legend) and as a PNG raster of the same plot.
#pragma once

#include <string>
#include <vector>

#include "tessera/core.h"

namespace tessera::cli {

/// One curve: y[i] is the fraction at threshold i * experiments::kSeamsCdfStep.
struct Curve {
  std::string label;
  std::string colour;  ///< "#rrggbb".
  std::string dash;    ///< SVG stroke-dasharray ("" = solid).
  std::vector<double> y;
};

/// A log-y CDF plot: x = 2-norm threshold (linear, 0..xmax), y = fraction >= x (1e-4..1).
std::string cdf_svg(const std::string& title, const std::vector<Curve>& curves, double xmax);

/// The same plot as `cdf_svg`, rasterised to a PNG image (same axes, grid, colours and dash
/// patterns; the legend swatches are in the same order as the SVG's labelled legend, which
/// carries the text). Pure code: no font or SVG library needed.
ImageRGBA8 cdf_png(const std::vector<Curve>& curves, double xmax);

}  // namespace tessera::cli
