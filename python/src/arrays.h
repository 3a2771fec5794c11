// Conversions between numpy arrays and tessera images, and tessera statuses as Python
// exceptions. Every function here needs the GIL.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <stdexcept>
#include <string>
#include <utility>

#include "tessera/core.h"

namespace tessera::python {

namespace py = pybind11;

/// A failed tessera `Status` on its way to Python: the module's translator raises
/// `tessera.InvalidArgumentError` (a `tessera.Error` and a `ValueError`) for invalid_argument
/// and `tessera.Error` (a `RuntimeError`) for every other code, with the status message as the
/// text and the code's name in the exception's `code` attribute.
class StatusError : public std::runtime_error {
 public:
  explicit StatusError(Status status)
      : std::runtime_error(status.message), status_(std::move(status)) {}
  const Status& status() const { return status_; }

 private:
  Status status_;
};

/// Throws `StatusError` when `status` is not ok.
inline void check(const Status& status) {
  if (!status.ok()) throw StatusError(status);
}

/// The value of `result`, or throws its status as `StatusError`.
template <class T>
T unwrap(Result<T> result) {
  if (!result) throw StatusError(result.status());
  return std::move(result).value();
}

/// Creates `tessera.Error` and `tessera.InvalidArgumentError` in `module` and registers the
/// translator for `StatusError`.
void register_errors(py::module_& module);

/// A view of a numpy uint8 array of shape (H, W, 3) or (H, W, 4) (`has_alpha` = 4 channels),
/// read where it lies when each texel's channels are adjacent; other layouts are first copied
/// by numpy. `keep` receives the array the view points into: hold it (and the GIL-free call
/// that reads the view must not outlive it). Raises ValueError for another type, dtype or
/// shape, naming `what`.
ImageView8 view_of_array(const py::handle& object, const std::string& what, py::array& keep);

/// Copies a numpy uint8 array of shape (H, W, 3) or (H, W, 4), any strides, into an image
/// (`has_alpha` = 4 channels; alpha 255 for 3). Raises ValueError for another type, dtype or
/// shape, naming `what`.
ImageRGBA8 image_from_array(const py::handle& object, const std::string& what);

/// Returns `image` as a new uint8 array of shape (H, W, channels), channels 3 or 4. The
/// 4-channel case takes over the pixel buffer without copying.
py::array image_to_array(ImageRGBA8&& image, int channels);

}  // namespace tessera::python
