#!/usr/bin/env bash
# The C API from outside, against an installed tree (the CTest c_api_consumers):
#  1. `cmake --install` into a scratch prefix;
#  2. tests/c_api/consumer.c built with `cc -std=c99 -Wall -Wextra -Werror -pedantic` and
#     `pkg-config --cflags --libs tessera` from that prefix alone (with clang too, when there);
#     it must load libtessera.so.0 from the prefix;
#  3. a generated 64x64 RGBA image encoded by the C program, by tests/c_api/consumer_ctypes.py
#     (Python ctypes on the installed libtessera.so.0) and by the build's `tessera compress`
#     from the same texels as a PNG, with the same options (mip chain, alpha bleed, KTX 2.0 with
#     Zstandard level 5): the three files must be equal byte for byte;
#  4. controls: another quality gives another file (so equal files mean something), and the
#     consumer fails with the library's message on a truncated input.
# Usage: consumer_test.sh SOURCE_DIR BINARY_DIR
set -euo pipefail
src="$1"
bin="$2"
here="$src/tests/c_api"
work="$bin/test-tmp/c_api_consumers"
rm -rf "$work"
mkdir -p "$work"
cmake --install "$bin" --prefix "$work/prefix" >/dev/null
pc=$(find "$work/prefix" -path '*/pkgconfig/tessera.pc' | head -1)
[ -n "$pc" ] || { echo "FAIL: no tessera.pc installed under $work/prefix"; exit 1; }
export PKG_CONFIG_PATH
PKG_CONFIG_PATH=$(dirname "$pc")
libdir=$(pkg-config --variable=libdir tessera)
read -r -a flags <<<"$(pkg-config --cflags --libs tessera)"

compilers=("${CC:-cc}")
if command -v clang >/dev/null && [ "${CC:-cc}" != clang ]; then compilers+=(clang); fi
for compiler in "${compilers[@]}"; do
  "$compiler" -std=c99 -Wall -Wextra -Werror -pedantic "$here/consumer.c" "${flags[@]}" \
    -Wl,-rpath,"$libdir" -o "$work/consumer-$(basename "$compiler")"
done
consumer="$work/consumer-$(basename "${compilers[0]}")"
loaded=$(ldd "$consumer" | awk '$1 == "libtessera.so.0" { print $3 }')
if [ -z "$loaded" ] || [ "$(readlink -f "$loaded")" != "$(readlink -f "$libdir/libtessera.so.0")" ]; then
  echo "FAIL: the consumer loads libtessera.so.0 from '$loaded', not from $libdir:"
  ldd "$consumer"
  exit 1
fi

# The image: raw RGBA8 for the consumers, the same texels as a PNG for the CLI.
/usr/bin/env python3 "$(dirname "${BASH_SOURCE[0]}")/make_test_image.py" "$work/in.rgba" "$work/in.png"

"$bin/bin/tessera" compress "$work/in.png" -o "$work/cli.ktx2" --quality fast --mipmaps \
  --alpha-bleed --zstd 5 -q
for compiler in "${compilers[@]}"; do
  "$work/consumer-$(basename "$compiler")" "$work/in.rgba" 64 64 "$work/c.ktx2" fast
  cmp "$work/c.ktx2" "$work/cli.ktx2" || { echo "FAIL: $compiler consumer's file differs from tessera compress's"; exit 1; }
done
/usr/bin/env python3 "$here/consumer_ctypes.py" "$libdir/libtessera.so.0" "$work/in.rgba" 64 64 \
  "$work/py.ktx2" fast
cmp "$work/py.ktx2" "$work/cli.ktx2" || { echo "FAIL: the ctypes consumer's file differs from tessera compress's"; exit 1; }

# Controls.
"$consumer" "$work/in.rgba" 64 64 "$work/normal.ktx2" normal >/dev/null
if cmp -s "$work/normal.ktx2" "$work/cli.ktx2"; then
  echo "FAIL (control): quality normal gave the same file as quality fast"
  exit 1
fi
set +e
out=$(printf '\x89PNG' >"$work/short.rgba" && "$consumer" "$work/short.rgba" 64 64 "$work/x.ktx2" fast 2>&1)
rc=$?
set -e
if [ $rc -eq 0 ]; then echo "FAIL (control): the consumer accepted a truncated input: $out"; exit 1; fi
echo "ok: C99 (${compilers[*]}) and ctypes consumers of the installed libtessera.so.0 wrote tessera compress's bytes ($(stat -c %s "$work/cli.ktx2") bytes)"
