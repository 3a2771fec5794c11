// Cube maps and arrays in Python: the images of `encode(x, cube=..., array=...)` from a leading
// axis or a list, the premultiply warning, and `decode`'s stacked arrays. Every function here
// needs the GIL (and releases it around the library's work).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "arrays.h"
#include "tessera/texture_file.h"

namespace tessera::python {

/// The images of one texture, layer-major then face, and their names for messages.
struct ShapedImages {
  std::vector<ImageRGBA8> images;
  std::vector<std::string> names;
};

/// The images `x` holds for a texture of `shape` (cube: 6 faces per layer): an array with a
/// leading axis ((6, H, W, C) for a cube map, (L, H, W, C) for an array, (L, 6, H, W, C) or
/// (6L, H, W, C) for a cube map array) or a list / tuple of (H, W, C) arrays, each copied.
/// Image i is named `name`[i] ("<array>[3]"; "<array>[1, 4]" from a 5-axis array). Raises
/// ValueError (naming `cube` / `array` and the shapes they take) for another form.
ShapedImages images_of(const py::handle& x, const texture_file::TextureShape& shape,
                       const std::string& name);

/// A `UserWarning` that `name` has no alpha channel and `premultiply` leaves it as it is (the
/// CLI's warning, in the keyword's words); a warning turned into an error is raised.
void warn_premultiply_without_alpha(const std::string& name);

/// For `encode` without cube / array: raises ValueError when `x` holds several images (an
/// array of 4 or 5 axes, a list or tuple), saying to pass cube=True or array=True.
void check_one_image(const py::handle& x, const std::string& name);

/// `tessera.decode`: level `level` of `texture` as a uint8 array with 4 channels (RGBA
/// texture) or 3 (RGB), (H, W, C) for one image; with a leading axis of the layers for an
/// array unless `layer` selects one, and of the 6 faces for a cube map unless `face` selects
/// one: (L, 6, H, W, C) for a whole level of a cube map array. Out-of-range indices give the
/// library's invalid_argument (`check_image_index`).
py::array decode_images(const texture_file::CompressedTexture& texture, int level,
                        std::optional<int> layer, std::optional<int> face, int threads);

}  // namespace tessera::python
