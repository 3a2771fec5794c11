// tessera.Texture; see texture.h.
#include "texture.h"

#include <pybind11/stl.h>

#include <optional>
#include <vector>

#include "arrays.h"
#include "compress.h"
#include "shapes.h"

namespace tessera::python {

namespace {

using namespace pybind11::literals;
using texture_file::CompressedTexture;
using texture_file::ContainerFormat;

const char* format_key(pvrtc::Format format) {
  return format == pvrtc::Format::pvrtc1_2bpp ? "pvrtc1-2" : "pvrtc1-4";
}

std::string repr(const CompressedTexture& t) {
  const std::string shape =
      t.image_count() > 1 || t.array ? ", " + texture_file::texture_shape_name(t) : std::string();
  return "<tessera.Texture " + std::to_string(t.width) + "x" + std::to_string(t.height) + " " +
         format_key(t.format) + (t.has_alpha ? " RGBA" : " RGB") + (t.srgb ? " sRGB" : "") +
         (t.premultiplied ? " premultiplied" : "") + shape + ", " +
         std::to_string(t.level_count()) + " level(s)>";
}

bool equal(const CompressedTexture& a, const CompressedTexture& b) {
  return a.format == b.format && a.width == b.width && a.height == b.height &&
         a.has_alpha == b.has_alpha && a.srgb == b.srgb && a.premultiplied == b.premultiplied &&
         a.faces == b.faces && a.layers == b.layers && a.array == b.array && a.levels == b.levels;
}

// Pickling: the PVR v3 bytes (validated again when read back) and the one field PVR v3 cannot
// hold, `array` (an array of one layer reads back as a 2D texture). PVR keeps everything else
// exactly; KTX 2.0 would not (it infers has_alpha from the blocks).
py::object pickle_state(const CompressedTexture& t) {
  return py::make_tuple(texture_to_bytes(t, "pvr", 0), t.array);
}

CompressedTexture unpickle(const py::object& state) {
  // Before cube maps and arrays, the state was the PVR bytes alone.
  if (py::isinstance<py::bytes>(state)) return texture_from_bytes(state, "<pickle>");
  const auto fields = state.cast<py::tuple>();
  if (fields.size() != 2) {
    throw py::value_error("<pickle>: a Texture's state is (PVR bytes, array), not " +
                          std::to_string(fields.size()) + " fields");
  }
  CompressedTexture t = texture_from_bytes(fields[0].cast<py::bytes>(), "<pickle>");
  if (fields[1].cast<bool>()) t.array = true;
  return t;
}

constexpr const char* kTextureDoc = R"doc(
A PVRTC1 texture: a 2D texture, a cube map (faces == 6: +X, -X, +Y, -Y, +Z, -Z), an array of
either (array, layers), with its mip chain (level 0 first). Made by encode(), encode_file(),
read() or from_bytes(); compared with == (every field and byte) and picklable.

    tex = tessera.encode(faces, cube=True)       # faces: (6, H, W, C)
    tex.shape_name, tex.image_count              # ('cube map', 6)
    tex.to_bytes("ktx2", zstd=19)                # KTX 2.0 bytes, levels zstd-compressed
    tex.write("sky.ktx2", zstd=19)               # the container by the extension
)doc";

}  // namespace

