#include "data_pass_bindings.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "photon/integrators/data_passes.h"

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
      .def_readwrite("cryptomatte", &DataPassSettings::cryptomatte,
                     "CRYPTOMATTE_OBJECT | _MATERIAL | _ASSET bits")
      .def_property(
          "cryptomatte_depth", [](const DataPassSettings& s) { return s.cryptomatte_depth; },
          [](DataPassSettings& s, int depth) { s.cryptomatte_depth = std::clamp(depth, 0, 32); },
          "IDs kept per pixel (Blender's Levels), clamped to [0, 32]")
      .def_readwrite("cryptomatte_default_material",
                     &DataPassSettings::cryptomatte_default_material)
      .def_property(
          "origin",
          [](const DataPassSettings& s) {
            return py::make_tuple(s.origin.x, s.origin.y, s.origin.z);
          },
          [](DataPassSettings& s, const std::vector<float>& v) {
            if (v.size() != 3) throw py::value_error("origin needs 3 floats");
            s.origin = Vec3(v[0], v[1], v[2]);
          })
      .def_property(
          "aovs",
          [](const DataPassSettings& s) {
            py::list out;
            for (const ShaderAovPass& aov : s.aovs)
              out.append(py::make_tuple(aov.name, aov.color ? "COLOR" : "VALUE"));
            return out;
          },
          [](DataPassSettings& s, const std::vector<std::pair<std::string, std::string>>& v) {
            std::vector<ShaderAovPass> aovs;
            for (const auto& [name, type] : v) {
              if (type != "COLOR" && type != "VALUE")
                throw py::value_error("shader AOV '" + name + "': type must be COLOR or VALUE");
              for (const ShaderAovPass& other : aovs)
                if (other.name == name)
                  throw py::value_error("shader AOV '" + name + "' is listed twice");
              aovs.push_back({name, type == "COLOR"});
            }
            s.aovs = std::move(aovs);
          },
          "[(name, 'COLOR' | 'VALUE')]: the view layer's shader AOVs, written after the "
          "Cryptomatte layers");
  py::list table;
  for (const DataPassInfo& p : data_pass_table())
    table.append(py::make_tuple(p.name, p.channels, p.channel_ids, p.bit));
  m.attr("DATA_PASSES") = py::tuple(table);
  m.attr("CRYPTOMATTE_OBJECT") = static_cast<uint32_t>(kCryptoObject);
  m.attr("CRYPTOMATTE_MATERIAL") = static_cast<uint32_t>(kCryptoMaterial);
  m.attr("CRYPTOMATTE_ASSET") = static_cast<uint32_t>(kCryptoAsset);
  m.def(
      "data_pass_names",
      [](const DataPassSettings& settings) {
        py::list out;
        for (const DataPassSlot& slot : data_pass_slots(settings))
          out.append(py::make_tuple(slot.name, slot.channels, slot.channel_ids));
        return out;
      },
      py::arg("settings"),
      "(name, channels, channel ids) of every pass `settings` asks for, Cryptomatte layers "
      "included, in the order take_tiles' data holds them.");
}

py::object passes_to_dict(std::vector<photon::PassImage>&& passes, int height, int width) {
  if (passes.empty()) return py::none();
  py::dict out;
  for (photon::PassImage& pass : passes) {
    auto* heap = new std::vector<float>(std::move(pass.pixels));
    py::capsule owner(heap, [](void* p) { delete static_cast<std::vector<float>*>(p); });
    out[py::str(pass.name)] =
        py::array_t<float>({height, width, pass.channels}, heap->data(), owner);
  }
  return std::move(out);
}

}  // namespace photon_python
