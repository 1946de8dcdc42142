// Shader programs between Python and native: the add-on's node descriptions
// (addon/photon/sync/shader_program.py) compiled through the node families.
#pragma once

#include <pybind11/pybind11.h>

#include <string>

#include "photon/shading/program.h"

namespace photon_python {

// A NodeDesc from {"type", "enums", "numbers", "inputs", "outputs", "table"}.
photon::NodeDesc parse_node_desc(const pybind11::handle& desc);

// {"registers": [float...], "nodes": [desc...]} compiled into a program; a node that does not
// compile raises ValueError naming it.
photon::ShaderProgram parse_program(const pybind11::handle& program);

// Module-level: check_shader_node(desc) -> None when the node compiles, else the reason.
void register_program_functions(pybind11::module_& m);

}  // namespace photon_python
