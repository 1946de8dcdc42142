// The Voronoi Texture node (ShaderNodeTexVoronoi) in shader programs: NodeFamily::kVoronoi.
#pragma once

#include <string>

#include "photon/shading/program.h"

namespace photon {

// Instruction layout of Blender 3.4's node (kind 0). mode: dimensions (1-4) in bits 0-3,
// voronoi::Feature in bits 4-7, voronoi::Metric in bits 8-11. in[]: Vector, W, Scale, Smoothness,
// Exponent, Randomness. out[]: Distance, Color, Position, W, Radius.
enum VoronoiInput {
  kVoronoiInVector,
  kVoronoiInW,
  kVoronoiInScale,
  kVoronoiInSmoothness,
  kVoronoiInExponent,
  kVoronoiInRandomness
};
enum VoronoiOutput {
  kVoronoiOutDistance,
  kVoronoiOutColor,
  kVoronoiOutPosition,
  kVoronoiOutW,
  kVoronoiOutRadius
};

// Blender 4.x's node (kind 1; it has Detail, Roughness, Lacunarity and Normalize): the same mode
// plus Normalize in bit 12; in[]: Vector, W, Scale, Detail, Roughness, Lacunarity, Smoothness,
// Exponent; Randomness's register is program.data[ins.data]. Same outputs.
enum Voronoi4xInput {
  kVoronoi4xInVector,
  kVoronoi4xInW,
  kVoronoi4xInScale,
  kVoronoi4xInDetail,
  kVoronoi4xInRoughness,
  kVoronoi4xInLacunarity,
  kVoronoi4xInSmoothness,
  kVoronoi4xInExponent
};

CompileStatus compile_voronoi_node(const NodeDesc& desc, ShaderProgram* program, Instruction* out,
                                   std::string* error);
void eval_voronoi_node(const Instruction& ins, const ShaderProgram& program,
                       const ShaderGlobals& globals, float* registers);

}  // namespace photon
