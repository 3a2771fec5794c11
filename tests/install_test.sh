#!/usr/bin/env bash
# Installs the build tree into a scratch prefix and builds examples/consumer against it with
# find_package(tessera), then runs it.
# Usage: install_test.sh SOURCE_DIR BINARY_DIR
set -euo pipefail
src="$1"
bin="$2"
work="$bin/test-tmp/install"
rm -rf "$work"
cmake --install "$bin" --prefix "$work/prefix" >/dev/null
cmake -S "$src/examples/consumer" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/build" >/dev/null
"$work/build/consumer"
