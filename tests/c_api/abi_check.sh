#!/usr/bin/env bash
# The C ABI of libtessera.so.0 against the checked-in baseline (the CTest c_api_abi): abidw
# writes the ABI of the C entry points (their debug information: src/c_api/c_api_entry.cpp,
# built with -g, sees only tessera/tessera_c.h; the library's other exported symbols, the C++
# API, are left out of the file), abidiff compares it with tests/c_api/abi/libtessera.so.0.abi.
# Removing or changing a C function, or changing a struct's or enum's layout, fails; adding a
# function passes (abidiff's summaries: any "N Removed" or "N Changed" with N > 0 fails).
# Controls, on copies of the library's own ABI file: tessera_compare taken away must fail, a
# member of tessera_metrics moved must fail, tessera_compare added (taken from the baseline's
# copy) must pass.
# Usage: abi_check.sh LIBRARY BASELINE.abi            check
#        abi_check.sh LIBRARY BASELINE.abi --update   write the baseline (a deliberate ABI change:
#                                                     commit it with the header change)
set -euo pipefail
lib="$1"
baseline="$2"
mode="${3:-check}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

abi_of() {  # $1 library: its C ABI as abixml on stdout
  abidw --no-corpus-path --no-show-locs --no-comp-dir-path --drop-undefined-syms "$1" |
    grep -vE "<elf-symbol name='([^t]|t[^e]|te[^s]|tes[^s]|tess[^e]|tesse[^r]|tesser[^a]|tessera[^_])"
}

abi_of "$lib" >"$work/current.abi"
if ! grep -q "function-decl name='tessera_encode'" "$work/current.abi"; then
  echo "FAIL: abidw found no debug information for tessera_encode in $lib (built without -g?)"
  exit 1
fi
if [ "$mode" = "--update" ]; then
  cp "$work/current.abi" "$baseline"
  echo "wrote $baseline"
  exit 0
fi

verdict() {  # $1 old.abi $2 new.abi: 0 when new only adds to old; prints the report otherwise
  set +e
  report=$(abidiff "$1" "$2" 2>&1)
  rc=$?
  set -e
  if (((rc & 3) != 0)); then
    echo "abidiff failed ($rc): $report"
    return 2
  fi
  if grep -qE '\b[1-9][0-9]* (Removed|Changed)\b' <<<"$report"; then
    echo "$report"
    return 1
  fi
  return 0
}

# Controls.
python3 - "$work" <<'PY'
import re, sys
work = sys.argv[1]
cur = open(f"{work}/current.abi").read()
decl = re.compile(r"\n *<function-decl name='tessera_compare'.*?</function-decl>", re.S)
sym = re.compile(r"\n *<elf-symbol name='tessera_compare'[^\n]*")
removed = sym.sub("", decl.sub("", cur, count=1), count=1)
assert removed != cur
open(f"{work}/removed.abi", "w").write(removed)
moved, n = re.subn(r"(<data-member[^>]*layout-offset-in-bits=')(\d+)('[^>]*>\s*<var-decl name='ssim')",
                   lambda m: m.group(1) + str(int(m.group(2)) + 64) + m.group(3), cur, count=1)
assert n == 1, "no ssim member in tessera_metrics"
open(f"{work}/moved.abi", "w").write(moved)
PY
if verdict "$work/current.abi" "$work/removed.abi" >/dev/null; then
  echo "FAIL (control): a removed tessera_compare passed"
  exit 1
fi
if verdict "$work/current.abi" "$work/moved.abi" >/dev/null; then
  echo "FAIL (control): a moved tessera_metrics::ssim passed"
  exit 1
fi
if ! verdict "$work/removed.abi" "$work/current.abi" >/dev/null; then
  echo "FAIL (control): an added tessera_compare failed"
  exit 1
fi

if ! verdict "$baseline" "$work/current.abi"; then
  echo "FAIL: the C ABI of $lib removes or changes what $baseline has (above). If that is meant,"
  echo "bump the SONAME or regenerate the baseline: bash tests/c_api/abi_check.sh LIB BASELINE --update"
  exit 1
fi
echo "ok: the C ABI of $(basename "$lib") keeps every function and layout of $(basename "$baseline")"
