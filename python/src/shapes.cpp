// Cube maps and arrays: encode's images from a leading axis or a list, decode's stacked
// arrays; see shapes.h.
#include "shapes.h"

#include <pybind11/pytypes.h>

#include <cstring>

namespace tessera::python {

namespace {

using texture_file::CompressedTexture;
using texture_file::TextureShape;

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

/// "cube=True", "array=True" or "cube=True, array=True".
std::string keywords(const TextureShape& shape) {
  const bool cube = shape.faces == 6;
  return cube && shape.array ? "cube=True, array=True" : cube ? "cube=True" : "array=True";
}

/// The forms of the first argument a texture of `shape` takes.
std::string forms(const TextureShape& shape) {
  const bool cube = shape.faces == 6;
  if (cube && shape.array) {
    return "an (L, 6, H, W, C) or (6L, H, W, C) array or a list of (H, W, C) arrays, 6 per "
           "layer";
  }
  return cube ? "a (6, H, W, C) array or a list of 6 (H, W, C) arrays"
              : "an (L, H, W, C) array or a list of (H, W, C) arrays";
}

[[noreturn]] void wrong_form(const std::string& name, const TextureShape& shape,
                             const std::string& got) {
  throw py::value_error(name + ": " + keywords(shape) + " takes " + forms(shape) + ", not " + got);
}

}  // namespace

void check_one_image(const py::handle& x, const std::string& name) {
  std::string got;
  if (py::isinstance<py::array>(x)) {
    const auto a = py::reinterpret_borrow<py::array>(x);
    if (a.ndim() == 4 || a.ndim() == 5) got = "shape " + shape_text(a) + " holds several images";
  } else if ((py::isinstance<py::list>(x) || py::isinstance<py::tuple>(x)) && py::len(x) > 0 &&
             py::isinstance<py::array>(x[py::int_(0)])) {
    // A list of arrays; a nested list of numbers is no array at all (view_of_array says so).
    got = "a " + std::string(py::str(py::type::of(x).attr("__name__"))) + " of " +
          std::to_string(py::len(x)) + " arrays holds several images";
  }
  if (!got.empty()) {
    throw py::value_error(name + ": " + got +
                          ": pass cube=True (a cube map) or array=True (an array texture), or "
                          "one (H, W, 3) or (H, W, 4) array");
  }
}

ShapedImages images_of(const py::handle& x, const TextureShape& shape, const std::string& name) {
  ShapedImages out;
  auto add = [&](const py::handle& image, const std::string& image_name) {
    out.names.push_back(image_name);
    out.images.push_back(image_from_array(image, image_name));
  };
  if (py::isinstance<py::list>(x) || py::isinstance<py::tuple>(x)) {
    const auto items = py::reinterpret_borrow<py::sequence>(x);
    for (std::size_t i = 0; i < items.size(); ++i) {
      add(items[i], name + "[" + std::to_string(i) + "]");
    }
    return out;  // the count is the library's to check (compress_images names it)
  }
  if (!py::isinstance<py::array>(x)) {
    wrong_form(name, shape, std::string(py::str(py::type::of(x).attr("__name__"))));
  }
  const auto a = py::reinterpret_borrow<py::array>(x);
  const bool cube = shape.faces == 6;
  const py::ssize_t n = a.ndim() >= 1 ? a.shape(0) : 0;
  const bool fits = a.ndim() == 5   ? cube && shape.array && a.shape(1) == 6 && n > 0
                    : a.ndim() == 4 ? n > 0 && (!cube || (shape.array ? n % 6 == 0 : n == 6))
                                    : false;
  if (!fits) wrong_form(name, shape, "shape " + shape_text(a));
  if (a.ndim() == 5) {
    for (py::ssize_t layer = 0; layer < n; ++layer) {
      for (py::ssize_t face = 0; face < 6; ++face) {
        add(a[py::make_tuple(layer, face)],
            name + "[" + std::to_string(layer) + ", " + std::to_string(face) + "]");
      }
    }
  } else {
    for (py::ssize_t i = 0; i < n; ++i) add(a[py::int_(i)], name + "[" + std::to_string(i) + "]");
  }
  return out;
}

void warn_premultiply_without_alpha(const std::string& name) {
  const std::string text = name + " has no alpha channel: premultiply leaves it as it is";
  if (PyErr_WarnEx(PyExc_UserWarning, text.c_str(), 1) != 0) throw py::error_already_set();
}

py::array decode_images(const CompressedTexture& texture, int level, std::optional<int> layer,
                        std::optional<int> face, int threads) {
  if (threads < 0) throw py::value_error("threads: " + std::to_string(threads) + " is negative");
  check(texture_file::check_image_index(texture, level, layer.value_or(0), face.value_or(0)));
  const int channels = texture.has_alpha ? 4 : 3;
  const Parallel parallel{threads};
  if ((layer || !texture.array) && (face || !texture.is_cube())) {
    ImageRGBA8 image;
    {
      py::gil_scoped_release release;
      image = unwrap(texture_file::decode_texture_image(texture, level, layer.value_or(0),
                                                        face.value_or(0), parallel));
    }
    return image_to_array(std::move(image), channels);
  }
  // Every selected image, each decoded into its place of one C-contiguous array.
  std::vector<int> layers, faces;
  for (int l = 0; l < texture.layers; ++l) {
    if (!layer || *layer == l) layers.push_back(l);
  }
  for (int f = 0; f < texture.faces; ++f) {
    if (!face || *face == f) faces.push_back(f);
  }
  const py::ssize_t h = texture.level_height(level), w = texture.level_width(level);
  std::vector<py::ssize_t> dims;
  if (!layer && texture.array) dims.push_back(py::ssize_t(layers.size()));
  if (!face && texture.is_cube()) dims.push_back(py::ssize_t(faces.size()));
  dims.insert(dims.end(), {h, w, py::ssize_t(channels)});
  py::array_t<std::uint8_t> out(dims);
  std::uint8_t* dst = out.mutable_data();
  {
    py::gil_scoped_release release;
    for (const int l : layers) {
      for (const int f : faces) {
        const ImageRGBA8 image =
            unwrap(texture_file::decode_texture_image(texture, level, l, f, parallel));
        const std::uint8_t* src = image.pixels.data();
        if (channels == 4) {
          std::memcpy(dst, src, image.pixels.size());
          dst += image.pixels.size();
          continue;
        }
        for (std::size_t i = 0, n = image.pixel_count(); i < n; ++i, src += 4, dst += 3) {
          dst[0] = src[0];
          dst[1] = src[1];
          dst[2] = src[2];
        }
      }
    }
  }
  return out;
}

}  // namespace tessera::python
