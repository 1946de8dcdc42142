// Image Texture (flat, box, sphere and tube projections) and Environment Texture
// (equirectangular and mirror ball) nodes, read through the scene's TextureSet.
#pragma once

#include <string>

#include "photon/shading/program.h"

namespace photon {

CompileStatus compile_image_node(const NodeDesc& desc, ShaderProgram* program, Instruction* out,
                                 std::string* error);
void eval_image_node(const Instruction& ins, const ShaderProgram& program,
                     const ShaderGlobals& globals, float* registers);

// Blender's equirectangular mapping of a direction (Cycles' direction_to_equirectangular):
// u = 0.5 - atan2(y, x) / 2 pi, v = 0.5 + asin(z) / pi.
Vec2 direction_to_equirectangular(const Vec3& direction);
// Blender's mirror-ball mapping of a direction (Cycles' direction_to_mirrorball).
Vec2 direction_to_mirror_ball(const Vec3& direction);

}  // namespace photon
