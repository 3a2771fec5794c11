// tessera view --html: one self-contained HTML file (page, script, style and every image as a
// data: URI) with the results of a fixed set of settings.
#include <algorithm>
#include <cstdio>

#include "tessera/io.h"
#include "view.h"
#include "view_png.h"

namespace tessera::cli {

namespace {

std::string base64(const std::vector<std::uint8_t>& bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t v =
        (std::uint32_t(bytes[i]) << 16) | (std::uint32_t(bytes[i + 1]) << 8) | bytes[i + 2];
    for (int s = 18; s >= 0; s -= 6) out += kAlphabet[(v >> s) & 63];
  }
  if (i < bytes.size()) {
    std::uint32_t v = std::uint32_t(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= std::uint32_t(bytes[i + 1]) << 8;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

/// The page's scripts (share/tessera/view/), in order: one <script>, one scope (an arrow
/// function's), so their top-level names are shared and none is global. view_start.js is last.
constexpr const char* kViewScripts[] = {
    "view.js",      "view_png.js",  "view_pvrtc.js", "view_tiles.js", "view_heatmap.js",
    "view_keys.js", "view_cube.js", "view_flow.js",  "view_first.js", "view_start.js"};

void replace_once(std::string& text, const std::string& marker, std::string_view with) {
  const std::size_t at = text.find(marker);
  if (at != std::string::npos) text.replace(at, marker.size(), with);
}

}  // namespace

std::string view_page(const nlohmann::json& data) {
  std::string page(view_asset("view.html"));
  // Inside <script>, "</script" would end the element and "<!--" change how it is parsed: every
  // "<" (only ever inside a JSON string) is written as the same string's "\u003c".
  std::string json;
  for (char c : dump_json(data)) {
    if (c == '<') {
      json += "\\u003c";
    } else {
      json += c;
    }
  }
  replace_once(page, "/*TESSERA_VIEW_CSS*/", view_asset("view.css"));
  replace_once(page, "/*TESSERA_VIEW_DATA*/", json);
  std::string script = "(() => {\n";
  for (const char* name : kViewScripts) script.append(view_asset(name)).append("\n");
  script += "})();";
  replace_once(page, "/*TESSERA_VIEW_JS*/", script);
  return page;
}

Status write_view_export(const std::vector<ViewInput>& inputs,
                         const std::vector<ViewSettings>& settings, int threads,
                         const std::string& output, std::vector<std::string>* errors,
                         bool resize_pot) {
  BlobStore blobs;
  blobs.png_level = kPngLevelSmall;  // written once, kept and sent around: small over fast
  nlohmann::json data = {{"mode", "static"},
                         {"version", TESSERA_VERSION_STRING},
                         {"inputs", nlohmann::json::array()},
                         {"results", nlohmann::json::array()}};
  // The overview lists every input at these settings (the first of the set).
  data["overview_settings"] = settings_to_json(settings.empty() ? ViewSettings{} : settings[0]);
  const std::vector<std::pair<int, int>> pairs = texture_pairs(inputs);
  std::string first_error;
  int working = 0;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const ViewInput& in = inputs[i];
    data["inputs"].push_back(input_json(in, int(i)));
    nlohmann::json& ij = data["inputs"].back();
    ij["thumbnail"] = put_thumbnail(in, 96, threads, blobs);
    // One bad input (unreadable, or an encode that fails) shows its one-line error on the page
    // and in `errors`; the others go on.
    auto bad = [&](std::string message) {
      if (message.rfind(in.name, 0) != 0 && message.rfind(in.path, 0) != 0) {
        message = in.path + ": " + message;
      }
      if (!ij.contains("error")) ij["error"] = message;
      if (errors) errors->push_back(message);
      if (first_error.empty()) first_error = message;
    };
    if (!in.error.empty()) {
      bad(in.error);
      continue;
    }
    std::vector<Result<nlohmann::json>> made;
    if (in.is_texture) {
      made.push_back(texture_view_result(in, threads, blobs));
    } else if (needs_resize_pot(in) && !resize_pot &&
               std::none_of(settings.begin(), settings.end(),
                            [](const ViewSettings& s) { return s.resize_pot; })) {
      // Not a power of two: the original with its note (the fix: --resize-pot).
      add_originals(ij, in, blobs);
      if (errors) errors->push_back(in.path + ": " + ij.value("note", std::string()));
      ++working;
      continue;
    } else {
      const bool alpha = ij.value("has_alpha", false);
      for (const ViewSettings& s :
           settings.empty() ? default_export_settings(alpha, resize_pot) : settings) {
        made.push_back(encode_view_result(in, s, threads, blobs, {}));
      }
      for (const auto& [t, im] : pairs) {
        if (im == int(i)) {
          made.push_back(
              texture_view_result(inputs[std::size_t(t)], threads, blobs, pair_references(in)));
        }
      }
    }
    bool any = false;
    for (Result<nlohmann::json>& r : made) {
      if (!r) {
        bad(r.status().message);
        continue;
      }
      nlohmann::json j = std::move(r).value();
      j["input_index"] = int(i);
      j["id"] = "r" + std::to_string(data["results"].size());
      data["results"].push_back(std::move(j));
      any = true;
    }
    if (any) {
      ++working;
      if (ij.contains("error")) ij["note"] = ij["error"];  // some settings failed: a note
      ij.erase("error");
    }
  }
  if (working == 0 && !first_error.empty()) {
    return Status::error(ErrorCode::io_error, first_error);
  }
  nlohmann::json uris = nlohmann::json::object();
  for (const std::string& key : blobs.keys()) {
    std::shared_ptr<const BlobStore::Blob> b = blobs.get(key);
    uris[key] = "data:" + b->mime + ";base64," + base64(b->bytes);
  }
  data["blobs"] = std::move(uris);
  const std::string page = view_page(data);
  return io::write_file_atomic(
      output, std::span(reinterpret_cast<const std::uint8_t*>(page.data()), page.size()));
}

}  // namespace tessera::cli
