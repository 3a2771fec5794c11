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
#include <tuple>
#include <vector>

#include "arrays.h"
#include "compress.h"
#include "experiments.h"
#include "records.h"
#include "shapes.h"
#include "tessera/io.h"
#include "tessera/metrics.h"
#include "tessera/pvrtc.h"
#include "tessera/texture_file.h"
#include "texture.h"

#ifndef TESSERA_VERSION_STRING
#error "TESSERA_VERSION_STRING must be defined by the build"
#endif

namespace tessera::python {

namespace {

using namespace pybind11::literals;
using Path = std::filesystem::path;
using texture_file::CompressedTexture;
using texture_file::TextureShape;

void check_threads(int threads) {
  if (threads < 0) throw py::value_error("threads: " + std::to_string(threads) + " is negative");
}

/// The keywords encode and encode_file share (`words.cube` / `words.array` give the texture's
/// shape; container and zstd are not theirs).
struct EncodeKeywords {
  texture_file::RecordedOptions words;
  int threads = 0;

  TextureShape shape() const { return {words.cube ? 6 : 1, words.array}; }
  bool several() const { return words.cube || words.array; }
};

/// A function of (x, the keywords of `encode_keyword_args` in order, extra...) that calls
/// `fn(x, EncodeKeywords, extra...)`.
template <class First, class... Extra, class Fn>
auto with_encode_keywords(Fn fn) {
  return [fn](const First& x, const std::string& format, const std::string& quality, bool mipmaps,
              bool srgb, int threads, int iterations, int exact_search_rounds, bool resize_pot,
              int mip_levels, const std::string& mip_filter, bool flip_y, bool premultiply,
              bool alpha_bleed, bool alpha_weighted, bool normal_map, bool cube, bool array,
              const Extra&... extra) {
    EncodeKeywords k;
    k.words.format = format;
    k.words.quality = quality;
    k.words.mipmaps = mipmaps;
    k.words.srgb = srgb;
    k.words.iterations = iterations;
    k.words.exact_search_rounds = exact_search_rounds;
    k.words.resize_pot = resize_pot;
    k.words.mip_levels = mip_levels;
    k.words.mip_filter = mip_filter;
    k.words.flip_y = flip_y;
    k.words.premultiply = premultiply;
    k.words.alpha_bleed = alpha_bleed;
    k.words.alpha_weighted = alpha_weighted;
    k.words.normal_map = normal_map;
    k.words.cube = cube;
    k.words.array = array;
    k.threads = threads;
    return fn(x, k, extra...);
  };
}

/// The keywords of encode and encode_file, with the CLI's defaults (ENCODE_DEFAULTS).
auto encode_keyword_args() {
  return std::make_tuple("format"_a = "pvrtc1-4", "quality"_a = "normal", "mipmaps"_a = false,
                         "srgb"_a = false, "threads"_a = 0, "iterations"_a = -1,
                         "exact_search_rounds"_a = 0, "resize_pot"_a = false, "mip_levels"_a = 0,
                         "mip_filter"_a = "box", "flip_y"_a = false, "premultiply"_a = false,
                         "alpha_bleed"_a = false, "alpha_weighted"_a = false,
                         "normal_map"_a = false, "cube"_a = false, "array"_a = false);
}

/// m.def(name, f, doc, first, *, the encode keywords, extra...).
template <class F, class... Extra>
void def_encode(py::module_& m, const char* name, F f, const char* doc, py::arg first,
                Extra... extra) {
  std::apply(
      [&](auto... keyword) { m.def(name, f, doc, first, py::kw_only(), keyword..., extra...); },
      encode_keyword_args());
}

// One array: the library's compress_view is compress_image, the pipeline of `tessera compress`
// (flip, alpha detection, the power-of-two rule, resize_pot, premultiply, mips, bleeding,
// per-level encodes), on pixels it does not own: the same texture, the same bytes.
// Several (cube / array): each image copied, then compress_images, as `compress --cube`.
CompressedTexture encode_array(const py::handle& x, const EncodeKeywords& k,
                               const std::string& name) {
  const texture_file::CompressOptions o = unwrap(keyword_options(k.words, k.threads));
  if (k.several()) {
    ShapedImages in = images_of(x, k.shape(), name);
    if (k.words.premultiply) {
      for (std::size_t i = 0; i < in.images.size(); ++i) {
        if (!in.images[i].has_alpha) warn_premultiply_without_alpha(in.names[i]);
      }
    }
    py::gil_scoped_release release;
    return unwrap(in_python_words(
                      texture_file::compress_images(std::move(in.images), k.shape(), o, in.names)))
        .texture;
  }
  check_one_image(x, name);
  // The encoder reads the array in place (no copy before a few-millisecond encode); `keep`
  // holds it for the call, and an array with a live reference cannot be resized meanwhile.
  py::array keep;
  const ImageView8 view = view_of_array(x, name, keep);
  if (k.words.premultiply && !view.has_alpha) warn_premultiply_without_alpha(name);
  py::gil_scoped_release release;
  return unwrap(in_python_words(texture_file::compress_view(view, o, name)));
}

bool is_path(const py::handle& x) {
  return py::isinstance<py::str>(x) || py::hasattr(x, "__fspath__");
}

CompressedTexture encode_file(const py::object& paths, const EncodeKeywords& k) {
  const texture_file::CompressOptions o = unwrap(keyword_options(k.words, k.threads));
  std::vector<std::string> names;
  if (is_path(paths)) {
    if (k.several()) {
      throw py::value_error(
          paths.cast<Path>().string() + ": " +
          std::string(k.words.cube && k.words.array ? "cube=True, array=True"
                      : k.words.cube                ? "cube=True"
                                                    : "array=True") +
          " takes a list of paths (" +
          (k.words.cube ? "6 faces per layer, +X, -X, +Y, -Y, +Z, -Z" : "the layers") + ")");
    }
    names.push_back(paths.cast<Path>().string());
  } else if (py::isinstance<py::list>(paths) || py::isinstance<py::tuple>(paths)) {
    for (const py::handle item : paths) names.push_back(item.cast<Path>().string());
    if (!k.several()) {
      throw py::value_error("encode_file: a list of " + std::to_string(names.size()) +
                            " paths needs cube=True (a cube map) or array=True (an array "
                            "texture)");
    }
  } else {
    throw py::type_error("encode_file: expected a path or a list of paths, got " +
                         std::string(py::str(py::type::of(paths).attr("__name__"))));
  }
  std::vector<ImageRGBA8> images;
  {
    py::gil_scoped_release release;
    for (const std::string& path : names) images.push_back(unwrap(io::read_image(path)));
  }
  if (k.words.premultiply) {
    for (std::size_t i = 0; i < images.size(); ++i) {
      if (!images[i].has_alpha) warn_premultiply_without_alpha(names[i]);
    }
  }
  py::gil_scoped_release release;
  return unwrap(
             in_python_words(texture_file::compress_images(std::move(images), k.shape(), o, names)))
      .texture;
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

// The keys of `tessera compare --json` from `r` (the error fields), added to `d`.
void add_comparison(py::dict& d, const metrics::ImageComparison& r) {
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
  if (r.has_premultiplied) {
    d["psnr_premultiplied"] = db_or_none(r.psnr_premultiplied);
    d["mse_premultiplied"] = r.mse_premultiplied;
  }
  if (r.has_normal) {
    d["angular_error_mean_deg"] = r.angular_error_mean_deg;
    d["angular_error_p99_deg"] = r.angular_error_p99_deg;
    d["angular_error_max_deg"] = r.angular_error_max_deg;
  }
}

py::dict compare_py(const py::handle& a_object, const py::handle& b_object, bool premultiplied,
                    bool normal, int threads) {
  check_threads(threads);
  Operand a = load_operand(a_object, "a");
  Operand b = load_operand(b_object, "b");
  const ImageRGBA8 &ia = a.image, &ib = b.image;
  if (ia.width != ib.width || ia.height != ib.height) {
    throw StatusError(Status::error(ErrorCode::size_mismatch,
                                    b.name + ": size " + size_text(ib.width, ib.height) +
                                        " differs from " + a.name + " (" +
                                        size_text(ia.width, ia.height) + ")"));
  }
  metrics::ImageComparison r;
  {
    py::gil_scoped_release release;
    metrics::CompareOptions options;
    options.threads = threads;
    options.premultiplied = premultiplied;
    options.normal = normal;
    r = unwrap(metrics::compare_images(ia, ib, options));
  }
  py::dict d;
  if (a.is_path) d["a"] = a.name;
  if (b.is_path) d["b"] = b.name;
  d["width"] = ia.width;
  d["height"] = ia.height;
  add_comparison(d, r);
  return d;
}

// `tessera.measure_level0`: the sources as `encode` takes the images of a texture of this shape
// (one array for a 2D texture; a leading axis or a list for a cube map or an array).
py::dict measure_level0_py(const CompressedTexture& texture, const py::handle& images,
                           int threads) {
  check_threads(threads);
  std::vector<ImageRGBA8> sources;
  const bool sequence = py::isinstance<py::list>(images) || py::isinstance<py::tuple>(images);
  if (texture.image_count() == 1 && !sequence) {
    sources.push_back(image_from_array(images, "images"));
  } else {
    const texture_file::TextureShape shape{texture.faces, texture.faces == 1 || texture.layers > 1};
    sources = images_of(images, shape, "images").images;
  }
  metrics::ImageComparison r;
  {
    py::gil_scoped_release release;
    r = unwrap(texture_file::measure_level0(texture, sources, threads));
  }
  py::dict d;
  d["width"] = texture.width;
  d["height"] = texture.height;
  d["images"] = texture.image_count();
  add_comparison(d, r);
  return d;
}

constexpr const char* kEncodeDoc = R"doc(
Compress an image, or the faces and layers of a cube map or array, to PVRTC1 exactly as
`tessera compress` does.

    tex = tessera.encode(rgba)                          # (H, W, 3) or (H, W, 4) uint8
    tex = tessera.encode(rgba, premultiply=True, mipmaps=True, mip_filter="kaiser")
    sky = tessera.encode(faces, cube=True)              # (6, H, W, C): +X, -X, +Y, -Y, +Z, -Z
    arr = tessera.encode([a, b, c], array=True)         # or an (L, H, W, C) array
    cubes = tessera.encode(f, cube=True, array=True)    # (L, 6, H, W, C) or (6L, H, W, C)

`x`: a numpy uint8 array of shape (H, W, 3) or (H, W, 4), any strides, read where it lies; with
`cube` / `array`, the images with a leading axis as above, or a list of (H, W, C) arrays
(layer-major then face, one size, square for a cube map), each copied. A 4-channel image whose
alpha is 255 everywhere is encoded as RGB (as the CLI does with an opaque RGBA PNG); the texture
has alpha when any image has.
Keywords are the CLI's options: format 'pvrtc1-4' | 'pvrtc1-2', quality 'fast' | 'normal' |
'high', mipmaps (the chain down to 1x1), mip_levels (at most N levels, level 0 included; > 0
implies mipmaps), mip_filter 'box' | 'lanczos' | 'kaiser' (with mips), srgb (sRGB flag; filter in
linear light), threads (-j; 0 = all; output is the same for any value), iterations (-1..1000),
exact_search_rounds (0..1000), resize_pot (resample non-power-of-two sides with Lanczos-3),
flip_y (flip upside down first), premultiply (colour x alpha, the texture marked premultiplied;
an image without alpha warns with a UserWarning and is left as it is), alpha_bleed (give fully
transparent texels the nearest visible colour; not with premultiply), alpha_weighted (4 bpp,
straight alpha: colour error weighted by alpha, no bits spent on invisible colour; not with
premultiply or format 'pvrtc1-2'), normal_map (RGB holds unit
vectors: modulation chosen by angle, mips averaged as vectors; not with srgb), cube (6 faces per
layer), array (layers). `name` names the image(s) in messages ("<array>[2]" for the third).
Serialising the result gives the CLI's bytes. The GIL is released while encoding: do not write
to the array from another thread during the call.
Raises ValueError (bad argument, dtype or shape; keywords that conflict, named),
tessera.InvalidArgumentError (e.g. a side that is not a power of two: "...; resample to 64x64
with resize_pot=True") or tessera.Error.
)doc";

constexpr const char* kEncodeFileDoc = R"doc(
Read an image file (PNG, JPEG, TGA, BMP) with tessera's reader and encode it like
`tessera compress PATH` (the keywords of encode; messages name the path). With cube / array,
`path` is a list of paths, layer-major then face, as `tessera compress A B ... --cube` takes:

    sky = tessera.encode_file([f"sky_{f}.png" for f in ("px", "nx", "py", "ny", "pz", "nz")],
                              cube=True, mipmaps=True)

The GIL is released for the reads and the encode.
)doc";

constexpr const char* kDecodeDoc = R"doc(
Decode one level to a numpy uint8 array with the channels `tessera decompress` writes: 4 for an
RGBA texture, 3 for an RGB one; values as stored (an sRGB texture gives sRGB-encoded values).

