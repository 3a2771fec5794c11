"""tessera's C API from Python through ctypes alone (no pybind11, no numpy): what a tool in
another language does with libtessera.so.0 and tessera/tessera_c.h.

    consumer_ctypes.py LIBTESSERA IN.rgba WIDTH HEIGHT OUT.ktx2 fast|normal|high

does what tests/c_api/consumer.c does (a mip chain with alpha bleed, a Zstandard KTX 2.0 file in
library memory, read back from memory, level 0 decoded into a padded buffer and measured), checks
that the structs declared here have the sizes the library's init functions set, and that a
progress callback that returns 1 cancels an encode. tests/c_api/consumer_test.sh compares the
file with `tessera compress`'s. Exit 0 on success, 1 with the library's message otherwise.
"""
import ctypes as C
import sys

SUCCESS, ERROR_BUFFER_TOO_SMALL, ERROR_CANCELLED = 0, 8, 10
QUALITY = {"fast": 0, "normal": 1, "high": 2}
FLAG_MIPMAPS, FLAG_ALPHA_BLEED = 0x1, 0x8
CONTAINER_KTX2 = 2

PROGRESS = C.CFUNCTYPE(C.c_int, C.c_void_p, C.c_double)


class ContextConfig(C.Structure):
    _fields_ = [("struct_size", C.c_uint32), ("threads", C.c_int32), ("progress", PROGRESS),
                ("progress_user_data", C.c_void_p)]


class Image(C.Structure):
    _fields_ = [("pixels", C.c_void_p), ("width", C.c_uint32), ("height", C.c_uint32),
                ("row_pitch", C.c_size_t), ("has_alpha", C.c_int32)]


class EncodeOptions(C.Structure):
    _fields_ = [("struct_size", C.c_uint32), ("format", C.c_int), ("quality", C.c_int),
                ("iterations", C.c_int32), ("exact_search_rounds", C.c_int32),
                ("flags", C.c_uint32), ("mip_levels", C.c_int32), ("mip_filter", C.c_int),
                ("faces", C.c_int32), ("array", C.c_int32)]


class TextureInfo(C.Structure):
    _fields_ = [("struct_size", C.c_uint32), ("format", C.c_int), ("width", C.c_uint32),
                ("height", C.c_uint32), ("levels", C.c_uint32), ("faces", C.c_uint32),
                ("layers", C.c_uint32), ("array", C.c_int32), ("has_alpha", C.c_int32),
                ("srgb", C.c_int32), ("premultiplied", C.c_int32)]


class Metrics(C.Structure):
    _fields_ = [("struct_size", C.c_uint32), ("mse_rgb", C.c_double), ("psnr_rgb", C.c_double),
                ("has_alpha", C.c_int32), ("mse_alpha", C.c_double), ("psnr_alpha", C.c_double),
                ("ssim", C.c_double), ("max_abs", C.c_int32)]


def bind(lib):
    """Declares the prototypes used here (every argument and result typed)."""
    P = C.c_void_p
    sigs = {
        "tessera_error_string": (C.c_char_p, [C.c_int]),
        "tessera_version": (C.c_char_p, []),
        "tessera_context_config_init": (C.c_int, [C.POINTER(ContextConfig)]),
        "tessera_context_create": (C.c_int, [C.POINTER(ContextConfig), C.POINTER(P)]),
        "tessera_context_free": (None, [P]),
        "tessera_context_last_error": (C.c_char_p, [P]),
        "tessera_encode_options_init": (C.c_int, [C.POINTER(EncodeOptions)]),
        "tessera_encode": (C.c_int, [P, C.POINTER(Image), C.c_uint32, C.POINTER(EncodeOptions),
                                     C.POINTER(P)]),
        "tessera_texture_write_alloc": (C.c_int, [P, P, C.c_int, C.c_int32, C.POINTER(P),
                                                  C.POINTER(C.c_size_t)]),
        "tessera_texture_read_memory": (C.c_int, [P, P, C.c_size_t, C.POINTER(P)]),
        "tessera_texture_get_info": (C.c_int, [P, C.POINTER(TextureInfo)]),
        "tessera_texture_decode": (C.c_int, [P, P, C.c_uint32, C.c_uint32, C.c_uint32, P,
                                             C.c_size_t, C.c_size_t]),
        "tessera_texture_free": (None, [P]),
        "tessera_compare": (C.c_int, [P, C.POINTER(Image), C.POINTER(Image), C.c_int32,
                                      C.POINTER(Metrics)]),
        "tessera_free": (None, [P]),
    }
    for name, (restype, argtypes) in sigs.items():
        f = getattr(lib, name)
        f.restype, f.argtypes = restype, argtypes
    return lib


