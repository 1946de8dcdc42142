// What the add-on keeps between the frames of an animation under Render > Performance >
// Persistent Data: finished native meshes (KeptMesh, so an unchanged mesh skips the loop gather,
// cleanup and normal snapping) and mesh BVHs (BlasCache, handed to RenderSession).
#include <pybind11/pybind11.h>

#include <memory>
#include <stdexcept>

#include "photon/render/blas_cache.h"
#include "photon/scene/scene.h"

namespace py = pybind11;
using namespace photon;

namespace {

// A copy of a Scene's mesh as add_mesh / add_loop_mesh left it (cleaned, normals snapped).
struct KeptMesh {
  Mesh mesh;
};

}  // namespace

void bind_persistent(py::module_& m) {
  py::class_<KeptMesh, std::shared_ptr<KeptMesh>>(m, "KeptMesh")
      .def_property_readonly("triangles",
                             [](const KeptMesh& k) { return k.mesh.triangle_count(); });

  // Scene is registered by module.cpp; these methods join it.
  auto scene = py::reinterpret_borrow<py::class_<Scene, std::shared_ptr<Scene>>>(m.attr("Scene"));
  scene
      .def(
          "keep_mesh",
          [](const Scene& s, size_t index) {
            if (index >= s.meshes.size()) throw std::out_of_range("keep_mesh: no such mesh");
            auto kept = std::make_shared<KeptMesh>();
            py::gil_scoped_release release;
            kept->mesh = s.meshes[index];
            return kept;
          },
          py::arg("index"), "A copy of mesh `index` to add to later scenes with add_kept_mesh.")
      .def(
          "add_kept_mesh",
          [](Scene& s, const KeptMesh& kept) {
            {
              py::gil_scoped_release release;
              s.meshes.push_back(kept.mesh);
            }
            return s.meshes.size() - 1;
          },
          py::arg("kept"), "Appends a kept mesh as it was; returns its index.");

  // Mesh BVHs kept between frames; begin_frame() drops those the previous frame did not use.
  py::class_<BlasCache, std::shared_ptr<BlasCache>>(m, "BlasCache")
      .def(py::init<>())
      .def("begin_frame", &BlasCache::begin_frame)
      .def_property_readonly("size", &BlasCache::size);
}
