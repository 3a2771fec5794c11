// tessera view: inputs, settings, blobs, and the `tessera compress` command line of a result.

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "tessera/io.h"
#include "view.h"

namespace tessera::cli {

namespace {

namespace fs = std::filesystem;

bool has_extension(const fs::path& p, std::initializer_list<const char*> exts) {
  std::string e = p.extension().string();
  std::transform(e.begin(), e.end(), e.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return std::any_of(exts.begin(), exts.end(), [&](const char* x) { return e == x; });
}

bool viewable_name(const fs::path& p) {
  return has_extension(p, {".png", ".jpg", ".jpeg", ".tga", ".bmp", ".pvr", ".ktx", ".ktx2"});
}

ViewInput load_one(const std::string& path) {
  Result<std::vector<std::uint8_t>> bytes = io::read_file(path, std::uint64_t{1} << 30);
  if (!bytes) {
    ViewInput in;
    in.path = path;
    in.name = fs::path(path).filename().string();
    in.error = bytes.status().message;
    return in;
  }
  return view_input_from_bytes(path, fs::path(path).filename().string(), std::move(*bytes));
}

bool word_in(const std::string& w, std::initializer_list<const char*> words) {
  return std::any_of(words.begin(), words.end(), [&](const char* x) { return w == x; });
}

/// True when `s` is valid UTF-8 (no overlong forms, surrogates or values past U+10FFFF).
bool valid_utf8(const std::string& s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    const int n = c < 0x80 ? 0 : (c >> 5) == 6 ? 1 : (c >> 4) == 14 ? 2 : (c >> 3) == 30 ? 3 : -1;
    if (n < 0) return false;
    std::uint32_t cp = n == 0 ? c : c & (0x3f >> n);
    for (int k = 1; k <= n; ++k) {
      if (i + std::size_t(k) >= s.size()) return false;
      const auto d = static_cast<unsigned char>(s[i + std::size_t(k)]);
      if ((d >> 6) != 2) return false;
      cp = (cp << 6) | (d & 0x3f);
    }
    static constexpr std::uint32_t kMin[] = {0, 0x80, 0x800, 0x10000};
    if (cp < kMin[n] || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff)) return false;
    i += std::size_t(n) + 1;
  }
  return true;
}

std::string quoted(const std::string& word) {
  if (word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"
                             "._-/+=:,@") == std::string::npos &&
      !word.empty()) {
    return word;
  }
  if (!valid_utf8(word)) {
    // Bytes that are not text (a file name in another encoding): the shell's $'...' with \xHH
    // for them, so that the command names the same bytes and stays ASCII on the page.
    std::string q = "$'";
    for (char c : word) {
      const auto u = static_cast<unsigned char>(c);
      if (c == '\'' || c == '\\') {
        q += '\\';
        q += c;
      } else if (u < 0x20 || u >= 0x7f) {
        char hex[8];
        std::snprintf(hex, sizeof hex, "\\x%02x", u);
        q += hex;
      } else {
        q += c;
      }
    }
    return q + "'";
  }
  std::string q = "'";
  for (char c : word) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace

ViewInput view_input_from_bytes(const std::string& path, const std::string& name,
                                std::vector<std::uint8_t> bytes) {
  ViewInput in;
  in.path = path;
  in.name = name;
  if (texture_file::detect_container(bytes) != texture_file::ContainerFormat::unknown) {
    in.is_texture = true;
    Result<texture_file::CompressedTexture> t = texture_file::parse_texture(bytes, path);
    if (!t) {
      in.error = t.status().message;
    } else {
      in.texture = std::move(t).value();
      in.file = std::move(bytes);
    }
    return in;
  }
  Result<ImageRGBA8> im = io::decode_image(bytes, path);
  if (!im) {
    in.error = im.status().message;
  } else {
    in.image = std::move(im).value();
  }
  return in;
}

Result<ViewSettings> settings_from_json(const nlohmann::json& j) {
  if (!j.is_object()) return Status::error(ErrorCode::invalid_argument, "settings: not an object");
  ViewSettings s;
  auto bad = [](const std::string& m) { return Status::error(ErrorCode::invalid_argument, m); };
  try {
    s.format = j.value("format", s.format);
    s.quality = j.value("quality", s.quality);
    s.alpha_bleed = j.value("alpha_bleed", false);
    s.alpha_weighted = j.value("alpha_weighted", false);
    s.premultiply = j.value("premultiply", false);
    s.normal_map = j.value("normal_map", false);
    s.srgb = j.value("srgb", false);
    s.mip_levels = j.value("mip_levels", 0);
    s.mip_filter = j.value("mip_filter", s.mip_filter);
    s.resize_pot = j.value("resize_pot", false);
    s.label = j.value("label", std::string());
  } catch (const nlohmann::json::exception&) {
    return bad("settings: a value has the wrong type");
  }
  if (!word_in(s.format, {"pvrtc1-4", "pvrtc1-2"})) return bad("format: '" + s.format + "'");
  if (!word_in(s.quality, {"fast", "normal", "high"})) return bad("quality: '" + s.quality + "'");
  if (!word_in(s.mip_filter, {"box", "lanczos", "kaiser"})) {
    return bad("mip_filter: '" + s.mip_filter + "'");
  }
  if (s.mip_levels < 0 || s.mip_levels > 17) return bad("mip_levels: out of range (0 to 17)");
  if (s.label.size() > 80) return bad("label: longer than 80 characters");
  CompressArgs args = compress_args(s, "in", "out.pvr");
  if (std::string p = compress_usage_problem(args, "pvr"); !p.empty()) return bad(p);
  return s;
}

nlohmann::json settings_to_json(const ViewSettings& s) {
  return {{"format", s.format},
          {"quality", s.quality},
          {"alpha_bleed", s.alpha_bleed},
          {"alpha_weighted", s.alpha_weighted},
          {"premultiply", s.premultiply},
          {"normal_map", s.normal_map},
          {"srgb", s.srgb},
          {"mip_levels", s.mip_levels},
          {"mip_filter", s.mip_filter},
          {"resize_pot", s.resize_pot},
          {"label", s.label}};
}

CompressArgs compress_args(const ViewSettings& s, const std::string& input,
                           const std::string& output) {
  return compress_args(s, std::vector<std::string>{input}, output, {});
}

CompressArgs compress_args(const ViewSettings& s, const std::vector<std::string>& inputs,
                           const std::string& output, texture_file::TextureShape shape) {
  CompressArgs a;
  a.inputs = inputs;
  a.output = output;
  a.words.cube = shape.faces == 6;
  a.words.array = shape.array;
  a.words.format = s.format;
  a.words.quality = s.quality;
  a.words.alpha_bleed = s.alpha_bleed;
  a.words.alpha_weighted = s.alpha_weighted;
  a.words.premultiply = s.premultiply;
  a.words.normal_map = s.normal_map;
  a.words.srgb = s.srgb;
  a.words.resize_pot = s.resize_pot;
  a.words.mip_levels = s.mip_levels;
  a.words.mipmaps = s.mip_levels > 0;
  // --mip-filter only means something with a chain (compress refuses it otherwise).
  a.words.mip_filter = s.mip_levels > 0 ? s.mip_filter : "box";
  return a;
}

std::string compress_command(const ViewSettings& s, const std::string& input,
                             const std::string& output) {
  return compress_command(s, std::vector<std::string>{input}, output, {});
}

std::string compress_command(const ViewSettings& s, const std::vector<std::string>& inputs,
                             const std::string& output, texture_file::TextureShape shape) {
  std::string c = "tessera compress";
  if (shape.faces == 6) c += " --cube";
  if (shape.array) c += " --array";
  for (const std::string& input : inputs) c += " " + quoted(input);
  c += " -o " + quoted(output);
  if (s.format != "pvrtc1-4") c += " --format " + s.format;
  if (s.quality != "normal") c += " --quality " + s.quality;
  if (s.mip_levels > 0) c += " --mip-levels " + std::to_string(s.mip_levels);
  if (s.mip_levels > 0 && s.mip_filter != "box") c += " --mip-filter " + s.mip_filter;
  if (s.srgb) c += " --srgb";
  if (s.premultiply) c += " --premultiply";
  if (s.alpha_bleed) c += " --alpha-bleed";
  if (s.alpha_weighted) c += " --alpha-weighted";
  if (s.normal_map) c += " --normal-map";
  if (s.resize_pot) c += " --resize-pot";
  return c;
}

std::string BlobStore::put(std::string mime, std::vector<std::uint8_t> bytes) {
  // FNV-1a over the MIME type, then over the bytes 8 at a time (a texel image is tens of MB).
  std::uint64_t h = 1469598103934665603ull;
  for (char c : mime) h = (h ^ std::uint8_t(c)) * 1099511628211ull;
  std::size_t i = 0;
  for (; i + 8 <= bytes.size(); i += 8) {
    std::uint64_t w;
    std::memcpy(&w, &bytes[i], 8);
    h = (h ^ w) * 1099511628211ull;
    h ^= h >> 29;
  }
  for (; i < bytes.size(); ++i) h = (h ^ bytes[i]) * 1099511628211ull;
  h = (h ^ bytes.size()) * 1099511628211ull;
  char key[17];
  std::snprintf(key, sizeof key, "%016llx", static_cast<unsigned long long>(h));
  std::lock_guard<std::mutex> lock(mutex_);
  auto& slot = blobs_[key];
  if (!slot) {
    bytes_ += bytes.size();
    slot = std::make_shared<const Blob>(Blob{std::move(mime), std::move(bytes)});
  }
  return key;
}

std::string BlobStore::put_lazy(std::string key, std::string mime,
                                std::function<std::vector<std::uint8_t>()> make) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (blobs_.count(key) || lazy_.count(key)) return key;
  auto l = std::make_shared<Lazy>();
  l->mime = std::move(mime);
  l->make = std::move(make);
  lazy_[key] = std::move(l);
  return key;
}

