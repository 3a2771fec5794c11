// The shader binary of vk::AdaptiveSupersampler (shader_binary.h).
#include "vk/shader_binary.h"

#include <cstdio>
#include <cstring>

namespace tessera::vk {

namespace {

constexpr char kMagic[4] = {'T', 'S', 'A', 'S'};
constexpr std::uint32_t kFormat = 2;
// Part of the key: a binary from another tessera is refused even when its GLSL is the same.
constexpr const char* kVersion = "tessera 0.1.0 shader binary 1";

void fnv(std::uint64_t& h, const void* data, std::size_t n) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i) {
    h ^= p[i];
    h *= 1099511628211ull;
  }
}

template <class T>
void put(std::vector<std::uint8_t>& out, T v) {
  const std::size_t at = out.size();
  out.resize(at + sizeof v);
  std::memcpy(out.data() + at, &v, sizeof v);
}

std::string hex(std::uint64_t v) {
  char b[24];
  std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(v));
  return b;
}

/// Bounds-checked reads of the binary.
class Reader {
 public:
  explicit Reader(const std::vector<std::uint8_t>& b) : b_(b) {}
  template <class T>
  bool get(T& v) {
    if (b_.size() - at_ < sizeof v) return false;
    std::memcpy(&v, b_.data() + at_, sizeof v);
    at_ += sizeof v;
    return true;
  }
  bool bytes(void* to, std::size_t n) {
    if (b_.size() - at_ < n) return false;
    std::memcpy(to, b_.data() + at_, n);
    at_ += n;
    return true;
  }
  bool skip(std::size_t n) {
    if (b_.size() - at_ < n) return false;
    at_ += n;
    return true;
  }

 private:
  const std::vector<std::uint8_t>& b_;
  std::size_t at_ = 0;
};

Status corrupt(const std::string& what) {
  return Status::error(ErrorCode::corrupt_data, "shader_binary: " + what);
}

}  // namespace

std::uint64_t shader_key(const std::map<std::string, std::string>& expanded) {
  std::uint64_t h = 14695981039346656037ull;
  fnv(h, kVersion, std::strlen(kVersion) + 1);
  for (const auto& [pass, text] : expanded) {
    fnv(h, pass.data(), pass.size() + 1);
    fnv(h, text.data(), text.size() + 1);
  }
  return h;
}

std::vector<std::uint8_t> write_shader_binary(const std::vector<ShaderBinaryEntry>& entries) {
  std::vector<std::uint8_t> out(kMagic, kMagic + 4);
  put(out, kFormat);
  put(out, std::uint32_t(entries.size()));
  for (const ShaderBinaryEntry& e : entries) {
    put(out, e.key);
    put(out, std::uint32_t(e.spirv.size()));
    for (const auto& [pass, words] : e.spirv) {
      put(out, std::uint32_t(pass.size()));
      out.insert(out.end(), pass.begin(), pass.end());
      out.resize((out.size() + 3) / 4 * 4, 0);
      put(out, std::uint32_t(words.size()));
      const std::size_t at = out.size();
      out.resize(at + words.size() * 4);
      std::memcpy(out.data() + at, words.data(), words.size() * 4);
    }
  }
  return out;
}

namespace {

/// One entry's passes (after its key).
Result<ShaderPasses> read_passes(Reader& r, std::size_t total_bytes) {
  std::uint32_t count = 0;
  if (!r.get(count)) return corrupt("truncated entry");
  ShaderPasses spirv;
  for (std::uint32_t i = 0; i < count; ++i) {
    std::uint32_t name_bytes = 0, words = 0;
    if (!r.get(name_bytes) || name_bytes > 64) return corrupt("pass " + std::to_string(i));
    std::string name(name_bytes, '\0');
    if (!r.bytes(name.data(), name_bytes) || !r.skip((4 - name_bytes % 4) % 4) || !r.get(words) ||
        words == 0 || words > (total_bytes / 4)) {
      return corrupt("truncated at pass " + std::to_string(i));
    }
    std::vector<std::uint32_t> code(words);
    if (!r.bytes(code.data(), std::size_t(words) * 4)) {
      return corrupt("truncated in pass " + name);
    }
    spirv.emplace(std::move(name), std::move(code));
  }
  return spirv;
}

}  // namespace

Result<ShaderPasses> read_shader_binary(const std::vector<std::uint8_t>& bytes, std::uint64_t key,
                                        const std::vector<std::string>& passes) {
  Reader r(bytes);
  char magic[4];
  std::uint32_t format = 0, entries = 1;
  if (!r.bytes(magic, 4) || std::memcmp(magic, kMagic, 4) != 0) {
    return corrupt("not a tessera shader binary (no TSAS header)");
  }
  if (!r.get(format) || (format != 1 && format != kFormat)) {
    return corrupt("format " + std::to_string(format) + ", this tessera reads formats 1 and 2");
  }
  if (format == kFormat && !r.get(entries)) return corrupt("truncated header");
  std::string keys;
  for (std::uint32_t e = 0; e < entries; ++e) {
    std::uint64_t got = 0;
    if (!r.get(got)) return corrupt("truncated header");
    Result<ShaderPasses> spirv = read_passes(r, bytes.size());
    if (!spirv) return spirv.status();
    if (got != key) {
      keys += (keys.empty() ? "" : ", ") + hex(got);
      continue;
    }
    for (const std::string& p : passes) {
      if (spirv->find(p) == spirv->end()) {
        return Status::error(ErrorCode::invalid_argument, "shader_binary: no pass " + p);
      }
    }
    return spirv;
  }
  return Status::error(ErrorCode::invalid_argument,
                       "shader_binary: made for other options, another device's limits or "
                       "another tessera (key " +
                           keys + ", these options need " + hex(key) + ")");
}

}  // namespace tessera::vk
