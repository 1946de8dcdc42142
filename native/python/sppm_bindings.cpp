#include "sppm_bindings.h"

#include "photon/integrators/sppm/sppm_renderer.h"

namespace py = pybind11;

namespace photon_python {

void register_sppm_classes(py::module_& m) {
  using photon::SppmStats;
  py::class_<SppmStats>(m, "SppmStats",
                        "What an SPPM render did (RenderStats.sppm; iterations is 0 for other "
                        "integrators).")
      .def_readonly("iterations", &SppmStats::iterations)
      .def_readonly("photons_emitted", &SppmStats::photons_emitted)
      .def_readonly("photons_recorded", &SppmStats::photons_recorded)
      .def_readonly("peak_photon_bytes", &SppmStats::peak_photon_bytes)
      .def_readonly("rays", &SppmStats::rays)
      .def_readonly("non_finite", &SppmStats::non_finite)
      .def_readonly("photon_seconds", &SppmStats::photon_seconds)
      .def_readonly("camera_seconds", &SppmStats::camera_seconds)
      .def_property_readonly_static(
          "bytes_per_pixel", [](py::object) { return photon::SppmRenderer::kBytesPerPixel; });
}

}  // namespace photon_python