    tessera.decode(tex)                   # 2D texture: (H, W, C)
    tessera.decode(sky)                   # cube map: (6, H, W, C), faces +X, -X, +Y, -Y, +Z, -Z
    tessera.decode(sky, face=4)           # (H, W, C): `tessera decompress sky.pvr --face 4`
    tessera.decode(layers, level=2)       # array: (L, H/4, W/4, C)
    tessera.decode(cubes)                 # cube map array: (L, 6, H, W, C)
    tessera.decode(cubes, layer=1)        # (6, H, W, C)

`layer` / `face` select one layer / face (that axis goes); out of range (or a layer of a texture
that is not an array, a face of one that is not a cube map) raises
tessera.InvalidArgumentError naming the range, as `level` does. The GIL is released while
decoding.
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
  m.doc() =
      "tessera: PVRTC1 encoding and decoding, PVR v3 / KTX 1.1 / KTX 2.0 files, image metrics.";
  m.attr("__version__") = TESSERA_VERSION_STRING;
  register_errors(m);

  register_texture(m);
  register_records(m);

  def_encode(m, "encode", with_encode_keywords<py::object, std::string>(&encode_array), kEncodeDoc,
             "x"_a, "name"_a = "<array>");
  def_encode(m, "encode_file", with_encode_keywords<py::object>(&encode_file), kEncodeFileDoc,
             "path"_a);
  m.def("decode", &decode_images, kDecodeDoc, "texture"_a, "level"_a = 0, "layer"_a = py::none(),
        "face"_a = py::none(), "threads"_a = 0);
  m.def(
      "read",
      [](const Path& path) {
        py::gil_scoped_release release;
        return unwrap(texture_file::read_texture_file(path.string()));
      },
      "path"_a, "Read a .pvr / .ktx / .ktx2 file (container detected by magic).");
  m.def(
      "write",
      [](const Path& path, const CompressedTexture& texture, int zstd) {
        write_texture(path, texture, zstd);
      },
      "path"_a, "texture"_a, "zstd"_a = 0,
      "Write a texture to .pvr, .ktx or .ktx2 (by extension), atomically; `zstd` (1-22, .ktx2 "
      "only) as Texture.write.");
  m.def("from_bytes", &texture_from_bytes, "data"_a, "name"_a = "<bytes>",
        "Parse PVR v3 / KTX 1.1 / KTX 2.0 file bytes held in memory; `name` prefixes error "
        "messages.");
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
        "psnr_rgb (None when identical), identical_rgb, mse, ssim_gray, max_abs, has_alpha, "
        "psnr_alpha / mse_alpha when either has alpha; with premultiplied=True (--premultiplied) "
        "psnr_premultiplied (None when identical) and mse_premultiplied, the error of colour x "
        "alpha; with normal=True (--normal) angular_error_mean_deg, angular_error_p99_deg and "
        "angular_error_max_deg between the normalised vectors; 'a' / 'b' hold the paths given "
        "as paths.",
        "a"_a, "b"_a, py::kw_only(), "premultiplied"_a = false, "normal"_a = false,
        "threads"_a = 0);
  m.def("measure_level0", &measure_level0_py,
        "The error of level 0 of `texture` against `images`, what it was encoded from, as "
        "`tessera compress --json` reports it (texture_file::measure_level0): `images` in the "
        "form `encode` takes for this texture (one (H, W, C) array; for a cube map or an array "
        "a leading axis or a list, layer-major then face). Pooled over the images: the MSE "
        "averaged, then the PSNR; the SSIM averaged; the largest difference. Returns a dict: "
        "width, height, images, and compare's keys (psnr_rgb, None when identical; "
        "identical_rgb, mse, ssim_gray, max_abs, has_alpha, psnr_alpha / mse_alpha). Another "
        "image count raises InvalidArgumentError, another size tessera.Error.",
        "texture"_a, "images"_a, py::kw_only(), "threads"_a = 0);
  register_experiments(m);
#ifdef TESSERA_PYTHON_BENCH_FUNCTIONS
  add_bench_functions(m);
#endif
}
