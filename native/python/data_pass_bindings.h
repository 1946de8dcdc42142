// Blender's data passes (Depth, Mist, Normal, ...) in Python: DataPassSettings, the pass table
// and the conversion of a tile's data buffer into one array per pass.
#pragma once

#include <pybind11/pybind11.h>

#include <cstdint>
#include <vector>

#include "photon/integrators/data_pass_settings.h"

namespace photon_python {

// DataPassSettings, DATA_PASSES (name, channels, channel ids, bit) and DATA_PASS_* bits.
void register_data_pass_classes(pybind11::module_& m);

// A tile's data and Cryptomatte passes (data_pass_pixel_floats(settings) floats per pixel) as
// {name: array[h, w, c]}, or None when the tile has none.
pybind11::object data_passes_to_dict(std::vector<float>&& data,
                                     const photon::DataPassSettings& settings, int height,
                                     int width);

}  // namespace photon_python
