#include "data_pass_bindings.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <memory>

#include "photon/session/data_passes.h"

namespace py = pybind11;
using namespace photon;

namespace photon_python {

void register_data_pass_classes(py::module_& m) {
  py::class_<DataPassSettings>(m, "DataPassSettings")
      .def(py::init<>())
      .def_readwrite("mask", &DataPassSettings::mask)
      .def_readwrite("mist_start", &DataPassSettings::mist_start)
      .def_readwrite("mist_depth", &DataPassSettings::mist_depth)
      .def_readwrite("mist_falloff", &DataPassSettings::mist_falloff)
      .def_readwrite("alpha_threshold", &DataPassSettings::alpha_threshold)
      .def_property(
          "origin",
          [](const DataPassSettings& s) {
            return py::make_tuple(s.origin.x, s.origin.y, s.origin.z);
          },
          [](DataPassSettings& s, const std::vector<float>& v) {
            if (v.size() != 3) throw py::value_error("origin needs 3 floats");
            s.origin = Vec3(v[0], v[1], v[2]);
          });
  py::list table;
  for (const DataPassInfo& p : data_pass_table())
    table.append(py::make_tuple(p.name, p.channels, p.channel_ids, p.bit));
  m.attr("DATA_PASSES") = py::tuple(table);
}

py::object data_passes_to_dict(std::vector<float>&& data, uint32_t mask, int height, int width) {
  const int floats = data_pass_floats(mask);
  if (data.empty() || floats == 0) return py::none();
  auto* heap = new std::vector<float>(std::move(data));
  py::capsule owner(heap, [](void* p) { delete static_cast<std::vector<float>*>(p); });
  const py::ssize_t h = height, w = width, f = sizeof(float);
  py::dict out;
  for (const DataPassInfo& p : data_pass_table()) {
    if (!(mask & p.bit)) continue;
    std::vector<py::ssize_t> shape{h, w, p.channels};
    std::vector<py::ssize_t> strides{w * floats * f, floats * f, f};
    out[p.name] =
        py::array_t<float>(shape, strides, heap->data() + data_pass_offset(mask, p.bit), owner);
  }
  return std::move(out);
}

}  // namespace photon_python
