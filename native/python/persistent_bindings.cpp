// What the add-on keeps between the frames of an animation under Render > Performance >
// Persistent Data: finished native meshes (KeptMesh, so an unchanged mesh skips the loop gather,
// cleanup and normal snapping, and is moved rather than copied) and mesh BVHs (BlasCache,
// handed to RenderSession).
#include <pybind11/pybind11.h>

#include <memory>
#include <stdexcept>

#include "photon/render/blas_cache.h"
#include "photon/scene/scene.h"

namespace py = pybind11;
using namespace photon;

namespace {

// A Scene's finished mesh (cleaned, normals snapped) kept for later frames without copying it:
// it is lent to the Scene that renders a frame and moved back out once that render is over.
struct KeptMesh {
  Mesh mesh;
  const Scene* lent_to = nullptr;  // the Scene holding the mesh now, or null (it is here)
  size_t index = 0;                // its index in that Scene
};

}  // namespace

void bind_persistent(py::module_& m) {
  py::class_<KeptMesh, std::shared_ptr<KeptMesh>>(m, "KeptMesh")
      .def_property_readonly("lent", [](const KeptMesh& k) { return k.lent_to != nullptr; });

  // Scene is registered by module.cpp; these methods join it.
  auto scene = py::reinterpret_borrow<py::class_<Scene, std::shared_ptr<Scene>>>(m.attr("Scene"));
  scene
      .def(
          "keep_mesh",
          [](const Scene& s, size_t index) {
            if (index >= s.meshes.size()) throw std::out_of_range("keep_mesh: no such mesh");
            auto kept = std::make_shared<KeptMesh>();
            kept->lent_to = &s;  // already where it renders: return_kept_mesh takes it
            kept->index = index;
            return kept;
          },
          py::arg("index"),
          "Keeps mesh `index` for later scenes (add_kept_mesh) once return_kept_mesh took it "
          "back from this scene.")
      .def(
          "add_kept_mesh",
          [](Scene& s, KeptMesh& kept) {
            if (kept.lent_to) throw std::runtime_error("add_kept_mesh: the mesh is lent out");
            s.meshes.push_back(std::move(kept.mesh));
            kept.lent_to = &s;
            kept.index = s.meshes.size() - 1;
            return kept.index;
          },
          py::arg("kept"), "Moves a kept mesh into this scene as it was; returns its index.")
      .def(
          "return_kept_mesh",
          [](Scene& s, KeptMesh& kept) {
            if (kept.lent_to != &s || kept.index >= s.meshes.size()) return false;
            kept.mesh = std::move(s.meshes[kept.index]);
            kept.lent_to = nullptr;
            return true;
          },
          py::arg("kept"),
          "Moves a mesh lent to this scene back into `kept` (call once no render uses the "
          "scene; the scene is left with an empty mesh there). False when it is not lent here.");

  // Mesh BVHs kept between frames; begin_frame() drops those the previous frame did not use.
  py::class_<BlasCache, std::shared_ptr<BlasCache>>(m, "BlasCache")
      .def(py::init<>())
      .def("begin_frame", &BlasCache::begin_frame)
      .def_property_readonly("size", &BlasCache::size);
}
