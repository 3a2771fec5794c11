// The C++ side of bench/python_encode.py's in-process comparison: built only into the bench
// module `_tessera_bench` (the module's own sources plus this file, python/CMakeLists.txt), so
// that `_tessera_bench.encode(array, ...)` and the C++ call timed here run the same machine code
// in the same process on the same heap, and differ only by what the binding does.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <string>
#include <vector>

#include "arrays.h"
#include "compress.h"
#include "tessera/texture_file.h"

namespace tessera::python {

void add_bench_functions(py::module_& m) {
  using namespace pybind11::literals;
  m.def(
      "native_encode_ms",
      [](const py::handle& array, int calls, const std::string& format, const std::string& quality,
         int threads) {
        texture_file::RecordedOptions words;
        words.format = format;
        words.quality = quality;
        const texture_file::CompressOptions options = unwrap(keyword_options(words, threads));
        py::array keep;
        const ImageView8 view = view_of_array(array, "array", keep);
        std::vector<double> ms;
        ms.reserve(static_cast<size_t>(calls > 0 ? calls : 0));
        py::gil_scoped_release release;
        for (int i = 0; i < calls; ++i) {
          const auto t0 = std::chrono::steady_clock::now();
          Result<texture_file::CompressedTexture> texture =
              texture_file::compress_view(view, options, "array");
          const auto t1 = std::chrono::steady_clock::now();
          if (!texture) throw StatusError(texture.status());  // GIL re-taken on the way out
          ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
        }
        return ms;
      },
      "array"_a, "calls"_a = 1, py::kw_only(), "format"_a = "pvrtc1-4", "quality"_a = "normal",
      "threads"_a = 0,
      "Milliseconds of each of `calls` C++ calls of texture_file::compress_view on `array`, the "
      "call `encode(array, format=, quality=, threads=)` makes, timed in C++ without the GIL.");
}

}  // namespace tessera::python
