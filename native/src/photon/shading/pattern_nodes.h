// Pattern textures as Cycles 3.4 evaluates them: Checker, Gradient, Brick, Magic, and the Sky
// texture (whose models live in shading/sky.*). See program.h for the compile/eval contract.
#pragma once

#include <string>

#include "photon/shading/program.h"

namespace photon {

// Instruction::kind within NodeFamily::kPattern.
enum class PatternKind : uint16_t { kChecker, kGradient, kBrick, kMagic, kSky };

// ShaderNodeTexGradient's gradient_type, as Instruction::mode.
enum class GradientType : uint32_t {
  kLinear,
  kQuadratic,
  kEasing,
  kDiagonal,
  kRadial,
  kQuadraticSphere,
  kSpherical,
};

CompileStatus compile_pattern_node(const NodeDesc& desc, ShaderProgram* program, Instruction* out,
                                   std::string* error);
void eval_pattern_node(const Instruction& ins, const ShaderProgram& program,
                       const ShaderGlobals& globals, float* registers);

// The per-point functions, exposed for tests.
float checker_texture(const Vec3& p);                      // 1 on Color1 cells, 0 on Color2 cells
float gradient_texture(const Vec3& p, GradientType type);  // before clamping to [0, 1]
// (tint, mortar): tint picks between Color1 and Color2, mortar is the Fac output.
Vec2 brick_texture(const Vec3& p, float mortar_size, float mortar_smooth, float bias,
                   float brick_width, float row_height, float offset_amount, int offset_frequency,
                   float squash_amount, int squash_frequency);
Vec3 magic_texture(const Vec3& p, int depth, float distortion);

}  // namespace photon