class Failure(Exception):
    pass


def main(argv):
    libpath, raw_path, width, height, out_path, quality = argv[1:]
    lib = bind(C.CDLL(libpath))
    width, height = int(width), int(height)
    texels = open(raw_path, "rb").read()
    if len(texels) != width * height * 4:
        raise Failure(f"{raw_path} is not {width} x {height} RGBA8 texels")
    context = C.c_void_p()

    def check(code, what):
        if code != SUCCESS:
            message = lib.tessera_context_last_error(context).decode()
            raise Failure(f"{what}: {lib.tessera_error_string(code).decode()}: {message}")

    fractions = []

    @PROGRESS
    def on_progress(_user, fraction):
        fractions.append(fraction)
        return 0

    config = ContextConfig()
    check(lib.tessera_context_config_init(C.byref(config)), "config")
    if config.struct_size != C.sizeof(config):
        raise Failure(f"tessera_context_config: {config.struct_size} bytes, here {C.sizeof(config)}")
    config.threads, config.progress = 2, on_progress
    check(lib.tessera_context_create(C.byref(config), C.byref(context)), "context")
    try:
        buffer = C.create_string_buffer(texels, len(texels))
        image = Image(C.cast(buffer, C.c_void_p), width, height, 0, 1)
        options = EncodeOptions()
        check(lib.tessera_encode_options_init(C.byref(options)), "options")
        if options.struct_size != C.sizeof(options):
            raise Failure(f"tessera_encode_options: {options.struct_size} bytes, here "
                          f"{C.sizeof(options)}")
        options.quality = QUALITY[quality]
        options.flags = FLAG_MIPMAPS | FLAG_ALPHA_BLEED
        texture = C.c_void_p()
        check(lib.tessera_encode(context, C.byref(image), 1, C.byref(options), C.byref(texture)),
              "encode")
        data, size = C.c_void_p(), C.c_size_t()
        try:
            check(lib.tessera_texture_write_alloc(context, texture, CONTAINER_KTX2, 5,
                                                  C.byref(data), C.byref(size)), "KTX2 file")
        finally:
            lib.tessera_texture_free(texture)
        file = C.string_at(data, size.value)
        lib.tessera_free(data)
        with open(out_path, "wb") as f:
            f.write(file)
        if not fractions or fractions[-1] != 1.0 or fractions != sorted(fractions):
            raise Failure(f"progress fractions {fractions}")

        back = C.c_void_p()
        check(lib.tessera_texture_read_memory(context, file, len(file), C.byref(back)), "read")
        try:
            info = TextureInfo(struct_size=C.sizeof(TextureInfo))
            check(lib.tessera_texture_get_info(back, C.byref(info)), "info")
            pitch = info.width * 4 + 16
            decoded = C.create_string_buffer(pitch * info.height)
            check(lib.tessera_texture_decode(context, back, 0, 0, 0, decoded, pitch,
                                             pitch * info.height), "decode")
        finally:
            lib.tessera_texture_free(back)
        result = Image(C.cast(decoded, C.c_void_p), info.width, info.height, pitch,
                       info.has_alpha)
        metrics = Metrics(struct_size=C.sizeof(Metrics))
        check(lib.tessera_compare(context, C.byref(image), C.byref(result), 1,
                                  C.byref(metrics)), "compare")
        print(f"tessera {lib.tessera_version().decode()}: {info.width}x{info.height}, "
              f"{info.levels} levels, {len(file)} bytes, PSNR {metrics.psnr_rgb:.2f} dB, "
              f"SSIM {metrics.ssim:.4f}, {len(fractions)} progress calls")

        # A callback that returns nonzero cancels: an error, and no texture.
        config.progress = PROGRESS(lambda _user, _fraction: 1)
        cancelling = C.c_void_p()
        check(lib.tessera_context_create(C.byref(config), C.byref(cancelling)), "context")
        texture = C.c_void_p(1)
        code = lib.tessera_encode(cancelling, C.byref(image), 1, C.byref(options),
                                  C.byref(texture))
        lib.tessera_context_free(cancelling)
        if code != ERROR_CANCELLED or texture.value is not None:
            raise Failure(f"a cancelling callback gave {code}, texture {texture.value}")
    finally:
        lib.tessera_context_free(context)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv))
    except Failure as e:
        print(f"consumer_ctypes: {e}", file=sys.stderr)
        sys.exit(1)
