#include "report.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <thread>

#include "cli.h"
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

Report::Report(std::string dir, std::string title)
    : dir_(std::move(dir)), title_(std::move(title)) {}

std::string Report::escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

Status Report::save_image(const std::string& name, const ImageRGBA8& image, std::string& rel) {
  std::error_code ec;
  fs::create_directories(fs::path(dir_) / "img", ec);
  if (ec) return Status::error(ErrorCode::io_error, dir_ + "/img: cannot create: " + ec.message());
  rel = "img/" + name + ".png";
  return io::write_png((fs::path(dir_) / rel).string(), image);
}

void Report::heading(const std::string& text, const std::string& id) {
  body_ += (id.empty() ? std::string("<h2>") : "<h2 id=\"" + escape(id) + "\">") + escape(text) +
           "</h2>\n";
}
void Report::html(const std::string& text) { body_ += text + "\n"; }
namespace {
/// Escaped text with `code` spans as <code> elements (an odd backtick stays as it is).
std::string inline_markup(const std::string& text) {
  std::string out;
  std::size_t i = 0;
  while (i < text.size()) {
    const std::size_t open = text.find('`', i);
    const std::size_t close = open == std::string::npos ? open : text.find('`', open + 1);
    if (close == std::string::npos) {
      out += Report::escape(text.substr(i));
      break;
    }
    out += Report::escape(text.substr(i, open - i)) + "<code>" +
           Report::escape(text.substr(open + 1, close - open - 1)) + "</code>";
    i = close + 1;
  }
  return out;
}
}  // namespace

void Report::paragraph(const std::string& text) { body_ += "<p>" + inline_markup(text) + "</p>\n"; }

Status Report::save_svg(const std::string& name, const std::string& svg, std::string& rel) {
  std::error_code ec;
  fs::create_directories(fs::path(dir_) / "img", ec);
  if (ec) return Status::error(ErrorCode::io_error, dir_ + "/img: cannot create: " + ec.message());
  rel = "img/" + name + ".svg";
  return io::write_file_atomic((fs::path(dir_) / rel).string(),
                               {reinterpret_cast<const std::uint8_t*>(svg.data()), svg.size()});
}

void Report::table(const std::vector<std::string>& header,
                   const std::vector<std::vector<std::string>>& rows) {
  body_ += "<div class=\"scroll\"><table><tr>";
  for (const auto& h : header) body_ += "<th>" + escape(h) + "</th>";
  body_ += "</tr>\n";
  for (const auto& row : rows) {
    body_ += "<tr>";
    for (const auto& cell : row) body_ += "<td>" + escape(cell) + "</td>";
    body_ += "</tr>\n";
  }
  body_ += "</table></div>\n";
}

void Report::figures(const std::vector<Figure>& figures, int zoom) {
  body_ += "<div class=\"row\">";
  for (const Figure& f : figures) {
    const bool svg = f.path.size() > 4 && f.path.compare(f.path.size() - 4, 4, ".svg") == 0;
    body_ +=
        "<figure><img src=\"" + escape(f.path) + "\"" +
        (svg ? std::string(" class=\"plot\"") : " style=\"zoom:" + std::to_string(zoom) + "\"") +
        " alt=\"" + escape(f.caption) + "\"><figcaption>" + inline_markup(f.caption) +
        "</figcaption></figure>";
  }
  body_ += "</div>\n";
}

Status Report::write() const {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) return Status::error(ErrorCode::io_error, dir_ + ": cannot create: " + ec.message());
  const std::string page =
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"><title>" +
      escape(title_) +
      "</title>\n<style>body{font-family:system-ui,sans-serif;max-width:1100px;"
      "margin:1.5em auto;padding:0 1em;color:#222;line-height:1.45}"
      "img{image-rendering:pixelated;border:1px solid #ccc;max-width:100%}"
      "img.plot{image-rendering:auto;border:none;width:640px;height:auto}"
      "figure{display:inline-block;margin:0 1em 1em 0;vertical-align:top;max-width:100%}"
      "figcaption{font-size:85%;max-width:320px}div.scroll{overflow-x:auto}"
      "table{border-collapse:collapse;margin:1em 0}"
      "td,th{border:1px solid #bbb;padding:3px 8px;text-align:right}"
      "th{background:#eee}code{background:#f4f4f4;padding:0 2px}"
      "footer{margin-top:3em;padding-top:1em;border-top:1px solid #ccc;font-size:85%;"
      "color:#555}</style></head>\n<body>\n<h1>" +
      escape(title_) + "</h1>\n" + top_ + body_ +
      (footer_.empty() ? std::string() : "<footer>" + inline_markup(footer_) + "</footer>\n") +
      "</body></html>\n";
  const std::string path = (fs::path(dir_) / "report.html").string();
  return io::write_file_atomic(path,
                               {reinterpret_cast<const std::uint8_t*>(page.data()), page.size()});
}

std::string report_footer() {
  std::string cpu = "unknown CPU";
  if (std::FILE* f = std::fopen("/proc/cpuinfo", "r")) {
    char line[512];
    while (std::fgets(line, sizeof line, f)) {
      if (std::strncmp(line, "model name", 10) == 0) {
        if (const char* colon = std::strchr(line, ':')) {
          cpu = colon + 1;
          while (!cpu.empty() && (cpu.front() == ' ' || cpu.front() == '\t')) cpu.erase(0, 1);
          while (!cpu.empty() && (cpu.back() == '\n' || cpu.back() == ' ')) cpu.pop_back();
        }
        break;
      }
    }
    std::fclose(f);
  }
  char date[64];
  const std::time_t now = std::time(nullptr);
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  return "tessera " TESSERA_VERSION_STRING " · " + std::string(date) + " · `" + command_line() +
         "` · " + cpu + ", " + std::to_string(std::thread::hardware_concurrency()) +
         " hardware threads";
}

}  // namespace tessera::cli
