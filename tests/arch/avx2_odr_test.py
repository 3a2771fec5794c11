#!/usr/bin/env python3
"""The AVX2 translation units (src/**/*_avx2.cpp, built with -mavx2) define no weak symbol
outside the SIMD wrapper's AVX2 inline namespace (labels unit).

A weak (COMDAT) definition there -- an inline function or template instantiation of external
linkage that the compiler did not inline -- could be the copy the linker keeps for the whole
program, and then run AVX2 instructions on a CPU without AVX2. The wrapper's own functions live
in tessera::simd::avx2 (core/simd_select.h), which only AVX2 code calls; anything else must have
internal linkage. Type information objects (`typeinfo for ...`, `typeinfo name for ...`, which
Clang's -fsanitize=function emits as weak data for function types) hold no code and are not
counted. Skips (77) where the build has no AVX2 objects (not x86-64).

Usage: avx2_odr_test.py NM 'OBJ1;OBJ2;...'
"""
import subprocess
import sys

nm = sys.argv[1]
objects = [o for o in sys.argv[2].split(";") if o.endswith("_avx2.cpp.o") or o.endswith("_avx2.cpp.obj")]
if not objects:
    print("no AVX2 objects in this build")
    sys.exit(77)
bad = []
for obj in objects:
    out = subprocess.run([nm, "-C", "--defined-only", obj], check=True, capture_output=True,
                         text=True).stdout
    for line in out.splitlines():
        parts = line.split(None, 2)
        if len(parts) == 3 and parts[1] in ("W", "V", "u") and \
                not parts[2].startswith("tessera::simd::avx2::") and \
                not parts[2].startswith(("typeinfo for ", "typeinfo name for ")):
            bad.append(f"{obj}: {parts[1]} {parts[2]}")
print(f"{len(objects)} AVX2 objects checked")
for b in bad:
    print("weak symbol outside tessera::simd::avx2:", b)
sys.exit(1 if bad else 0)
