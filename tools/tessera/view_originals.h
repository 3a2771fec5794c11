// tessera view, serving: each image input's own texels for the page's first draw. The page
// shows an input's original at once, before its first encode (seconds at 4096²) is done: the
// texels are made into a PNG (view_png.h, its fast level) when the page first asks for them (so
// a folder of many images starts at once and only what is looked at is made), and kept while
// the server runs, like the input itself (not a result: never evicted, not in the results'
// budget).
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "view.h"

namespace tessera::cli {

class ViewOriginals {
 public:
  /// Registers image input number `index` (at `path`); returns the blob key the page asks for
  /// (16 hex digits, like BlobStore's).
  std::string add(int index, const std::string& path);
  /// The blob of `key`, made from `inputs` on its first request (requests at once wait for the
  /// one making it), or null when `key` is not an original's.
  std::shared_ptr<const BlobStore::Blob> get(const std::string& key,
                                             const std::vector<ViewInput>& inputs);

 private:
  struct Entry {
    int index = 0;
    std::mutex making;
    std::shared_ptr<const BlobStore::Blob> blob;  ///< Under `making`.
  };
  std::mutex mutex_;
  std::map<std::string, std::unique_ptr<Entry>> entries_;
};

}  // namespace tessera::cli
