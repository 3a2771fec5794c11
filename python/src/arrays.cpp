// numpy <-> ImageRGBA8 and Status -> exception; see arrays.h.
#include "arrays.h"

#include <cstddef>
#include <cstring>
#include <vector>

namespace tessera::python {

namespace {

// Created once at import and kept for the life of the process (the module is never unloaded).
PyObject* g_error = nullptr;
PyObject* g_invalid_argument = nullptr;

std::string shape_text(const py::array& array) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < array.ndim(); ++i) {
    if (i) s += ", ";
    s += std::to_string(array.shape(i));
  }
  return s + (array.ndim() == 1 ? ",)" : ")");
}

}  // namespace

void register_errors(py::module_& module) {
  g_error = PyErr_NewExceptionWithDoc(
      "tessera.Error",
      "A tessera operation failed: missing, unreadable or corrupt file, unwritable output, "
      "unsupported content. `code` holds the error category ('io_error', 'corrupt_data', ...); "
      "the text is the message `tessera` CLI prints.",
      PyExc_RuntimeError, nullptr);
  if (!g_error) throw py::error_already_set();
  py::tuple bases = py::make_tuple(py::handle(g_error), py::handle(PyExc_ValueError));
  g_invalid_argument = PyErr_NewExceptionWithDoc(
      "tessera.InvalidArgumentError",
      "A tessera.Error for an invalid argument or input the operation cannot take (e.g. a size "
      "that is not a power of two); also a ValueError.",
      bases.ptr(), nullptr);
  if (!g_invalid_argument) throw py::error_already_set();
  module.attr("Error") = py::handle(g_error);
  module.attr("InvalidArgumentError") = py::handle(g_invalid_argument);

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const StatusError& e) {
      PyObject* type =
          e.status().code == ErrorCode::invalid_argument ? g_invalid_argument : g_error;
      try {
        py::object instance = py::reinterpret_borrow<py::object>(type)(e.status().message);
        instance.attr("code") = error_code_name(e.status().code);
        PyErr_SetObject(type, instance.ptr());
      } catch (py::error_already_set& nested) {
        nested.restore();
      }
    }
  });
}

ImageView8 view_of_array(const py::handle& object, const std::string& what, py::array& keep) {
  if (!py::isinstance<py::array>(object)) {
    throw py::value_error(what +
                          ": expected a numpy uint8 array of shape (H, W, 3) or (H, W, 4), " +
                          "got " + std::string(py::str(py::type::of(object).attr("__name__"))));
  }
  keep = py::reinterpret_borrow<py::array>(object);
  if (keep.dtype().kind() != 'u' || keep.itemsize() != 1) {
    throw py::value_error(what + ": dtype " + std::string(py::str(keep.dtype())) + " is not uint8");
  }
  if (keep.ndim() != 3 || (keep.shape(2) != 3 && keep.shape(2) != 4)) {
    throw py::value_error(what + ": shape " + shape_text(keep) + " is not (H, W, 3) or (H, W, 4)");
  }
  const py::ssize_t h = keep.shape(0), w = keep.shape(1), c = keep.shape(2);
  if (h == 0 || w == 0) {
    throw py::value_error(what + ": shape " + shape_text(keep) + " is empty");
  }
  check(check_image_size(w, h, what));
  // A view needs each texel's channels side by side (any row and texel strides, broadcasts
  // included); anything else (transposed channels, every other channel) is first copied
  // C-contiguous by numpy.
  if (keep.strides(2) != 1) keep = py::array_t<std::uint8_t, py::array::c_style>::ensure(keep);
  if (!keep) throw py::error_already_set();
  ImageView8 view;
  view.data = static_cast<const std::uint8_t*>(keep.data());
  view.width = static_cast<int>(w);
  view.height = static_cast<int>(h);
  view.channels = static_cast<int>(c);
  view.pixel_stride = keep.strides(1);
  view.row_stride = keep.strides(0);
  view.has_alpha = c == 4;
  check(check_view(view, what));
  return view;
}

ImageRGBA8 image_from_array(const py::handle& object, const std::string& what) {
  py::array keep;
  return to_image(view_of_array(object, what, keep));
}

py::array image_to_array(ImageRGBA8&& image, int channels) {
  const py::ssize_t h = image.height, w = image.width;
  if (channels == 4) {
    auto* owned = new std::vector<std::uint8_t>(std::move(image.pixels));
    py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<std::uint8_t>*>(p); });
    return py::array_t<std::uint8_t>({h, w, py::ssize_t{4}}, owned->data(), owner);
  }
  py::array_t<std::uint8_t> array({h, w, py::ssize_t{3}});
  std::uint8_t* out = array.mutable_data();
  const std::uint8_t* in = image.pixels.data();
  for (std::size_t i = 0, n = image.pixel_count(); i < n; ++i, in += 4, out += 3) {
    out[0] = in[0];
    out[1] = in[1];
    out[2] = in[2];
  }
  return array;
}

}  // namespace tessera::python
