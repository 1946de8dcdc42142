// Shader programs as scene data: a material's (or the world's) node tree compiled by the add-on
// into a flat list of instructions over a register file of floats (the design of Cycles' SVM). A
// colour or vector occupies three consecutive registers, a float one. Constants (unlinked
// sockets) are the program's initial register values; linked sockets name the registers their
// source node writes. shading/ compiles node descriptions into programs and runs them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "photon/base/math.h"

namespace photon {

enum class NodeFamily : uint16_t {
  kInput,      // coordinates and geometry (shading/input_nodes.*)
  kConvert,    // implicit socket conversions, Value/RGB (shading/input_nodes.*)
  kMath,       // Math, Vector Math, Map Range, Clamp, Mapping, Vector Rotate (shading/math_nodes.*)
  kColor,      // Mix, MixRGB, HSV, Gamma, Invert, ... ColorRamp, curves (shading/color_nodes.*)
  kNoise,      // Noise, Musgrave, White Noise, Wave (shading/noise_nodes.*)
  kVoronoi,    // Voronoi (shading/voronoi_nodes.*)
  kPattern,    // Checker, Gradient, Brick, Magic, Sky (shading/pattern_nodes.*)
  kImage,      // Image / Environment Texture (shading/image_nodes.*)
  kNormal,     // Bump, Normal Map (shading/normal_nodes.*)
  kAttribute,  // Attribute, Color Attribute, named UV Map (shading/attribute_nodes.*)
  kCount,
};

struct Instruction {
  NodeFamily family = NodeFamily::kConvert;
  uint16_t kind = 0;  // which node of the family (family-defined)
  uint32_t mode = 0;  // family-defined: an operation, a dimension count, flags
  int32_t in[8] = {-1, -1, -1, -1, -1, -1, -1, -1};  // first register of each input
  int32_t out[5] = {-1, -1, -1, -1, -1};             // first register of each output, -1 unused
  float param[4] = {0.0f, 0.0f, 0.0f, 0.0f};         // family-defined constants
  int32_t data = -1;                                 // offset into ShaderProgram::data
  int32_t data_size = 0;
  int32_t skip = 0;  // kNormal Bump: instructions of the height block that precede it
};

// A mesh attribute a program reads by name (shading/attribute_nodes.*).
struct ProgramAttribute {
  std::string name;
  uint64_t key = 0;  // attribute_key(name) (scene/mesh_attribute.h)
};

struct ShaderProgram {
  std::vector<Instruction> code;
  std::vector<float> registers;              // initial values; size() is the register count
  std::vector<float> data;                   // tables
  std::vector<ProgramAttribute> attributes;  // named mesh attributes, by slot

  bool empty() const { return code.empty(); }
};

// Checks that every register an instruction names lies inside the register file (with room for a
// vector where one may be read) and that Bump blocks lie inside the code; false with `error` if
// not. Programs from Python are checked before they are rendered.
bool validate_program(const ShaderProgram& program, std::string* error);

}  // namespace photon