py::bytes texture_to_bytes(const CompressedTexture& texture, const std::string& container,
                           int zstd) {
  const ContainerFormat format = container == "pvr"    ? ContainerFormat::pvr3
                                 : container == "ktx"  ? ContainerFormat::ktx1
                                 : container == "ktx2" ? ContainerFormat::ktx2
                                                       : ContainerFormat::unknown;
  if (format == ContainerFormat::unknown) {
    throw py::value_error("container: '" + container + "' is not one of 'pvr', 'ktx', 'ktx2'");
  }
  check(check_zstd(zstd, format == ContainerFormat::ktx2, "container='ktx2'"));
  std::vector<std::uint8_t> bytes;
  {
    py::gil_scoped_release release;
    bytes = unwrap(texture_file::serialise_texture(texture, format, {zstd}));
  }
  return py::bytes(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

void write_texture(const std::filesystem::path& path, const CompressedTexture& texture, int zstd) {
  const std::string name = path.string();
  if (zstd != 0) {
    const bool ktx2 = texture_file::container_from_extension(name) == ContainerFormat::ktx2;
    check(check_zstd(zstd, ktx2, "a .ktx2 path"));
  }
  py::gil_scoped_release release;
  check(texture_file::write_texture_file(name, texture, {zstd}));
}

CompressedTexture texture_from_bytes(const py::bytes& data, const std::string& name) {
  const std::string_view view = data;  // the bytes object outlives the call
  py::gil_scoped_release release;
  return unwrap(texture_file::parse_texture(
      std::span(reinterpret_cast<const std::uint8_t*>(view.data()), view.size()), name));
}

void register_texture(py::module_& m) {
  py::class_<CompressedTexture>(m, "Texture", kTextureDoc)
      .def_readonly("width", &CompressedTexture::width, "Level 0 width in texels.")
      .def_readonly("height", &CompressedTexture::height, "Level 0 height in texels.")
      .def_readonly("has_alpha", &CompressedTexture::has_alpha, "RGBA (True) or RGB format.")
      .def_readonly("srgb", &CompressedTexture::srgb, "sRGB colour space flag.")
      .def_readonly("premultiplied", &CompressedTexture::premultiplied,
                    "Colour is premultiplied by alpha (encode(premultiply=True); the PVR v3 "
                    "flag, the KTX 2.0 DFD flag; KTX 1.1 cannot say it).")
      .def_readonly("faces", &CompressedTexture::faces,
                    "1, or 6 for a cube map (+X, -X, +Y, -Y, +Z, -Z).")
      .def_readonly("layers", &CompressedTexture::layers, "Array layers (1 unless an array).")
      .def_readonly("array", &CompressedTexture::array,
                    "An array texture (even of one layer; PVR v3 cannot say so for one layer).")
      .def_property_readonly("shape_name", &texture_file::texture_shape_name,
                             "'2D texture', 'cube map', 'array of 3 layers', 'cube map array "
                             "of 2 layers' (the `shape` of `tessera info --json`).")
      .def_property_readonly("image_count", &CompressedTexture::image_count,
                             "Images per level: faces x layers.")
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
          "Compressed data of each level (list of bytes: the level's images, layer-major then "
          "face, each of Morton-ordered 64-bit blocks).")
      .def(
          "level_shape",
          [](const CompressedTexture& t, int level) {
            if (level < 0 || level >= t.level_count()) {
              throw py::index_error("level " + std::to_string(level) + " is out of range");
            }
            return py::make_tuple(t.level_height(level), t.level_width(level));
          },
          "level"_a, "(height, width) of a level.")
      .def("decode", &decode_images, "level"_a = 0, "layer"_a = py::none(), "face"_a = py::none(),
           "threads"_a = 0, "Same as tessera.decode(self, ...).")
      .def(
          "write",
          [](const CompressedTexture& t, const std::filesystem::path& path, int zstd) {
            write_texture(path, t, zstd);
          },
          "path"_a, "zstd"_a = 0,
          "Write a .pvr, .ktx or .ktx2 file (container by extension), atomically; `zstd` (1-22, "
          ".ktx2 only) compresses the levels with Zstandard, as `tessera compress --zstd`.")
      .def("to_bytes", &texture_to_bytes, "container"_a = "pvr", "zstd"_a = 0,
           "The file bytes of the 'pvr' (PVR v3), 'ktx' (KTX 1.1) or 'ktx2' (KTX 2.0) "
           "container; `zstd` (1-22, 'ktx2' only) compresses the levels with Zstandard.")
      .def("__repr__", &repr)
      .def("__eq__", &equal)
      .def(py::pickle(&pickle_state, &unpickle));
}

}  // namespace tessera::python
