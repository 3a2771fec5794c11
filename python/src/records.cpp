// The up-to-date record functions of the module (records.h): the library's record, so that
// `tessera.batch` and `tessera compress --skip-up-to-date` write the same bytes and each skips
// what the other made.
#include "records.h"

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <string>
#include <vector>

#include "arrays.h"
#include "compress.h"
#include "tessera/texture_file.h"

namespace tessera::python {

namespace {

using namespace pybind11::literals;

/// One path (str or os.PathLike) or a sequence of them, as the library's input list.
std::vector<std::string> input_paths(const py::object& inputs) {
  if (py::isinstance<py::str>(inputs) || py::hasattr(inputs, "__fspath__")) {
    return {inputs.cast<std::filesystem::path>().string()};
  }
  std::vector<std::string> paths;
  for (const py::handle& p : inputs) paths.push_back(p.cast<std::filesystem::path>().string());
  if (paths.empty()) throw py::value_error("inputs: no path given");
  return paths;
}

/// The record's options from the keywords, checked as encode checks them (and the container
/// and zstd as Texture.write does); raises InvalidArgumentError naming the keyword.
texture_file::RecordedOptions recorded(const std::string& container, int zstd, bool cube,
                                       bool array, const std::string& format,
                                       const std::string& quality, bool mipmaps, bool srgb,
                                       int iterations, int exact_search_rounds, bool resize_pot,
                                       int mip_levels, const std::string& mip_filter, bool flip_y,
                                       bool premultiply, bool alpha_bleed, bool alpha_weighted,
                                       bool normal_map) {
  texture_file::RecordedOptions r;
  r.container = container;
  r.format = format;
  r.quality = quality;
  r.iterations = iterations;
  r.exact_search_rounds = exact_search_rounds;
  r.mipmaps = mipmaps;
  r.mip_levels = mip_levels;
  r.mip_filter = mip_filter;
  r.srgb = srgb;
  r.resize_pot = resize_pot;
  r.flip_y = flip_y;
  r.premultiply = premultiply;
  r.alpha_bleed = alpha_bleed;
  r.alpha_weighted = alpha_weighted;
  r.normal_map = normal_map;
  r.zstd = zstd;
  r.cube = cube;
  r.array = array;
  unwrap(keyword_options(r, 0));
  if (container != "pvr" && container != "ktx" && container != "ktx2") {
    check(Status::error(ErrorCode::invalid_argument,
                        "container: '" + container + "' is not one of 'pvr', 'ktx', 'ktx2'"));
  }
  check(check_zstd(zstd, container == "ktx2", "container='ktx2'"));
  return r;
}

/// `fn(inputs, extra..., RecordedOptions)` as a function of (inputs, extra..., the keywords of
/// `record_keyword_args` in order).
template <class... Extra, class Fn>
auto with_record_keywords(Fn fn) {
  return
      [fn](const py::object& inputs, const Extra&... extra, const std::string& container, int zstd,
           bool cube, bool array, const std::string& format, const std::string& quality,
           bool mipmaps, bool srgb, int iterations, int exact_search_rounds, bool resize_pot,
           int mip_levels, const std::string& mip_filter, bool flip_y, bool premultiply,
           bool alpha_bleed, bool alpha_weighted, bool normal_map) {
        return fn(input_paths(inputs), extra...,
                  recorded(container, zstd, cube, array, format, quality, mipmaps, srgb, iterations,
                           exact_search_rounds, resize_pot, mip_levels, mip_filter, flip_y,
                           premultiply, alpha_bleed, alpha_weighted, normal_map));
      };
}

/// The container and shape keywords, then encode's (without threads), with the CLI's defaults.
template <class F, class... First>
void def_record(py::module_& m, const char* name, F f, const char* doc, First... first) {
  m.def(name, f, doc, first..., py::kw_only(), "container"_a = "pvr", "zstd"_a = 0,
        "cube"_a = false, "array"_a = false, "format"_a = "pvrtc1-4", "quality"_a = "normal",
        "mipmaps"_a = false, "srgb"_a = false, "iterations"_a = -1, "exact_search_rounds"_a = 0,
        "resize_pot"_a = false, "mip_levels"_a = 0, "mip_filter"_a = "box", "flip_y"_a = false,
        "premultiply"_a = false, "alpha_bleed"_a = false, "alpha_weighted"_a = false,
        "normal_map"_a = false);
}

constexpr const char* kRecordDoc = R"doc(
The up-to-date record of an output made from `inputs` (one path, or the faces / layers of a
cube map / array in order) with these options: the JSON text `tessera compress
--skip-up-to-date` writes beside the output as OUT.json, byte for byte. The keywords are
encode's (without threads), `container` ('pvr', 'ktx', 'ktx2') and `zstd` as Texture.write,
`cube` / `array` as encode_file. It holds the tessera version, the container, the options (the
later ones only when not their defaults) and each input's size and modification time; raises
tessera.Error naming an input that cannot be examined.
)doc";

constexpr const char* kUpToDateDoc = R"doc(
True when `output` exists, is newer than every input and OUTPUT.json holds the record
up_to_date_record gives now (the rule of `tessera compress --skip-up-to-date`); False when any
of that cannot be read. Keywords as up_to_date_record.
)doc";

}  // namespace

void register_records(py::module_& m) {
  def_record(m, "up_to_date_record",
             with_record_keywords([](const std::vector<std::string>& inputs,
                                     const texture_file::RecordedOptions& o) {
               py::gil_scoped_release release;
               return unwrap(texture_file::up_to_date_record(o, inputs));
             }),
             kRecordDoc, "inputs"_a);
  def_record(m, "is_up_to_date",
             with_record_keywords<std::filesystem::path>(
                 [](const std::vector<std::string>& inputs, const std::filesystem::path& output,
                    const texture_file::RecordedOptions& o) {
                   py::gil_scoped_release release;
                   return texture_file::is_up_to_date(o, inputs, output.string());
                 }),
             kUpToDateDoc, "inputs"_a, "output"_a);
  m.def(
      "write_up_to_date_record",
      [](const std::filesystem::path& output, const std::string& record) {
        py::gil_scoped_release release;
        check(texture_file::write_up_to_date_record(output.string(), record));
      },
      "output"_a, "record"_a,
      "Write `record` (from up_to_date_record) to OUTPUT.json atomically; call it after the "
      "output is written, so that an interrupted run never leaves an output that looks "
      "complete without being so.");
}

}  // namespace tessera::python
