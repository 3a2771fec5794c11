// The paper experiments from Python (tessera.run_seams, tessera.run_aa): experiments::run_seams /
// run_aa on the CPU, returned as the dict of the library's to_json (the keys of `tessera seams
// --json` / `tessera aa --json`) or its Markdown.
#pragma once

#include "arrays.h"

namespace tessera::python {

void register_experiments(py::module_& module);

}  // namespace tessera::python
