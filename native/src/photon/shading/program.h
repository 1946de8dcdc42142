// Shader programs: a material's (or the world's) node tree compiled by the add-on into a flat list
// of instructions over a register file of floats, evaluated per shading point (the design of
// Cycles' SVM). A colour or vector occupies three consecutive registers, a float one. Constants
// (unlinked sockets) are the program's initial register values; linked sockets name the
// registers their source node writes. Each node family (maths, colour, textures, ...) compiles its
// nodes from a NodeDesc and evaluates its instructions in its own file.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "photon/base/math.h"

namespace photon {

class TextureSet;
struct Camera;
struct Mesh;

// One node as the add-on describes it (see addon/photon/sync/shader_program.py).
struct NodeDesc {
  std::string type;                             // bl_idname, e.g. "ShaderNodeMath"
  std::map<std::string, std::string> enums;     // enum and bool properties ("ADD", "True")
  std::map<std::string, double> numbers;        // int and float properties
  std::map<std::string, int32_t> inputs;        // socket identifier -> first register
  std::map<std::string, int32_t> outputs;       // socket identifier -> first register (used ones)
  std::vector<float> table;                     // node-specific tables (ramps, curves)
};

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
  uint16_t kind = 0;   // which node of the family (family-defined)
  uint32_t mode = 0;   // family-defined: an operation, a dimension count, flags
  int32_t in[8] = {-1, -1, -1, -1, -1, -1, -1, -1};  // first register of each input
  int32_t out[5] = {-1, -1, -1, -1, -1};             // first register of each output, -1 unused
  float param[4] = {0.0f, 0.0f, 0.0f, 0.0f};         // family-defined constants
  int32_t data = -1;                                  // offset into ShaderProgram::data
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
  std::vector<float> registers;  // initial values; size() is the register count
  std::vector<float> data;       // tables
  std::vector<ProgramAttribute> attributes;  // named mesh attributes, by slot

  bool empty() const { return code.empty(); }
};

// What input nodes read at a shading point (world space unless named otherwise).
struct ShaderGlobals {
  Vec3 p{0.0f};          // position
  Vec3 n{0.0f, 0.0f, 1.0f};   // shading normal, on the incoming ray's side
  Vec3 ng{0.0f, 0.0f, 1.0f};  // true (geometric) normal, on the incoming ray's side
  Vec3 incoming{0.0f, 0.0f, 1.0f};  // towards where the ray came from (Cycles' I)
  Vec2 uv{0.0f, 0.0f};   // the active UV map
  Vec3 dpdu{0.0f}, dpdv{0.0f};  // UV tangents (zero when unknown)
  bool backfacing = false;
  Vec3 generated{0.0f};  // Generated coordinates (mesh texture space, [0, 1]^3)
  Vec3 generated_scale{1.0f};  // d generated / d object position (per axis)
  Transform object_to_world;
  Transform world_to_object;
  Transform world_to_camera;  // Cycles' camera space: looking down +Z (Blender's with Z negated)
  const Camera* camera = nullptr;  // for Window coordinates
  Vec3 object_location{0.0f};
  Vec3 object_color{1.0f};
  float object_alpha = 1.0f;
  float object_random = 0.0f;
  float object_pass_index = 0.0f;
  float material_pass_index = 0.0f;
  // Light Path: the ray that reached this point.
  uint32_t ray_flags = 1;  // LightPathFlag bits
  float ray_length = 0.0f;
  float ray_depth = 0.0f, diffuse_depth = 0.0f, glossy_depth = 0.0f,
        transparent_depth = 0.0f, transmission_depth = 0.0f;
  bool is_background = false;  // a world shader: p is irrelevant, incoming is -direction
  const TextureSet* textures = nullptr;
  // The mesh point: named attributes are interpolated on triangle `primitive` of `mesh` at
  // Embree barycentrics (null mesh: none, e.g. the world).
  const Mesh* mesh = nullptr;
  uint32_t primitive = 0;
  Vec2 barycentric{0.0f, 0.0f};
  // Bump: a small step along the surface for finite differences (scene units).
  float bump_step = 1e-3f;
};

enum LightPathFlag : uint32_t {
  kRayCamera = 1u << 0,
  kRayShadow = 1u << 1,
  kRayDiffuse = 1u << 2,
  kRayGlossy = 1u << 3,
  kRaySingular = 1u << 4,
  kRayReflect = 1u << 5,
  kRayTransmit = 1u << 6,
  kRayVolumeScatter = 1u << 7,
};

// What a family's compile function made of a NodeDesc.
enum class CompileStatus { kUnknownNode, kCompiled, kError };

// Every node family provides, in shading/<family>_nodes.h:
//   CompileStatus compile_<family>_node(const NodeDesc& desc, ShaderProgram* program,
//                                       Instruction* out, std::string* error);
//     kUnknownNode if desc.type is not one of its nodes; else fills `out` (family, kind, mode,
//     in/out registers, params; tables appended to program->data) and returns kCompiled, or sets
//     `error` (a clear sentence for the artist) and returns kError.
//   void eval_<family>_node(const Instruction& ins, const ShaderProgram& program,
//                           const ShaderGlobals& globals, float* registers);
// The program's evaluator (program_eval.cpp) dispatches on Instruction::family.

// Register access: a vector input or output is three consecutive floats.
inline float load1(const float* r, int32_t i) { return r[i]; }
inline Vec3 load3(const float* r, int32_t i) { return Vec3(r[i], r[i + 1], r[i + 2]); }
inline void store1(float* r, int32_t i, float v) {
  if (i >= 0) r[i] = v;
}
inline void store3(float* r, int32_t i, const Vec3& v) {
  if (i >= 0) r[i] = v.x, r[i + 1] = v.y, r[i + 2] = v.z;
}

// The register an input of `desc` reads (identifier), or -1 when the add-on did not send it.
inline int32_t input_register(const NodeDesc& desc, const char* identifier) {
  auto it = desc.inputs.find(identifier);
  return it == desc.inputs.end() ? -1 : it->second;
}
inline int32_t output_register(const NodeDesc& desc, const char* identifier) {
  auto it = desc.outputs.find(identifier);
  return it == desc.outputs.end() ? -1 : it->second;
}
inline std::string enum_value(const NodeDesc& desc, const char* name, const char* fallback) {
  auto it = desc.enums.find(name);
  return it == desc.enums.end() ? std::string(fallback) : it->second;
}
inline double number_value(const NodeDesc& desc, const char* name, double fallback) {
  auto it = desc.numbers.find(name);
  return it == desc.numbers.end() ? fallback : it->second;
}

}  // namespace photon
