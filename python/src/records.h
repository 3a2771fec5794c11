// The up-to-date records of `tessera compress --skip-up-to-date` and `tessera.batch`
// (texture_file::up_to_date_record) as Python functions.
#pragma once

#include <pybind11/pybind11.h>

namespace tessera::python {

namespace py = pybind11;

/// Adds up_to_date_record, is_up_to_date and write_up_to_date_record to `module`.
void register_records(py::module_& module);

}  // namespace tessera::python
