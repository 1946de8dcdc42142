// The noise family (NodeFamily::kNoise): Blender's Noise, Musgrave, White Noise and Wave textures,
// compiled from NodeDescs and evaluated as Cycles 3.4 evaluates them; Blender 4.x's Noise Texture
// (fractal types, Lacunarity, Normalize: told apart by those settings) as Cycles 4.x does.
#pragma once

#include <string>

#include "photon/shading/program.h"

namespace photon {

// Instruction::kind of the family's nodes.
// kNoise4x: the Noise Texture of Blender 4.x (it has noise_type / normalize / Lacunarity);
// kWave4x: the Wave Texture as Cycles 4.x computes its distortion (the add-on marks it with the
// enum "photon_cycles" >= "4": the node itself did not change).
// kGabor: Blender 4.3's Gabor Texture (shading/gabor.h).
enum class NoiseNodeKind : uint16_t {
  kNoise,
  kMusgrave,
  kWhiteNoise,
  kWave,
  kNoise4x,
  kWave4x,
  kGabor
};

CompileStatus compile_noise_node(const NodeDesc& desc, ShaderProgram* program, Instruction* out,
                                 std::string* error);
void eval_noise_node(const Instruction& ins, const ShaderProgram& program,
                     const ShaderGlobals& globals, float* registers);

}  // namespace photon