std::shared_ptr<const BlobStore::Blob> BlobStore::get(const std::string& key) const {
  std::shared_ptr<Lazy> l;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (auto it = blobs_.find(key); it != blobs_.end()) return it->second;
    auto it = lazy_.find(key);
    if (it == lazy_.end()) return nullptr;
    l = it->second;
  }
  // Made outside the lock (other blobs are served meanwhile), once however many ask.
  std::call_once(l->once, [&] {
    l->blob = std::make_shared<const Blob>(Blob{l->mime, l->make()});
    l->make = nullptr;  // frees what it captured
  });
  std::lock_guard<std::mutex> lock(mutex_);
  if (auto it = lazy_.find(key); it != lazy_.end() && it->second == l) {
    bytes_ += l->blob->bytes.size();
    blobs_[key] = l->blob;
    lazy_.erase(it);
  }
  return l->blob;
}

bool BlobStore::has(const std::string& key) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return blobs_.count(key) || lazy_.count(key);
}

void BlobStore::erase(const std::string& key) {
  std::lock_guard<std::mutex> lock(mutex_);
  lazy_.erase(key);
  auto it = blobs_.find(key);
  if (it == blobs_.end()) return;
  bytes_ -= it->second->bytes.size();
  blobs_.erase(it);
}

std::size_t BlobStore::bytes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return bytes_;
}

