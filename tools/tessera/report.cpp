#include "report.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "tessera/io.h"

namespace tessera::cli {

namespace fs = std::filesystem;

ImageRGBA8 crop(const ImageRGBA8& img, int x0, int y0, int w, int h) {
  ImageRGBA8 out(w, h);
  out.has_alpha = img.has_alpha;
  for (int y = 0; y < h; ++y) {
    const std::uint8_t* s = img.at(x0, y0 + y);
    std::copy(s, s + std::size_t(w) * 4, out.at(0, y));
  }
  return out;
}

std::string fmt(const char* format, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, value);
  return buf;
}

Report::Report(std::string dir, std::string title) : dir_(std::move(dir)), title_(std::move(title)) {}

std::string Report::escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

Status Report::save_image(const std::string& name, const ImageRGBA8& image, std::string& rel) {
  std::error_code ec;
  fs::create_directories(fs::path(dir_) / "img", ec);
  if (ec) return Status::error(ErrorCode::io_error, dir_ + "/img: cannot create: " + ec.message());
  rel = "img/" + name + ".png";
  return write_png((fs::path(dir_) / rel).string(), image);
}

void Report::heading(const std::string& text) { body_ += "<h2>" + escape(text) + "</h2>\n"; }
void Report::html(const std::string& text) { body_ += text + "\n"; }
void Report::paragraph(const std::string& text) { body_ += "<p>" + escape(text) + "</p>\n"; }

void Report::table(const std::vector<std::string>& header,
                   const std::vector<std::vector<std::string>>& rows) {
  body_ += "<table><tr>";
  for (const auto& h : header) body_ += "<th>" + escape(h) + "</th>";
  body_ += "</tr>\n";
  for (const auto& row : rows) {
    body_ += "<tr>";
    for (const auto& cell : row) body_ += "<td>" + escape(cell) + "</td>";
    body_ += "</tr>\n";
  }
  body_ += "</table>\n";
}

void Report::figures(const std::vector<Figure>& figures, int zoom) {
  body_ += "<div class=\"row\">";
  for (const Figure& f : figures) {
    body_ += "<figure><img src=\"" + escape(f.path) + "\" style=\"zoom:" + std::to_string(zoom) +
             "\"><figcaption>" + escape(f.caption) + "</figcaption></figure>";
  }
  body_ += "</div>\n";
}

Status Report::write() const {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) return Status::error(ErrorCode::io_error, dir_ + ": cannot create: " + ec.message());
  const std::string page =
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" +
      escape(title_) +
      "</title>\n<style>body{font-family:sans-serif;max-width:1200px;margin:2em auto;"
      "color:#222}img{image-rendering:pixelated;border:1px solid #ccc}"
      "figure{display:inline-block;margin:0 1em 1em 0;vertical-align:top}"
      "figcaption{font-size:85%;max-width:300px}table{border-collapse:collapse;margin:1em 0}"
      "td,th{border:1px solid #bbb;padding:3px 8px;text-align:right}"
      "th{background:#eee}code{background:#f4f4f4}</style></head>\n<body>\n<h1>" +
      escape(title_) + "</h1>\n" + body_ + "</body></html>\n";
  const std::string path = (fs::path(dir_) / "report.html").string();
  return write_file_atomic(
      path, {reinterpret_cast<const std::uint8_t*>(page.data()), page.size()});
}

}  // namespace tessera::cli
