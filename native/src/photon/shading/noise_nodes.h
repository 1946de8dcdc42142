// The noise family (NodeFamily::kNoise): Blender's Noise, Musgrave, White Noise and Wave textures,
// compiled from NodeDescs and evaluated as Cycles 3.4 evaluates them.
#pragma once

#include <string>

#include "photon/shading/program.h"

namespace photon {

// Instruction::kind of the family's nodes.
enum class NoiseNodeKind : uint16_t { kNoise, kMusgrave, kWhiteNoise, kWave };

CompileStatus compile_noise_node(const NodeDesc& desc, ShaderProgram* program, Instruction* out,
                                 std::string* error);
void eval_noise_node(const Instruction& ins, const ShaderProgram& program,
                     const ShaderGlobals& globals, float* registers);

}  // namespace photon