std::vector<std::string> BlobStore::keys() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<std::string> k;
  for (const auto& [key, blob] : blobs_) k.push_back(key);
  for (const auto& [key, blob] : lazy_) k.push_back(key);
  std::sort(k.begin(), k.end());
  return k;
}

std::vector<ViewInput> load_view_inputs(const std::vector<std::string>& paths) {
  std::vector<ViewInput> out;
  for (const std::string& p : paths) {
    std::error_code ec;
    if (fs::is_directory(p, ec)) {
      // A folder's files, by their real paths: a link that resolves outside the folder is
      // refused (a folder given to view shares what is in it, not what its links point to).
      const fs::path root = fs::weakly_canonical(p, ec);
      std::vector<std::string> files;
      for (const fs::directory_entry& e : fs::directory_iterator(p, ec)) {
        std::error_code fec;
        if (!e.is_regular_file(fec) || !viewable_name(e.path())) continue;
        if (e.is_symlink(fec)) {
          const fs::path target = fs::weakly_canonical(e.path(), fec);
          const fs::path rel = fec ? fs::path("..") : target.lexically_relative(root);
          if (rel.empty() || *rel.begin() == ".." || rel.is_absolute()) {
            std::fprintf(stderr, "tessera: view: %s: a link out of the folder (to %s): skipped\n",
                         e.path().c_str(), target.c_str());
            continue;
          }
        }
        files.push_back(e.path().string());
      }
      std::sort(files.begin(), files.end());
      if (files.empty()) {
        ViewInput none;
        none.path = p;
        none.name = p;
        none.error = p + ": no images or textures in this folder";
        out.push_back(std::move(none));
      }
      for (const std::string& f : files) out.push_back(load_one(f));
    } else {
      out.push_back(load_one(p));
    }
  }
  return out;
}

