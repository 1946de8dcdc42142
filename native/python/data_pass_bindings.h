// Blender's data passes (Depth, Mist, Normal, ...) in Python: DataPassSettings, the pass table
// and the conversion of a tile's data buffer into one array per pass.
#pragma once

#include <pybind11/pybind11.h>

#include <cstdint>
#include <vector>

#include "photon/film/film.h"

namespace photon_python {

// DataPassSettings, DATA_PASSES (name, channels, channel ids, bit) and DATA_PASS_* bits.
void register_data_pass_classes(pybind11::module_& m);

// A tile's passes as {name: array[h, w, channels]}, or None when the tile has none.
pybind11::object passes_to_dict(std::vector<photon::PassImage>&& passes, int height, int width);

}  // namespace photon_python
