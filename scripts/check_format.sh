#!/usr/bin/env bash
# Fails, naming each file, when a tracked C or C++ file differs from clang-format's output with the
# repository's .clang-format (clang-format 14, Debian 12's). Fix with:
#   git ls-files '*.c' '*.cpp' '*.h' | xargs clang-format -i
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
fmt="${CLANG_FORMAT:-clang-format}"
version="$("$fmt" --version)"
case "$version" in
  *"version 14."*) ;;
  *) echo "check_format: $fmt is not clang-format 14 ($version)" >&2; exit 1 ;;
esac
bad=()
while IFS= read -r f; do
  "$fmt" --dry-run -Werror "$f" >/dev/null 2>&1 || bad+=("$f")
done < <(git ls-files '*.c' '*.cpp' '*.h')
if [ "${#bad[@]}" -gt 0 ]; then
  echo "check_format: ${#bad[@]} file(s) differ from clang-format:" >&2
  printf '  %s\n' "${bad[@]}" >&2
  exit 1
fi
echo "check_format: $(git ls-files '*.c' '*.cpp' '*.h' | wc -l) files formatted"
