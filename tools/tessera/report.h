// A small HTML report builder for `tessera demo`: sections of text, tables and image rows,
// with the images written as PNG files next to the page.
#pragma once

#include <string>
#include <vector>

#include "tessera/core.h"

namespace tessera::cli {

/// One image in a row of figures.
struct Figure {
  std::string path;     ///< Relative to the report folder.
  std::string caption;  ///< Plain text.
};

/// Copies the w x h rectangle at (x0, y0) of `img` (must lie inside it).
ImageRGBA8 crop(const ImageRGBA8& img, int x0, int y0, int w, int h);
/// printf-style formatting of one number ("%.2f", ...).
std::string fmt(const char* format, double value);

/// Accumulates an HTML page; `write` stores it atomically as DIR/report.html.
class Report {
 public:
  Report(std::string dir, std::string title);

  /// Writes `image` to DIR/img/NAME.png; on success sets `rel` to its relative path.
  Status save_image(const std::string& name, const ImageRGBA8& image, std::string& rel);
  /// Writes an SVG document to DIR/img/NAME.svg; on success sets `rel` to its relative path.
  Status save_svg(const std::string& name, const std::string& svg, std::string& rel);

  /// A section heading; `id` (optional) is its anchor for links (`#id`).
  void heading(const std::string& text, const std::string& id = "");
  /// Raw HTML shown first, right under the title (a summary written once the sections know
  /// their numbers).
  void top(const std::string& html) { top_ = html; }
  /// Raw HTML (callers escape what they insert; see `escape`).
  void html(const std::string& text);
  /// A paragraph of plain text; `code` spans (between backticks) become <code>.
  void paragraph(const std::string& text);
  void table(const std::vector<std::string>& header,
             const std::vector<std::vector<std::string>>& rows);
  /// A row of images shown at `zoom` times their size without smoothing.
  void figures(const std::vector<Figure>& figures, int zoom = 1);

  /// The page's footer line (plain text): version, date, command line, machine.
  void footer(const std::string& text) { footer_ = text; }

  /// Writes DIR/report.html (folder created if needed).
  Status write() const;
  const std::string& dir() const { return dir_; }

  static std::string escape(const std::string& text);

 private:
  std::string dir_;
  std::string title_;
  std::string top_;
  std::string body_;
  std::string footer_;
};

/// The footer every report carries: "tessera VERSION · DATE UTC · `COMMAND` · MACHINE".
std::string report_footer();

}  // namespace tessera::cli
