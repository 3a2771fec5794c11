// tessera view without cpp-httplib (libcpp-httplib-dev absent at configure time): the static
// export works, serving says what is missing.
#include <cstdio>

#include "view.h"

namespace tessera::cli {

int serve_view(std::vector<ViewInput>, const ViewServeOptions&) {
  std::fprintf(stderr,
               "tessera: view: this tessera was built without its HTTP server (install "
               "libcpp-httplib-dev and rebuild); `tessera view INPUT --html -o VIEW.html` works\n");
  return kExitBadInput;
}

}  // namespace tessera::cli
