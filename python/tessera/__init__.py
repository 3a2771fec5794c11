"""tessera: PVRTC1 texture compression from Python.

The functions are bindings of the C++ library behind the ``tessera`` command-line tool, and give
the same bytes::

    import numpy as np, tessera
    rgba = np.zeros((256, 256, 4), np.uint8)            # or tessera.read_image("in.png")
    tex = tessera.encode(rgba, quality="normal", mipmaps=True)
    tex.write("out.pvr")        # the bytes of: tessera compress in.png -o out.pvr --mipmaps
    pixels = tessera.decode(tex)                        # (H, W, 4) RGBA, (H, W, 3) RGB texture

* ``encode(array, *, format, quality, mipmaps, srgb, threads, iterations, exact_search_rounds,
  resize_pot)`` -> ``Texture``; ``encode_file(path, ...)`` reads the image with tessera's reader
  first (exactly ``tessera compress PATH``).
* ``Texture``: ``width``, ``height``, ``format`` ('pvrtc1-4' / 'pvrtc1-2'), ``srgb``,
  ``has_alpha``, ``levels`` (list of bytes), ``write(path)`` (.pvr / .ktx by extension),
  ``to_bytes(container='pvr'|'ktx')``, ``decode(level)``; picklable.
* ``decode(texture, level=0)``, ``read(path)``, ``write(path, texture)``, ``from_bytes(data)``,
  ``read_image(path)``, ``write_image(path, array)`` (PNG), ``compare(a, b)`` (the keys of
  ``tessera compare --json``).
* Errors: ``tessera.Error`` (a ``RuntimeError``; ``.code`` is the category, the text is the
  message the CLI prints) and ``tessera.InvalidArgumentError`` (also a ``ValueError``); wrong
  array types, dtypes or shapes and bad keyword values raise ``ValueError``.
* The GIL is released while encoding, decoding, reading, writing and comparing, so threads run
  in parallel.

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
    read,
    read_image,
    write,
    write_image,
)

#: The option names and defaults of ``encode`` / ``tessera compress`` (besides ``threads``).
ENCODE_DEFAULTS = {
    "format": "pvrtc1-4",
    "quality": "normal",
    "mipmaps": False,
    "srgb": False,
    "iterations": -1,
    "exact_search_rounds": 0,
    "resize_pot": False,
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
    "read",
    "read_image",
    "write",
    "write_image",
]
