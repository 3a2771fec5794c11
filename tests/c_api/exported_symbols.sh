#!/usr/bin/env bash
# What libtessera.so exports (the CTest c_api_exported_symbols):
#  * its SONAME is SONAME (libtessera.so.<major>);
#  * every defined dynamic symbol (nm -D --defined-only, demangled) is tessera's: a `tessera_` C
#    function, a `tessera::` C++ name, the vtable or type information of a `tessera::` class, or
#    the version node TESSERA_0; no std:: instantiation, no symbol of a statically linked
#    dependency (libdeflate, zstd, stb, tinygltf, ...);
#  * every function tessera/tessera_c.h declares is exported.
# Control: the filter is first shown names it must refuse (a std:: instantiation, a zstd and a
# libdeflate function, a global operator new) and must refuse each.
# Usage: exported_symbols.sh LIBRARY SONAME HEADER
set -euo pipefail
lib="$1"
soname="$2"
header="$3"

foreign() {  # the names on stdin that are not tessera's
  sed -E 's/@.*$//' | grep -vE '^(tessera_[A-Za-z0-9_]+|tessera::.*|(vtable|typeinfo|typeinfo name) for tessera::.*|TESSERA_0)$' || true
}

control=$(printf '%s\n' 'std::vector<int, std::allocator<int> >::push_back(int const&)' \
  'ZSTD_compress' 'libdeflate_alloc_decompressor' 'operator new(unsigned long)' | foreign | wc -l)
if [ "$control" -ne 4 ]; then
  echo "FAIL: the filter let a foreign name through (control: $control of 4 refused)"
  exit 1
fi

got_soname=$(readelf -d "$lib" | sed -nE 's/.*Library soname: \[(.*)\].*/\1/p')
if [ "$got_soname" != "$soname" ]; then
  echo "FAIL: $lib has SONAME '$got_soname', not $soname"
  exit 1
fi

names=$(nm -D --defined-only -C "$lib" | cut -c20-)
count=$(wc -l <<<"$names")
bad=$(foreign <<<"$names")
if [ -n "$bad" ]; then
  echo "FAIL: $lib exports $(wc -l <<<"$bad") names that are not tessera's, e.g.:"
  head -20 <<<"$bad"
  exit 1
fi

declared=$(sed -nE 's/^[a-z_ *]*[ *](tessera_[a-z_0-9]+)\(.*/\1/p' "$header" | sort -u)
exported=$(sed -E 's/@.*$//' <<<"$names" | grep -E '^tessera_' | sort -u)
missing=$(comm -23 <(echo "$declared") <(echo "$exported"))
if [ -n "$missing" ]; then
  echo "FAIL: declared in $(basename "$header") but not exported:"
  echo "$missing"
  exit 1
fi
echo "ok: $soname exports $count names, all tessera's; the $(wc -l <<<"$declared") C functions included"
