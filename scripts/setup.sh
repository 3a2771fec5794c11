#!/usr/bin/env bash
# Sets up everything tessera needs on Debian 12, then configures and builds it.
# Idempotent: packages already installed are not touched, the PVRTexTool oracle is fetched once
# into a cache, and an up-to-date build is a no-op. Run as root (or with sudo available).
#
#   bash scripts/setup.sh            # Release build in build/ (CLI at build/bin/tessera)
#   bash scripts/setup.sh --arm64    # the same, plus what the arm64 stage of scripts/test.sh
#                                    # needs: the AArch64 cross compiler, qemu-user and the arm64
#                                    # (multiarch) libraries the library links
#
# Environment:
#   TESSERA_CACHE   where peers are cached (default: ${XDG_CACHE_HOME:-$HOME/.cache}/tessera)
#   TESSERA_BUILD   build folder (default: build)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

log() { printf '[setup] %s\n' "$*"; }

arm64=0
for arg in "$@"; do
  case "$arg" in
    --arm64) arm64=1 ;;
    *) echo "usage: bash scripts/setup.sh [--arm64]" >&2; exit 2 ;;
  esac
done

# --- Debian packages -------------------------------------------------------------------------
packages=(
  build-essential cmake ninja-build pkg-config git ca-certificates
  clang lld libclang-rt-14-dev                 # second compiler, sanitizers, libFuzzer
  clang-format                                 # the test command checks the C++ formatting
  libspng-dev zlib1g-dev libstb-dev            # PNG, zlib, JPEG/TGA/BMP
  libdeflate-dev                               # PNG fast path (inflate)
  libzstd-dev                                  # KTX 2.0 Zstandard supercompression
  libtbb-dev                                   # parallel_for
  libcli11-dev nlohmann-json3-dev              # CLI, --json
  libtinyobjloader-dev libtinygltf-dev         # OBJ and glTF scenes
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri  # GL runtime: EGL + OpenGL 4.5 (Mesa llvmpipe)
  glslang-tools                                # glslangValidator checks the shipped GLSL
  spirv-tools                                  # spirv-val/-dis: the GLSL's Vulkan SPIR-V
  pybind11-dev python3-dev python3-pytest      # the Python module and its tests
  python3-distributed                          # tessera.batch on a Dask cluster
  chromium                                     # the report and view tests drive it headless
  libglfw3-dev xvfb xauth                      # engine examples/tests on a real GLX window
  libvulkan-dev mesa-vulkan-drivers            # Vulkan loader + headers, lavapipe (CPU Vulkan)
  vulkan-validationlayers vulkan-tools         # validation layer (a message fails a test)
  glslc libshaderc-dev                         # GLSL to SPIR-V: offline (glslc) and at create
  libcpp-httplib-dev                           # `tessera view`'s local HTTP server
  abigail-tools                                # abidw/abidiff: the C ABI against its baseline (c_api_abi)
  debhelper dh-python lintian                  # scripts/package.sh: the Debian packages, checked
  libgtest-dev libgmock-dev libbenchmark-dev   # tests, benchmarks
  python3 python3-numpy python3-skimage python3-pil  # independent SSIM/PSNR, image checks
)
if ((arm64)); then
  # Cross-compiling and running the library for AArch64 (tests/arch/pvrtc_arch_bytes.sh,
  # cmake/aarch64-linux-gnu.cmake): Debian's cross g++, qemu-aarch64, and the arm64 builds of
  # the libraries the library and its tests link (Multi-Arch: same, beside the host's; header-only
  # ones like nlohmann-json and CLI11 are architecture-independent and already above).
  packages+=(g++-aarch64-linux-gnu qemu-user)
  for p in libtbb-dev libspng-dev zlib1g-dev libdeflate-dev libzstd-dev libstb-dev \
    libtinyobjloader-dev libtinygltf-dev libgtest-dev; do
    packages+=("$p:arm64")
  done
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
# npm ships the PVRTexTool and ktx-parse oracles; any Node.js install with npm will do.
command -v npm >/dev/null 2>&1 || missing+=(nodejs npm)
if ((${#missing[@]})); then
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  if ((arm64)) && ! dpkg --print-foreign-architectures | grep -qx arm64; then
    log "adding the arm64 architecture (multiarch)"
    $SUDO dpkg --add-architecture arm64
  fi
  log "installing: ${missing[*]}"
  $SUDO apt-get update -q
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# --- PVRTexToolCLI 4.17 (test oracle and benchmark peer; never committed) --------------------
cache="${TESSERA_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/tessera}"
pvrtextool="$cache/peers/PVRTexToolCLI"
if [ ! -x "$pvrtextool" ]; then
  log "fetching PVRTexToolCLI from the npm package texture-compressor@1.0.2"
  tmp="$(mktemp -d)"
  trap 'rm -rf "$tmp"' EXIT
  (cd "$tmp" && npm pack --silent texture-compressor@1.0.2 >/dev/null && tar xzf texture-compressor-1.0.2.tgz)
  mkdir -p "$cache/peers"
  install -m 0755 "$tmp/package/bin/linux/PVRTexToolCLI" "$pvrtextool.tmp"
  mv "$pvrtextool.tmp" "$pvrtextool"
fi

# --- ktx-parse 2.0.0 + fzstd 0.1.1 (KTX 2.0 test oracle: tests/oracle/ktx2_oracle.mjs) ------
# ktx-parse reads the container but leaves Zstandard levels compressed; fzstd, a separate
# pure-JavaScript decoder, inflates them. Exact versions, installed once into the cache.
ktx_parse="$cache/peers/ktx-parse"
if [ ! -f "$ktx_parse/node_modules/ktx-parse/package.json" ] ||
  [ ! -f "$ktx_parse/node_modules/fzstd/package.json" ]; then
  log "installing ktx-parse@2.0.0 and fzstd@0.1.1 (npm) into $ktx_parse"
  mkdir -p "$ktx_parse"
  (cd "$ktx_parse" && npm install --silent --no-audit --no-fund --save-exact \
    ktx-parse@2.0.0 fzstd@0.1.1 >/dev/null)
fi

# --- puppeteer-core 24.43.1 (drives Debian's chromium in tests/cli/view_browser_test.py) ------
# Node 18 or later (Debian 12 has 18); no browser download: the test uses /usr/bin/chromium.
puppeteer="$cache/peers/puppeteer"
if [ ! -f "$puppeteer/node_modules/puppeteer-core/package.json" ]; then
  log "installing puppeteer-core@24.43.1 (npm) into $puppeteer"
  mkdir -p "$puppeteer"
  (cd "$puppeteer" && PUPPETEER_SKIP_DOWNLOAD=1 npm install --silent --no-audit --no-fund \
    --save-exact puppeteer-core@24.43.1 >/dev/null)
fi

# --- Configure and build ---------------------------------------------------------------------
build="${TESSERA_BUILD:-build}"
log "building in $build/"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DTESSERA_WERROR=ON \
  -DTESSERA_PVRTEXTOOL="$pvrtextool" -DTESSERA_KTX_PARSE="$ktx_parse" \
  -DTESSERA_PUPPETEER="$puppeteer" >/dev/null
cmake --build "$build"
