#include "sppm_bindings.h"

#include "photon/integrators/sppm/sppm_integrator.h"

namespace py = pybind11;

namespace photon_python {

void register_sppm_classes(py::module_& m) {
  using photon::IterationStats;
  py::class_<IterationStats>(m, "IterationStats",
                             "What the iterations of an SPPM or VCM render did "
                             "(RenderStats.iterations; iterations is 0 for other integrators): "
                             "photons_emitted counts SPPM's photons or VCM's light paths, "
                             "photons_recorded the photons or light vertices stored by the last "
                             "iteration.")
      .def_readonly("iterations", &IterationStats::iterations)
      .def_readonly("photons_emitted", &IterationStats::photons_emitted)
      .def_readonly("photons_recorded", &IterationStats::photons_recorded)
      .def_readonly("peak_photon_bytes", &IterationStats::peak_photon_bytes)
      .def_readonly("rays", &IterationStats::rays)
      .def_readonly("non_finite", &IterationStats::non_finite)
      .def_readonly("photon_seconds", &IterationStats::photon_seconds)
      .def_readonly("camera_seconds", &IterationStats::camera_seconds)
      .def_property_readonly_static(
          "bytes_per_pixel", [](py::object) { return photon::SppmIntegrator::kBytesPerPixel; });
}

}  // namespace photon_python
