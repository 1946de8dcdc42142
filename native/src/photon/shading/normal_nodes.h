// Bump and Normal Map nodes: shading normals from a height field (finite differences of the
// Height input's nodes at points offset along the surface, as Cycles' bump node) or from a
// normal-map colour.
#pragma once

#include <string>

#include "photon/shading/program.h"

namespace photon {

CompileStatus compile_normal_node(const NodeDesc& desc, ShaderProgram* program, Instruction* out,
                                  std::string* error);
void eval_normal_node(const Instruction& ins, const ShaderProgram& program,
                      const ShaderGlobals& globals, float* registers);

// The shading point moved by `dp` along the surface: position, texture coordinates (Generated
// through the object's texture space, UV through the UV tangents) follow.
ShaderGlobals offset_globals(const ShaderGlobals& g, const Vec3& dp);

}  // namespace photon
