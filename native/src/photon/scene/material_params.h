// The one table of material inputs: for every closure type, the Blender node it comes from and
// the inputs it reads (dict key, Blender socket names, colour or scalar, Blender's default and
// the range Photon accepts). sanitize_material and the texture lookups clamp with it
// (param_range), the Python binding parses closure dicts with it and the add-on reads it
// through _photon.material_parameters() to convert node trees, so it is stated only here.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "photon/scene/material.h"

namespace photon {

enum class ParamKind : uint8_t { kScalar, kColor };

// One closure input.
struct ClosureParamSpec {
  Param param;
  const char* key;  // the closure dict's key ("color", "roughness", ...)
  // Blender's socket names: Blender 3.4's first, then the 4.x name when it differs (or null).
  const char* sockets[2];
  ParamKind kind;
  float default_value;  // Blender's default for the node's socket (a grey for colours)
  ParamRange range;
};

// One closure type: its dict name, the Blender node type it converts, and its inputs in the
// order the add-on reads (and reports) them.
struct ClosureSpec {
  ClosureType type;
  const char* name;  // "PRINCIPLED", ...
  const char* node;  // bpy ShaderNode.type: "BSDF_PRINCIPLED", ...
  std::vector<ClosureParamSpec> params;
};

// Every closure type, in ClosureType order.
const std::vector<ClosureSpec>& closure_specs();
const ClosureSpec& closure_spec(ClosureType type);
const ClosureSpec* find_closure(const char* name);
// The input `p` of closure `type`; for an input the closure does not read (it keeps its value
// but never renders it), the Principled BSDF's (v1's, else v2's: together they read every Param).
const ClosureParamSpec& param_spec(ClosureType type, Param p);
// The input named `key` (any closure's: the dict keys are shared; v1's spec where both Principled
// versions read it), or null.
const ClosureParamSpec* find_param(const char* key);

// Blender's defaults for the inputs of `type` (Principled's for inputs it does not read).
std::array<Input, static_cast<size_t>(Param::kCount)> default_params(ClosureType type);

// A scalar input outside the closure params: its default and range.
struct ScalarSpec {
  float default_value;
  ParamRange range;
};
// A Normal Map node's Strength (Blender's soft range is [0, 10]; 100 bounds absurd values).
constexpr ScalarSpec kNormalMapStrength{1.0f, {0.0f, 100.0f}};
// A Mix Shader's factor.
constexpr ScalarSpec kMixFactor{0.5f, {0.0f, 1.0f}};

}  // namespace photon
