#!/usr/bin/env bash
# Builds the Debian packages of debian/ (libtessera0, libtessera-dev, tessera, python3-tessera)
# and checks them; not part of scripts/test.sh (it rebuilds the whole tree):
#   1. dpkg-buildpackage -us -uc -b (debhelper 13, CMake + Ninja, no tests: scripts/test.sh has
#      them); the .deb files, .changes and build log go to build-packages/;
#   2. lintian on the .changes: any error fails (warnings are printed);
#   3. the packages unpacked with dpkg-deb -x into a scratch root, and from there alone:
#      `tessera compress`, the C consumer (tests/c_api/consumer.c, -std=c99 -pedantic -Werror,
#      pkg-config from the root's tessera.pc) and the ctypes consumer on the root's
#      libtessera.so.0 must write the same KTX 2.0 bytes; the Python module imports.
# Usage: bash scripts/package.sh   (after bash scripts/setup.sh)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
src="$PWD"
out="$src/build-packages"
jobs="${TESSERA_PACKAGE_JOBS:-$(nproc)}"
# What debian/control builds with (scripts/setup.sh installs it all, debhelper and lintian too).
dpkg-checkbuilddeps || { echo "FAIL: run bash scripts/setup.sh first"; exit 1; }
command -v lintian >/dev/null || { echo "FAIL: no lintian (bash scripts/setup.sh installs it)"; exit 1; }

version=$(sed -nE 's/^project\(tessera VERSION ([0-9.]+).*/\1/p' CMakeLists.txt)
deb_version=$(dpkg-parsechangelog -S Version)
if [ "$version" != "$deb_version" ]; then
  echo "FAIL: CMakeLists.txt says $version, debian/changelog $deb_version (add a changelog entry)"
  exit 1
fi

echo "== dpkg-buildpackage"
rm -rf "$out"
mkdir -p "$out"
arch=$(dpkg-architecture -qDEB_HOST_ARCH)
parent=$(dirname "$src")
DEB_BUILD_OPTIONS="nocheck parallel=$jobs" dpkg-buildpackage -us -uc -b >"$out/build.log" 2>&1 || {
  tail -40 "$out/build.log"
  echo "FAIL: dpkg-buildpackage (log: $out/build.log)"
  exit 1
}
for f in "$parent"/*_"${deb_version}"_"$arch".deb "$parent"/*_"${deb_version}"_"$arch".ddeb \
  "$parent/tessera_${deb_version}_$arch.changes" "$parent/tessera_${deb_version}_$arch.buildinfo"; do
  [ -e "$f" ] && mv "$f" "$out/"
done
ls "$out"

echo "== lintian"
lintian --fail-on error --info "$out/tessera_${deb_version}_$arch.changes" | tee "$out/lintian.txt"

echo "== the unpacked packages, alone"
root="$out/root"
for deb in "$out"/*.deb; do dpkg-deb -x "$deb" "$root"; done
multiarch=$(dpkg-architecture -qDEB_HOST_MULTIARCH)
libdir="$root/usr/lib/$multiarch"
work="$out/check"
mkdir -p "$work"
python3 tests/c_api/make_test_image.py "$work/in.rgba" "$work/in.png"
export LD_LIBRARY_PATH="$libdir"
"$root/usr/bin/tessera" compress "$work/in.png" -o "$work/cli.ktx2" --quality fast --mipmaps \
  --alpha-bleed --zstd 5 -q
PKG_CONFIG_PATH="$libdir/pkgconfig" cc -std=c99 -Wall -Wextra -Werror -pedantic \
  tests/c_api/consumer.c $(PKG_CONFIG_PATH="$libdir/pkgconfig" pkg-config --cflags --libs tessera) \
  -o "$work/consumer"
# (ldd's output captured first: `ldd | grep -q` under pipefail fails when grep stops reading early)
loaded=$(ldd "$work/consumer")
if ! grep -q "=> $libdir/libtessera.so.0 " <<<"$loaded"; then
  echo "FAIL: the consumer does not load the unpacked libtessera.so.0"
  ldd "$work/consumer"
  exit 1
fi
"$work/consumer" "$work/in.rgba" 64 64 "$work/c.ktx2" fast
python3 tests/c_api/consumer_ctypes.py "$libdir/libtessera.so.0" "$work/in.rgba" 64 64 \
  "$work/py.ktx2" fast
cmp "$work/c.ktx2" "$work/cli.ktx2"
cmp "$work/py.ktx2" "$work/cli.ktx2"
PYTHONPATH="$root/usr/lib/python3/dist-packages" python3 -c \
  "import tessera; assert tessera.__file__.startswith('$root'), tessera.__file__; print('python3-tessera imports from', tessera.__file__)"
packages=$(find "$out" -maxdepth 1 -name '*.deb' ! -name '*-dbgsym_*' | wc -l)
echo "ok: $packages packages (and their -dbgsym); lintian without errors; the unpacked CLI, C and ctypes consumers wrote the same bytes"
