// The failure path of TESSERA_DCHECK (check.h): out of line, so checks cost one compare inline.
#include "core/check.h"

#include <cstdio>
#include <cstdlib>

namespace tessera::detail {

void dcheck_failed(const char* file, int line, const char* condition) noexcept {
  std::fprintf(stderr, "%s:%d: TESSERA_DCHECK(%s) failed\n", file, line, condition);
  std::fflush(stderr);
  std::abort();
}

}  // namespace tessera::detail
