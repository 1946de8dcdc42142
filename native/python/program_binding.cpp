#include "program_binding.h"

#include <pybind11/stl.h>

#include "photon/shading/program_eval.h"

namespace py = pybind11;
using namespace photon;

namespace photon_python {
namespace {

template <typename T>
void read_map(const py::dict& d, const char* key, std::map<std::string, T>* out) {
  if (!d.contains(key)) return;
  for (auto item : py::reinterpret_borrow<py::dict>(d[key]))
    (*out)[py::str(item.first)] = item.second.cast<T>();
}

}  // namespace

NodeDesc parse_node_desc(const py::handle& handle) {
  if (!py::isinstance<py::dict>(handle)) throw py::value_error("a node description must be a dict");
  const py::dict d = py::reinterpret_borrow<py::dict>(handle);
  NodeDesc desc;
  desc.type = py::str(d["type"]);
  if (d.contains("enums"))
    for (auto item : py::reinterpret_borrow<py::dict>(d["enums"]))
      desc.enums[py::str(item.first)] = py::str(item.second);
  read_map(d, "numbers", &desc.numbers);
  read_map(d, "inputs", &desc.inputs);
  read_map(d, "outputs", &desc.outputs);
  if (d.contains("table")) desc.table = d["table"].cast<std::vector<float>>();
  return desc;
}

ShaderProgram parse_program(const py::handle& handle) {
  ShaderProgram program;
  if (handle.is_none()) return program;
  const py::dict d = py::reinterpret_borrow<py::dict>(handle);
  program.registers = d["registers"].cast<std::vector<float>>();
  size_t index = 0;
  for (auto node : py::reinterpret_borrow<py::list>(d["nodes"])) {
    const NodeDesc desc = parse_node_desc(node);
    std::string error;
    const CompileStatus status = compile_node(desc, &program, &error);
    if (status == CompileStatus::kUnknownNode)
      throw py::value_error("shader node " + std::to_string(index) + " (" + desc.type +
                            ") is not known to the native library");
    if (status == CompileStatus::kError)
      throw py::value_error("shader node " + std::to_string(index) + " (" + desc.type +
                            "): " + error);
    ++index;
  }
  // Any register may be read as a vector: two spare floats keep a scalar at the end in range.
  program.registers.resize(program.registers.size() + 2, 0.0f);
  return program;
}

void register_program_functions(py::module_& m) {
  m.def(
      "check_shader_node",
      [](const py::handle& desc) -> py::object {
        const NodeDesc node = parse_node_desc(desc);
        ShaderProgram scratch;
        scratch.registers.assign(1 << 16, 0.0f);
        std::string error;
        const CompileStatus status = compile_node(node, &scratch, &error);
        if (status == CompileStatus::kCompiled) return py::none();
        if (status == CompileStatus::kUnknownNode) return py::str("not supported");
        return py::str(error);
      },
      py::arg("desc"),
      "None when the native library compiles the node description, else the reason it cannot.");
}

}  // namespace photon_python
