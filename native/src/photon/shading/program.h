// Compiling and running shader programs (scene/shader_program.h): the node descriptions the
// add-on sends, what a program reads at a shading point, and the register helpers. Each node family
// (maths, colour, textures, ...) compiles its nodes from a NodeDesc and evaluates its instructions
// in its own file.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "photon/base/math.h"
#include "photon/scene/shader_program.h"

namespace photon {

class TextureSet;
struct Camera;
struct Mesh;

// One node as the add-on describes it (see addon/photon/sync/shader_program.py).
struct NodeDesc {
  std::string type;                          // bl_idname, e.g. "ShaderNodeMath"
  std::map<std::string, std::string> enums;  // enum and bool properties ("ADD", "True")
  std::map<std::string, double> numbers;     // int and float properties
  std::map<std::string, int32_t> inputs;     // socket identifier -> first register
  std::map<std::string, int32_t> outputs;    // socket identifier -> first register (used ones)
  std::vector<float> table;                  // node-specific tables (ramps, curves)
};

// What input nodes read at a shading point (world space unless named otherwise).
struct ShaderGlobals {
  Vec3 p{0.0f};                     // position
  Vec3 n{0.0f, 0.0f, 1.0f};         // shading normal, on the incoming ray's side
  Vec3 ng{0.0f, 0.0f, 1.0f};        // true (geometric) normal, on the incoming ray's side
  Vec3 incoming{0.0f, 0.0f, 1.0f};  // towards where the ray came from (Cycles' I)
  Vec2 uv{0.0f, 0.0f};              // the active UV map
  Vec3 dpdu{0.0f}, dpdv{0.0f};      // UV tangents (zero when unknown)
  bool backfacing = false;
  Vec3 generated{0.0f};        // Generated coordinates (mesh texture space, [0, 1]^3)
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
  float ray_depth = 0.0f, diffuse_depth = 0.0f, glossy_depth = 0.0f, transparent_depth = 0.0f,
        transmission_depth = 0.0f;
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
inline float load1(const float* r, int32_t i) {
  return r[i];
}
inline Vec3 load3(const float* r, int32_t i) {
  return Vec3(r[i], r[i + 1], r[i + 2]);
}
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
