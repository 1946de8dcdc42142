// Input nodes (Texture Coordinate, Geometry, UV Map, Object Info, Light Path, Fresnel, Layer
// Weight, Camera Data) read the shading point; conversion instructions implement Blender's
// implicit socket conversions between float, vector and colour.
#pragma once

#include <string>

#include "photon/shading/program.h"

namespace photon {

CompileStatus compile_input_node(const NodeDesc& desc, ShaderProgram* program, Instruction* out,
                                 std::string* error);
void eval_input_node(const Instruction& ins, const ShaderProgram& program,
                     const ShaderGlobals& globals, float* registers);

// Conversions, as NodeDesc types the add-on emits between sockets of different kinds:
//   "PhotonFloatToVector" (x, x, x), "PhotonVectorToFloat" (the average, as Cycles),
//   "PhotonColorToFloat" (Rec.709 luminance, Blender's colour-to-float conversion),
//   each with input "In" and output "Out"; and "PhotonBlockBegin", a marker (no effect) where
//   the code a Bump node re-runs at offset positions (its Height's nodes) begins.
CompileStatus compile_convert_node(const NodeDesc& desc, ShaderProgram* program, Instruction* out,
                                   std::string* error);
void eval_convert_node(const Instruction& ins, const ShaderProgram& program,
                       const ShaderGlobals& globals, float* registers);

// Whether `ins` is a block marker not yet claimed by a Bump (its mode becomes 1 once claimed).
bool is_open_block_marker(const Instruction& ins);

// Fresnel reflectance of a dielectric for cosine `cosi` and relative index `eta` (Cycles'
// fresnel_dielectric_cos, unpolarised light).
float fresnel_dielectric_cos(float cosi, float eta);

// The inverse of an affine transform (the identity when singular).
Transform inverse_affine(const Transform& t);

}  // namespace photon
