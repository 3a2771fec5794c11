"""tessera: PVRTC1 texture compression from Python.

The functions are bindings of the C++ library behind the ``tessera`` command-line tool, and give
the same bytes::

    import numpy as np, tessera
    rgba = np.zeros((256, 256, 4), np.uint8)            # or tessera.read_image("in.png")
    tex = tessera.encode(rgba, quality="normal", mipmaps=True)
    tex.write("out.pvr")        # the bytes of: tessera compress in.png -o out.pvr --mipmaps
    pixels = tessera.decode(tex)                        # (H, W, 4) RGBA, (H, W, 3) RGB texture

Real assets: a cube map from six faces, an array from a leading axis, sprites with
premultiplied or bled alpha, normal maps, KTX 2.0 with Zstandard::

    faces = np.stack([tessera.read_image(f"sky_{f}.png") for f in ("px", "nx", "py", "ny",
                                                                  "pz", "nz")])
    sky = tessera.encode(faces, cube=True, mipmaps=True, srgb=True)   # faces: (6, H, W, C)
    sky.shape_name, sky.faces                            # ('cube map', 6)
    tessera.decode(sky).shape                            # (6, H, W, C); face=2 gives (H, W, C)
    sky.write("sky.ktx2", zstd=19)     # tessera compress sky_{px,nx,py,ny,pz,nz}.png --cube
                                       #   --mipmaps --srgb -o sky.ktx2 --zstd 19
    tiles = tessera.encode([a, b, c], array=True)        # or an (L, H, W, C) array
    sprite = tessera.encode(rgba, premultiply=True)      # or alpha_bleed=True (straight alpha)
    normals = tessera.encode(nrm, normal_map=True, mip_levels=4, mip_filter="kaiser")
    tessera.compare(nrm, tessera.decode(normals), normal=True)["angular_error_mean_deg"]

* ``encode(x, *, format, quality, mipmaps, srgb, threads, iterations, exact_search_rounds,
  resize_pot, mip_levels, mip_filter, flip_y, premultiply, alpha_bleed, alpha_weighted,
  normal_map, cube, array, name)`` -> ``Texture``: ``x`` is one (H, W, 3|4) uint8 array, or
  with ``cube`` / ``array`` a (6, H, W, C) / (L, H, W, C) / (L, 6, H, W, C) array (or
  (6L, H, W, C)), or a list of (H, W, C) arrays, layer-major then face.
  ``encode_file(path, ...)`` reads the image with tessera's reader first (exactly
  ``tessera compress PATH``); with ``cube`` / ``array`` it takes a list of paths.
  The keywords are the CLI's options (``ENCODE_DEFAULTS``); ``premultiply`` on an image without
  alpha warns (``UserWarning``) and leaves it as it is, as the CLI does.
* ``Texture``: ``width``, ``height``, ``format`` ('pvrtc1-4' / 'pvrtc1-2'), ``srgb``,
  ``has_alpha``, ``premultiplied``, ``faces`` (1 or 6), ``layers``, ``array``, ``shape_name``
  ('2D texture', 'cube map', 'array of 3 layers', ...), ``image_count``, ``levels`` (list of
  bytes: every image of the level, layer-major then face), ``write(path, zstd=0)`` (.pvr / .ktx /
  .ktx2 by extension), ``to_bytes(container='pvr'|'ktx'|'ktx2', zstd=0)``, ``decode(...)``;
  comparable with ``==`` and picklable (every field kept).
* ``decode(texture, level=0, layer=None, face=None)``: (H, W, C) for a 2D texture, (6, H, W, C)
  for a cube map, (L, H, W, C) for an array, (L, 6, H, W, C) for a cube map array; ``layer`` /
  ``face`` select one layer / face (its axis goes).
* ``read(path)``, ``write(path, texture, zstd=0)``, ``from_bytes(data)`` (PVR v3, KTX 1.1,
  KTX 2.0), ``read_image(path)``, ``write_image(path, array)`` (PNG), ``compare(a, b, *,
  premultiplied=False, normal=False)`` (the keys of ``tessera compare --json [--premultiplied]
  [--normal]``); ``measure_level0(texture, images)``: the error of level 0 against the images
  it was encoded from, pooled over faces and layers (what ``tessera compress --json`` reports).
* Errors: ``tessera.Error`` (a ``RuntimeError``; ``.code`` is the category, the text is the
  message the CLI prints, with keywords where the CLI names its flags: ``resize_pot=True`` for
  ``--resize-pot``) and ``tessera.InvalidArgumentError`` (also a ``ValueError``); wrong array
  types, dtypes or shapes and bad keyword values raise ``ValueError``.
* The GIL is released while encoding, decoding, reading, writing and comparing, so threads run
  in parallel.

``run_seams(*, msaa, frames, quality_frames, width, height, reference_factor, near_seam_pixels,
threads, markdown=False)`` and ``run_aa(*, ssaa, width, height, frames, lights, heavy, threads,
markdown=False)`` run the papers' experiments on the CPU and return the dict of ``tessera seams
--json`` / ``tessera aa --json`` (the library's result format), or the Markdown report.

``python3 -m tessera.batch SRC DST`` compresses a directory tree over a Dask cluster (see
``tessera.batch``).
"""

from ._tessera import (  # noqa: F401  (re-exported API)
    Error,
    InvalidArgumentError,
    Texture,
    __version__,
    compare,
    decode,
    encode,
    encode_file,
    from_bytes,
    is_up_to_date,
    measure_level0,
    read,
    read_image,
    run_aa,
    run_seams,
    up_to_date_record,
    write,
    write_image,
    write_up_to_date_record,
)

#: The option names and defaults of ``encode`` / ``tessera compress``: the per-image options
#: (besides ``threads``, ``name`` and the shape keywords ``cube`` / ``array``), which
#: ``tessera.batch`` takes too.
ENCODE_DEFAULTS = {
    "format": "pvrtc1-4",
    "quality": "normal",
    "mipmaps": False,
    "srgb": False,
    "iterations": -1,
    "exact_search_rounds": 0,
    "resize_pot": False,
    "mip_levels": 0,
    "mip_filter": "box",
    "flip_y": False,
    "premultiply": False,
    "alpha_bleed": False,
    "alpha_weighted": False,
    "normal_map": False,
}

#: File extensions ``encode_file`` and ``tessera.batch`` take (tessera's image readers).
IMAGE_EXTENSIONS = (".png", ".jpg", ".jpeg", ".tga", ".bmp")

__all__ = [
    "ENCODE_DEFAULTS",
    "Error",
    "IMAGE_EXTENSIONS",
    "InvalidArgumentError",
    "Texture",
    "__version__",
    "compare",
    "decode",
    "encode",
    "encode_file",
    "from_bytes",
    "is_up_to_date",
    "measure_level0",
    "read",
    "read_image",
    "run_aa",
    "run_seams",
    "up_to_date_record",
    "write",
    "write_image",
    "write_up_to_date_record",
]
