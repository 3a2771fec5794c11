// tessera._tessera: the Python bindings of the PVRTC codec, texture files, image I/O and
// metrics. Thin wrappers: arguments are converted while the GIL is held, then every library
// call runs with the GIL released. The package `tessera` (python/tessera/__init__.py)
// re-exports everything here.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "arrays.h"
#include "compress.h"
#include "tessera/io.h"
#include "tessera/metrics.h"
#include "tessera/pvrtc.h"
#include "tessera/texture_file.h"

#ifndef TESSERA_VERSION_STRING
#error "TESSERA_VERSION_STRING must be defined by the build"
#endif

namespace tessera::python {

namespace {

using namespace pybind11::literals;
using Path = std::filesystem::path;
using texture_file::CompressedTexture;

const char* format_key(pvrtc::Format format) {
  return format == pvrtc::Format::pvrtc1_2bpp ? "pvrtc1-2" : "pvrtc1-4";
}

void check_threads(int threads) {
  if (threads < 0) throw py::value_error("threads: " + std::to_string(threads) + " is negative");
}

texture_file::CompressOptions make_options(const std::string& format, const std::string& quality,
                                           bool mipmaps, bool srgb, int threads, int iterations,
                                           int exact_search_rounds, bool resize_pot) {
  CompressKeywords k;
  k.format = format;
  k.quality = quality;
  k.mipmaps = mipmaps;
  k.srgb = srgb;
  k.threads = threads;
  k.iterations = iterations;
  k.exact_search_rounds = exact_search_rounds;
  k.resize_pot = resize_pot;
  return unwrap(compress_options(k));
}

// The library's compress_view is compress_image, the pipeline of `tessera compress` (alpha
// detection, the power-of-two rule, --resize-pot, mips, per-level encodes), on pixels it does not
// own: the same texture, the same bytes.
CompressedTexture encode_array(const py::handle& array, const std::string& format,
                               const std::string& quality, bool mipmaps, bool srgb, int threads,
                               int iterations, int exact_search_rounds, bool resize_pot,
                               const std::string& name) {
  const texture_file::CompressOptions o = make_options(format, quality, mipmaps, srgb, threads,
                                                       iterations, exact_search_rounds, resize_pot);
  // The encoder reads the array in place (no copy before a few-millisecond encode); `keep`
  // holds it for the call, and an array with a live reference cannot be resized meanwhile.
  py::array keep;
  const ImageView8 view = view_of_array(array, name, keep);
  py::gil_scoped_release release;
  return unwrap(texture_file::compress_view(view, o, name));
}

CompressedTexture encode_file(const Path& path, const std::string& format,
                              const std::string& quality, bool mipmaps, bool srgb, int threads,
                              int iterations, int exact_search_rounds, bool resize_pot) {
  const texture_file::CompressOptions o = make_options(format, quality, mipmaps, srgb, threads,
                                                       iterations, exact_search_rounds, resize_pot);
  py::gil_scoped_release release;
  ImageRGBA8 image = unwrap(io::read_image(path.string()));
  return unwrap(texture_file::compress_image(std::move(image), o, path.string())).texture;
}

py::array decode_level(const CompressedTexture& texture, int level, int threads) {
  check_threads(threads);
  ImageRGBA8 image;
  {
    py::gil_scoped_release release;
    image = unwrap(texture_file::decode_texture_level(texture, level, {threads}));
  }
  return image_to_array(std::move(image), texture.has_alpha ? 4 : 3);
}

py::bytes to_bytes(const CompressedTexture& texture, const std::string& container) {
  if (container != "pvr" && container != "ktx") {
    throw py::value_error("container: '" + container + "' is not one of 'pvr', 'ktx'");
  }
  std::vector<std::uint8_t> bytes;
  {
    py::gil_scoped_release release;
    bytes = unwrap(container == "ktx" ? texture_file::serialise_ktx1(texture)
                                      : texture_file::serialise_pvr3(texture));
  }
  return py::bytes(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

void write_texture_py(const Path& path, const CompressedTexture& texture) {
  py::gil_scoped_release release;
  check(texture_file::write_texture_file(path.string(), texture));
}

CompressedTexture from_bytes(const py::bytes& data, const std::string& name) {
  const std::string_view view = data;  // the bytes object outlives the call
  py::gil_scoped_release release;
  return unwrap(texture_file::parse_texture(
      std::span(reinterpret_cast<const std::uint8_t*>(view.data()), view.size()), name));
}

// A compare operand: a path (read like `tessera compare` reads its files) or an array.
struct Operand {
  ImageRGBA8 image;
  std::string name;
  bool is_path = false;
};

Operand load_operand(const py::handle& object, const std::string& default_name) {
  Operand op;
  if (py::isinstance<py::str>(object) || py::hasattr(object, "__fspath__")) {
    op.name = object.cast<Path>().string();
    op.is_path = true;
    py::gil_scoped_release release;
    op.image = unwrap(io::read_image(op.name));
  } else {
    op.name = default_name;
    op.image = image_from_array(object, default_name);
  }
  return op;
}

py::object db_or_none(double v) {
  return std::isfinite(v) ? py::object(py::float_(v)) : py::none();
}

py::dict compare_py(const py::handle& a_object, const py::handle& b_object, int threads) {
  check_threads(threads);
  Operand a = load_operand(a_object, "a");
  Operand b = load_operand(b_object, "b");
  const ImageRGBA8 &ia = a.image, &ib = b.image;
  if (ia.width != ib.width || ia.height != ib.height) {
    throw StatusError(Status::error(
        ErrorCode::size_mismatch, b.name + ": size " + std::to_string(ib.width) + "x" +
                                      std::to_string(ib.height) + " differs from " + a.name + " (" +
                                      std::to_string(ia.width) + "x" + std::to_string(ia.height) +
                                      ")"));
  }
  metrics::ImageComparison r;
  {
    py::gil_scoped_release release;
    metrics::CompareOptions options;
    options.threads = threads;
    r = unwrap(metrics::compare_images(ia, ib, options));
  }
  py::dict d;
  if (a.is_path) d["a"] = a.name;
  if (b.is_path) d["b"] = b.name;
  d["width"] = ia.width;
  d["height"] = ia.height;
  d["psnr_rgb"] = db_or_none(r.psnr_rgb);
  d["identical_rgb"] = !std::isfinite(r.psnr_rgb);
  d["mse"] = r.mse_rgb;
  d["ssim_gray"] = r.ssim_gray;
  d["max_abs"] = r.max_abs;
  d["has_alpha"] = r.has_alpha;
  if (r.has_alpha) {
    d["psnr_alpha"] = db_or_none(r.psnr_alpha);
    d["mse_alpha"] = r.mse_alpha;
  }
  return d;
}

std::string repr(const CompressedTexture& t) {
  return "<tessera.Texture " + std::to_string(t.width) + "x" + std::to_string(t.height) + " " +
         format_key(t.format) + (t.has_alpha ? " RGBA" : " RGB") + (t.srgb ? " sRGB" : "") + ", " +
         std::to_string(t.level_count()) + " level(s)>";
}

constexpr const char* kEncodeDoc = R"doc(
Compress an image to PVRTC1 exactly as `tessera compress` does.

`array`: numpy uint8 array of shape (H, W, 3) or (H, W, 4), any strides. A 4-channel array whose
alpha is 255 everywhere gives an RGB texture (as the CLI does with an opaque RGBA PNG).
Keywords are the CLI's options: format 'pvrtc1-4' | 'pvrtc1-2', quality 'fast' | 'normal' |
'high', mipmaps (full chain), srgb (sRGB flag, mips filtered in linear light), threads (-j; 0 =
all; output is the same for any value), iterations (-1..1000), exact_search_rounds (0..1000),
resize_pot (resample non-power-of-two sides with Lanczos-3). `name` prefixes error messages.
Serialising the result gives the CLI's bytes. The GIL is released while encoding, and the
encoder reads the array where it lies (no copy first, unless its channels are not adjacent or a
mip chain or resample is asked): do not write to it from another thread during the call.
Raises ValueError (bad argument, dtype or shape), tessera.InvalidArgumentError (e.g. a side
that is not a power of two) or tessera.Error.
)doc";

}  // namespace

#ifdef TESSERA_PYTHON_BENCH_FUNCTIONS
// The build makes these sources a second time, as `_tessera_bench` with the timing functions of
// bench/python_native_calls.cpp added, so that a benchmark compares a Python call with the
// same C++ call in one process and one binary (python/CMakeLists.txt).
void add_bench_functions(py::module_& m);
#endif

}  // namespace tessera::python

#ifndef TESSERA_PYTHON_MODULE_NAME
#define TESSERA_PYTHON_MODULE_NAME _tessera
#endif

PYBIND11_MODULE(TESSERA_PYTHON_MODULE_NAME, m) {
  using namespace tessera;
  using namespace tessera::python;
  using namespace pybind11::literals;
  m.doc() = "tessera: PVRTC1 encoding and decoding, PVR v3 / KTX 1.1 files, image metrics.";
  m.attr("__version__") = TESSERA_VERSION_STRING;
  register_errors(m);

  py::class_<CompressedTexture>(m, "Texture",
                                "A PVRTC1 texture and its mip chain (level 0 first). Made by "
                                "encode(), encode_file(), read() or from_bytes().")
      .def_readonly("width", &CompressedTexture::width, "Level 0 width in texels.")
      .def_readonly("height", &CompressedTexture::height, "Level 0 height in texels.")
      .def_readonly("has_alpha", &CompressedTexture::has_alpha, "RGBA (True) or RGB format.")
      .def_readonly("srgb", &CompressedTexture::srgb, "sRGB colour space flag.")
      .def_readonly("premultiplied", &CompressedTexture::premultiplied,
                    "PVR v3 premultiplied flag.")
      .def_property_readonly(
          "format", [](const CompressedTexture& t) { return format_key(t.format); },
          "'pvrtc1-4' or 'pvrtc1-2' (the CLI's --format values).")
      .def_property_readonly("format_name", &texture_file::texture_format_name,
                             "Human-readable format, e.g. 'PVRTC1 4bpp RGBA'.")
      .def_property_readonly("level_count", &CompressedTexture::level_count)
      .def_property_readonly(
          "levels",
          [](const CompressedTexture& t) {
            py::list out;
            for (const auto& level : t.levels) {
              out.append(py::bytes(reinterpret_cast<const char*>(level.data()), level.size()));
            }
            return out;
          },
          "Compressed data of each level (list of bytes, Morton-ordered 64-bit blocks).")
      .def(
          "level_shape",
          [](const CompressedTexture& t, int level) {
            if (level < 0 || level >= t.level_count()) {
              throw py::index_error("level " + std::to_string(level) + " is out of range");
            }
            return py::make_tuple(t.level_height(level), t.level_width(level));
          },
          "level"_a, "(height, width) of a level.")
      .def("decode", &decode_level, "level"_a = 0, "threads"_a = 0,
           "Same as tessera.decode(self, ...).")
      .def(
          "write", [](const CompressedTexture& t, const Path& path) { write_texture_py(path, t); },
          "path"_a, "Write a .pvr or .ktx file (container by extension), atomically.")
      .def("to_bytes", &to_bytes, "container"_a = "pvr",
           "The file bytes of the 'pvr' (PVR v3) or 'ktx' (KTX 1.1) container.")
      .def("__repr__", &repr)
      .def("__eq__",
           [](const CompressedTexture& a, const CompressedTexture& b) {
             return a.format == b.format && a.width == b.width && a.height == b.height &&
                    a.has_alpha == b.has_alpha && a.srgb == b.srgb &&
                    a.premultiplied == b.premultiplied && a.levels == b.levels;
           })
      .def(py::pickle([](const CompressedTexture& t) { return to_bytes(t, "pvr"); },
                      [](const py::bytes& b) { return from_bytes(b, "<pickle>"); }));

  m.def("encode", &encode_array, kEncodeDoc, "array"_a, py::kw_only(), "format"_a = "pvrtc1-4",
        "quality"_a = "normal", "mipmaps"_a = false, "srgb"_a = false, "threads"_a = 0,
        "iterations"_a = -1, "exact_search_rounds"_a = 0, "resize_pot"_a = false,
        "name"_a = "<array>");
  m.def("encode_file", &encode_file,
        "Read an image file (PNG, JPEG, TGA, BMP) with tessera's reader and encode it like "
        "`tessera compress PATH` (same keywords as encode; messages name the path). The GIL is "
        "released for the read and the encode.",
        "path"_a, py::kw_only(), "format"_a = "pvrtc1-4", "quality"_a = "normal",
        "mipmaps"_a = false, "srgb"_a = false, "threads"_a = 0, "iterations"_a = -1,
        "exact_search_rounds"_a = 0, "resize_pot"_a = false);
  m.def("decode", &decode_level,
        "Decode one level to a numpy uint8 array: (H, W, 4) for an RGBA texture, (H, W, 3) for "
        "an RGB one - the channels `tessera decompress` writes to its PNG. Values as stored "
        "(an sRGB texture gives sRGB-encoded values). The GIL is released while decoding.",
        "texture"_a, "level"_a = 0, "threads"_a = 0);
  m.def(
      "read",
      [](const Path& path) {
        py::gil_scoped_release release;
        return unwrap(texture_file::read_texture_file(path.string()));
      },
      "path"_a, "Read a .pvr / .ktx file (container detected by magic).");
  m.def("write", &write_texture_py, "path"_a, "texture"_a,
        "Write a texture to .pvr or .ktx (by extension), atomically.");
  m.def("from_bytes", &from_bytes, "data"_a, "name"_a = "<bytes>",
        "Parse PVR v3 / KTX 1.1 file bytes held in memory; `name` prefixes error messages.");
  m.def(
      "read_image",
      [](const Path& path) {
        ImageRGBA8 image;
        {
          py::gil_scoped_release release;
          image = unwrap(io::read_image(path.string()));
        }
        const int channels = image.has_alpha ? 4 : 3;
        return image_to_array(std::move(image), channels);
      },
      "path"_a,
      "Read a PNG / JPEG / TGA / BMP file to a uint8 array: (H, W, 4) when the file has an "
      "alpha channel, else (H, W, 3) (grey and palette images are expanded).");
  m.def(
      "write_image",
      [](const Path& path, const py::handle& array) {
        std::string ext = path.extension().string();
        for (char& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
        if (ext != ".png") {
          throw py::value_error(path.string() + ": write_image writes PNG only (use a .png name)");
        }
        ImageRGBA8 image = image_from_array(array, path.string());
        py::gil_scoped_release release;
        check(io::write_png(path.string(), image));
      },
      "path"_a, "array"_a,
      "Write a uint8 (H, W, 3) or (H, W, 4) array as a PNG (RGB or RGBA), atomically.");
  m.def("compare", &compare_py,
        "Compare two images like `tessera compare --json`: each of a, b is a path (read as the "
        "CLI reads it) or a uint8 array. Returns a dict with the CLI's keys: width, height, "
        "psnr_rgb (None when identical), identical_rgb, mse, ssim_gray, max_abs, has_alpha, and "
        "psnr_alpha / mse_alpha when either has alpha; 'a' / 'b' hold the paths given as paths.",
        "a"_a, "b"_a, py::kw_only(), "threads"_a = 0);
#ifdef TESSERA_PYTHON_BENCH_FUNCTIONS
  add_bench_functions(m);
#endif
}