std::string dump_json(const nlohmann::json& j) {
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::vector<std::pair<int, int>> texture_pairs(const std::vector<ViewInput>& inputs) {
  std::vector<std::pair<int, int>> pairs;
  for (std::size_t t = 0; t < inputs.size(); ++t) {
    const ViewInput& tex = inputs[t];
    if (!tex.is_texture || !tex.error.empty()) continue;
    const texture_file::CompressedTexture& x = tex.texture;
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      const ViewInput& im = inputs[i];
      const std::size_t count = im.images.empty() ? 1 : im.images.size();
      const int faces = im.images.empty() ? 1 : im.shape.faces;
      if (im.is_texture || !im.error.empty() || int(count) != x.image_count() || faces != x.faces ||
          fs::path(view_output_name(im)).stem() != fs::path(tex.name).stem() ||
          im.image.width != x.width || im.image.height != x.height) {
        continue;
      }
      pairs.emplace_back(int(t), int(i));
      break;
    }
  }
  return pairs;
}

nlohmann::json input_json(const ViewInput& input, int index) {
  nlohmann::json j = {{"index", index},
                      {"name", input.name},
                      {"path", input.path},
                      {"kind", input.is_texture ? "texture" : "image"}};
  if (!input.error.empty()) {
    j["error"] = input.error;
  } else if (input.is_texture) {
    j["width"] = input.texture.width;
    j["height"] = input.texture.height;
    j["has_alpha"] = input.texture.has_alpha;
  } else {
    j["width"] = input.image.width;
    j["height"] = input.image.height;
    j["has_alpha"] = input.image.has_alpha && !all_opaque(ImageView8::of(input.image));
    add_group_json(j, input);
  }
  return j;
}

std::vector<ViewSettings> default_export_settings(bool has_alpha, bool resize_pot) {
  std::vector<ViewSettings> v;
  for (const char* q : {"fast", "normal", "high"}) {
    ViewSettings s;
    s.quality = q;
    v.push_back(s);
  }
  if (has_alpha) {
    ViewSettings bleed;
    bleed.alpha_bleed = true;
    v.push_back(bleed);
    ViewSettings weighted;
    weighted.alpha_weighted = true;
    v.push_back(weighted);
  }
  for (ViewSettings& s : v) s.resize_pot = resize_pot;
  return v;
}

}  // namespace tessera::cli
