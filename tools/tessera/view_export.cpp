// tessera view --html: one self-contained HTML file (page, script, style and every image as a
// data: URI) with the results of a fixed set of settings.
#include <cstdio>

#include "tessera/io.h"
#include "view.h"

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
constexpr const char* kViewScripts[] = {"view.js", "view_flow.js", "view_start.js"};

/// An encoded result's texture in the other containers too (`files`), for the page's downloads:
/// the server makes them on request, a static view has them inline.
void add_containers(nlohmann::json& result, BlobStore& blobs) {
  if (!result.contains("settings")) return;
  std::shared_ptr<const BlobStore::Blob> pvr = blobs.get(result["file"].get<std::string>());
  if (!pvr) return;
  result["files"] = {{"pvr", result["file"]}};
  for (const char* container : {"ktx", "ktx2"}) {
    Result<std::vector<std::uint8_t>> file = convert_texture(pvr->bytes, container);
    if (file) result["files"][container] = blobs.put("application/octet-stream", std::move(*file));
  }
}

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
                         const std::string& output) {
  BlobStore blobs;
  nlohmann::json data = {{"mode", "static"},
                         {"version", TESSERA_VERSION_STRING},
                         {"inputs", nlohmann::json::array()},
                         {"results", nlohmann::json::array()}};
  // The overview lists every input at these settings (the first of the set).
  data["overview_settings"] = settings_to_json(settings.empty() ? ViewSettings{} : settings[0]);
  const std::vector<std::pair<int, int>> pairs = texture_pairs(inputs);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const ViewInput& in = inputs[i];
    if (!in.error.empty()) return Status::error(ErrorCode::io_error, in.error);
    data["inputs"].push_back(input_json(in, int(i)));
    data["inputs"].back()["thumbnail"] = put_thumbnail(in, 96, threads, blobs);
    std::vector<Result<nlohmann::json>> made;
    if (in.is_texture) {
      made.push_back(texture_view_result(in, threads, blobs));
    } else {
      const bool alpha = data["inputs"].back().value("has_alpha", false);
      for (const ViewSettings& s : settings.empty() ? default_export_settings(alpha) : settings) {
        made.push_back(encode_view_result(in, s, threads, blobs, {}));
      }
      for (const auto& [t, im] : pairs) {
        if (im == int(i)) {
          made.push_back(texture_view_result(inputs[std::size_t(t)], threads, blobs, &in.image));
        }
      }
    }
    for (Result<nlohmann::json>& r : made) {
      if (!r) {
        Status s = r.status();
        if (s.message.rfind(in.name, 0) != 0 && s.message.rfind(in.path, 0) != 0) {
          s.message = in.path + ": " + s.message;
        }
        return s;
      }
      nlohmann::json j = std::move(r).value();
      j["input_index"] = int(i);
      add_containers(j, blobs);
      j["id"] = "r" + std::to_string(data["results"].size());
      data["results"].push_back(std::move(j));
    }
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
