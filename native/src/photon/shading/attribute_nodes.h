// Mesh attribute nodes, as Cycles 3.4 evaluates them: Attribute (Geometry type), Color
// Attribute (ShaderNodeVertexColor) and a UV Map node naming its map. See program.h for the
// compile/eval contract.
//
// The add-on sends the attribute's name in NodeDesc::enums["photon_attribute"] (an empty or
// absent name: the node reads nothing); the name is kept in ShaderProgram::attributes and
// found by name in the shaded mesh's Mesh::attributes at each point (scene/mesh_attribute.h).
// Names the add-on resolves itself: a Color Attribute node without a layer reads
// kRenderColorAttribute, the mesh's active render colour attribute exported under that name.
#pragma once

#include <string>

#include "photon/shading/program.h"

namespace photon {

// The name the add-on exports a mesh's active render colour attribute under (a name Blender
// attributes cannot collide with in practice: it begins with a control character).
inline constexpr const char* kRenderColorAttribute = "\x01render_color";

// Instruction::kind within NodeFamily::kAttribute.
enum class AttributeKind : uint16_t { kAttribute, kVertexColor, kUvMap };

CompileStatus compile_attribute_node(const NodeDesc& desc, ShaderProgram* program, Instruction* out,
                                     std::string* error);
void eval_attribute_node(const Instruction& ins, const ShaderProgram& program,
                         const ShaderGlobals& globals, float* registers);

// The slot of attribute `name` in program->attributes (added on first use; one per name).
uint32_t program_attribute_slot(ShaderProgram* program, const std::string& name);

// UV tangents d position / du, d position / dv (world space) of the shading point's triangle
// in the 2-component attribute at `slot` (a named UV map), as Accel::uv_tangents computes them
// for the active map; false when the mesh lacks it or its UVs are degenerate there.
bool attribute_uv_tangents(const ShaderGlobals& globals, const ShaderProgram& program,
                           uint32_t slot, Vec3* dpdu, Vec3* dpdv);

// What an attribute node's outputs read from an attribute value of `components` floats (0: the
// attribute is missing), as Cycles' svm_node_attr converts them: the vector / colour, the
// float (Fac) and the alpha. `missing_alpha` is the Alpha of a missing attribute (1 for the
// Attribute node, 0 for Color Attribute).
struct AttributeOutputs {
  Vec3 vector{0.0f};
  float fac = 0.0f;
  float alpha = 0.0f;
};
AttributeOutputs attribute_outputs(const float* value, uint32_t components, float missing_alpha);

}  // namespace photon
