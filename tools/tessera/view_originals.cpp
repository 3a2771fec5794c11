// tessera view, serving: each image input's own texels for the page's first draw (see
// view_originals.h).
#include "view_originals.h"

#include <cstdio>

#include "view_png.h"

namespace tessera::cli {

std::string ViewOriginals::add(int index, const std::string& path) {
  // A key of its own (not the bytes' hash: they are not made yet), from the input's place and
  // path; FNV-1a as BlobStore's keys, so it has their form and the same route serves it.
  std::uint64_t h = 1469598103934665603ull;
  const std::string seed = "tessera view original " + std::to_string(index) + " " + path;
  for (char c : seed) h = (h ^ std::uint8_t(c)) * 1099511628211ull;
  char key[17];
  std::snprintf(key, sizeof key, "%016llx", static_cast<unsigned long long>(h));
  auto entry = std::make_unique<Entry>();
  entry->index = index;
  std::lock_guard<std::mutex> lock(mutex_);
  entries_[key] = std::move(entry);
  return key;
}

std::shared_ptr<const BlobStore::Blob> ViewOriginals::get(const std::string& key,
                                                          const std::vector<ViewInput>& inputs) {
  Entry* e = nullptr;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = entries_.find(key);
    if (it == entries_.end()) return nullptr;
    e = it->second.get();  // entries are never removed
  }
  std::lock_guard<std::mutex> making(e->making);
  if (!e->blob) {
    e->blob = std::make_shared<const BlobStore::Blob>(BlobStore::Blob{
        "image/png", encode_view_png(inputs[std::size_t(e->index)].image, kPngLevelFast)});
  }
  return e->blob;
}

}  // namespace tessera::cli
