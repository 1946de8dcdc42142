// The progressive session (session/progressive_session.h) for Blender's viewport and preview
// renders: started, re-aimed (set_view) and read (image) from Python, rendering off the GIL.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <stdexcept>

#include "material_binding.h"
#include "photon/render/blas_cache.h"
#include "photon/session/progressive_session.h"
#include "photon/session/viewport_scene.h"

namespace py = pybind11;
using namespace photon;

void bind_progressive(py::module_& m) {
  using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;
  py::class_<ViewportScene, std::shared_ptr<ViewportScene>>(m, "ViewportScene")
      .def(py::init([](std::shared_ptr<Scene> scene, std::shared_ptr<BlasCache> blas_cache) {
             if (!scene) throw std::invalid_argument("ViewportScene: scene is None");
             return std::make_shared<ViewportScene>(std::move(scene), std::move(blas_cache));
           }),
           py::arg("scene"), py::arg("blas_cache") = nullptr,
           "A synced scene whose BVH, lights and textures the ProgressiveSessions started on it "
           "share (built by the first).")
      .def(
          "move_instances",
          [](ViewportScene& vs, const std::vector<uint32_t>& indices, const FloatArray& matrices) {
            if (matrices.size() != static_cast<py::ssize_t>(16 * indices.size()))
              throw std::invalid_argument("matrices: one 4 x 4 matrix per index expected");
            std::vector<Transform> to_world;
            to_world.reserve(indices.size());
            for (size_t i = 0; i < indices.size(); ++i)
              to_world.push_back(Transform::from_rows(matrices.data() + 16 * i));
            py::gil_scoped_release release;
            return vs.move_instances(indices, to_world);
          },
          py::arg("indices"), py::arg("matrices"),
          "Moves Scene.instances[indices] to the (N, 4, 4) row-major matrices; with its "
          "resources built they are updated in place (top-level BVH only): True. False when "
          "they had to be dropped (the next session rebuilds them from the moved scene). No "
          "session may be running (RuntimeError).")
      .def(
          "replace_material",
          [](ViewportScene& vs, uint32_t index, const std::string& name, const py::list& closures,
             const py::object& program, float pass_index, float cryptomatte_id) {
            std::string warning;
            Material material = photon_python::parse_material(
                name, closures, static_cast<int64_t>(vs.scene().textures.size()), program,
                &warning);
            if (!warning.empty()) throw py::value_error(warning);
            material.pass_index = pass_index;
            material.cryptomatte_material = cryptomatte_id;
            py::gil_scoped_release release;
            return vs.replace_material(index, std::move(material));
          },
          py::arg("index"), py::arg("name"), py::arg("closures"), py::arg("program") = py::none(),
          py::arg("pass_index") = 0.0f, py::arg("cryptomatte_id") = 0.0f,
          "Replaces Scene.materials[index] with an edited material (closure dicts as "
          "Scene.add_material takes them; its textures must already be in the scene). True "
          "when the built resources were kept (BVH, lamps, textures; emissive triangles "
          "refreshed), False when the next session rebuilds them. No session may be running.")
      .def_property_readonly(
          "bounds",
          [](ViewportScene& vs) -> py::object {
            Vec3 lo, hi;
            if (!vs.bounds(&lo, &hi)) return py::none();
            return py::make_tuple(py::make_tuple(lo.x, lo.y, lo.z),
                                  py::make_tuple(hi.x, hi.y, hi.z));
          },
          "((min x, y, z), (max x, y, z)) of the built BVH, or None (not built, or empty).")
      .def_property_readonly("builds", &ViewportScene::builds)
      .def_property_readonly("moves_in_place", &ViewportScene::moves_in_place)
      .def_property_readonly("built", &ViewportScene::built);

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
      .def(py::init([](std::shared_ptr<ViewportScene> viewport_scene,
                       const RenderSettings& settings, bool quick_first_pass) {
             if (!viewport_scene) throw std::invalid_argument("ProgressiveSession: no scene");
             return std::make_unique<ProgressiveSession>(std::move(viewport_scene), settings,
                                                         quick_first_pass);
           }),
           py::arg("viewport_scene"), py::arg("settings"), py::arg("quick_first_pass") = true,
           "Renders a ViewportScene, reusing the resources an earlier session on it built.")
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
            // 0: the integrator's own passes; 1: the direct-light first look; 2: the look over
            // a coarse photon map. Distinct values tell the two first looks apart (same size
            // and sample count) to a viewer that redraws on change.
            const int quick = img.coarse_photons ? 2 : (img.quick ? 1 : 0);
            return py::make_tuple(pixels, img.samples, quick, img.view_serial);
          },
          "(rgba[h, w, 4] top row first, samples, quick, view serial) of the latest finished "
          "pass, or None before the first. quick is 0 for the integrator's own passes, 1 for "
          "the ray-traced first look and 2 for the look over a coarse photon map.")
      .def_property_readonly("samples_done", &ProgressiveSession::samples_done)
      .def_property_readonly("target_samples", &ProgressiveSession::target_samples)
      .def_property_readonly("converged", &ProgressiveSession::converged)
      .def("wait_for_samples", &ProgressiveSession::wait_for_samples, py::arg("samples"),
           py::arg("timeout"), py::call_guard<py::gil_scoped_release>())
      .def("wait_for_image", &ProgressiveSession::wait_for_image, py::arg("timeout"),
           py::call_guard<py::gil_scoped_release>(),
           "Waits until an image (quick included) of the current view exists; True then.")
      .def_property_readonly("first_image_seconds", &ProgressiveSession::first_image_seconds)
      .def_property_readonly("finished", &ProgressiveSession::finished)
      .def_property_readonly("cancelled", &ProgressiveSession::cancelled)
      .def_property_readonly("preparing", &ProgressiveSession::preparing)
      .def_property_readonly("progress", &ProgressiveSession::progress)
      .def_property_readonly("status", &ProgressiveSession::status)
      .def_property_readonly("warnings", &ProgressiveSession::warnings)
      .def_property_readonly("error", &ProgressiveSession::error);
}
