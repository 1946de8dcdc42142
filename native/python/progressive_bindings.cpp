// The progressive session (session/progressive_session.h) for Blender's viewport and preview
// renders: started, re-aimed (set_view) and read (image) from Python, rendering off the GIL.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <stdexcept>

#include "photon/render/blas_cache.h"
#include "photon/session/progressive_session.h"

namespace py = pybind11;
using namespace photon;

void bind_progressive(py::module_& m) {
  py::class_<ProgressiveSession>(m, "ProgressiveSession")
      .def(py::init([](std::shared_ptr<Scene> scene, const RenderSettings& settings,
                       std::shared_ptr<BlasCache> blas_cache, bool quick_first_pass) {
             if (!scene) throw std::invalid_argument("ProgressiveSession: scene is None");
             return std::make_unique<ProgressiveSession>(std::move(scene), settings,
                                                         std::move(blas_cache), quick_first_pass);
           }),
           py::arg("scene"), py::arg("settings"), py::arg("blas_cache") = nullptr,
           py::arg("quick_first_pass") = true,
           "Renders `scene` from its camera in passes up to settings.samples; start() it.")
      .def("start", &ProgressiveSession::start)
      .def("cancel", &ProgressiveSession::cancel)
      .def("wait", &ProgressiveSession::wait, py::call_guard<py::gil_scoped_release>())
      .def(
          "set_view",
          [](ProgressiveSession& s, const Scene& camera_of, int full_width, int full_height,
             const std::vector<int>& region) {
            if (region.size() != 4) throw std::invalid_argument("region: x0 y0 x1 y1");
            ProgressiveView v;
            v.camera = camera_of.camera;
            v.full_width = full_width;
            v.full_height = full_height;
            v.x0 = region[0];
            v.y0 = region[1];
            v.x1 = region[2];
            v.y1 = region[3];
            return s.set_view(v);
          },
          py::arg("camera_of"), py::arg("full_width"), py::arg("full_height"), py::arg("region"),
          "Restarts from the camera of Scene `camera_of` (a small scene set_camera was called "
          "on) over a full_width x full_height frame, rendering region (x0, y0, x1, y1), y "
          "downwards. Returns the view's serial.")
      .def(
          "image",
          [](const ProgressiveSession& s) -> py::object {
            ProgressiveImage img = s.image();
            if (img.rgba.empty()) return py::none();
            auto* data = new std::vector<float>(std::move(img.rgba));
            py::capsule owner(data, [](void* p) { delete static_cast<std::vector<float>*>(p); });
            py::array_t<float> pixels({img.height, img.width, 4}, data->data(), owner);
            return py::make_tuple(pixels, img.samples, img.quick, img.view_serial);
          },
          "(rgba[h, w, 4] top row first, samples, quick, view serial) of the latest finished "
          "pass, or None before the first.")
      .def_property_readonly("samples_done", &ProgressiveSession::samples_done)
      .def_property_readonly("target_samples", &ProgressiveSession::target_samples)
      .def_property_readonly("converged", &ProgressiveSession::converged)
      .def("wait_for_samples", &ProgressiveSession::wait_for_samples, py::arg("samples"),
           py::arg("timeout"), py::call_guard<py::gil_scoped_release>())
      .def_property_readonly("first_image_seconds", &ProgressiveSession::first_image_seconds)
      .def_property_readonly("finished", &ProgressiveSession::finished)
      .def_property_readonly("cancelled", &ProgressiveSession::cancelled)
      .def_property_readonly("preparing", &ProgressiveSession::preparing)
      .def_property_readonly("progress", &ProgressiveSession::progress)
      .def_property_readonly("status", &ProgressiveSession::status)
      .def_property_readonly("warnings", &ProgressiveSession::warnings)
      .def_property_readonly("error", &ProgressiveSession::error);
}
