// Statistics of an SPPM render (RenderStats.sppm) as a Python object.
#pragma once

#include <pybind11/pybind11.h>

namespace photon_python {

void register_sppm_classes(pybind11::module_& m);

}  // namespace photon_python
