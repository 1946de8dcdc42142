#include "photon/shading/voronoi_nodes.h"

#include <algorithm>

#include "photon/shading/voronoi.h"

namespace photon {
namespace {

constexpr const char* kInputNames[] = {"Vector",     "W",        "Scale",
                                       "Smoothness", "Exponent", "Randomness"};
constexpr const char* kOutputNames[] = {"Distance", "Color", "Position", "W", "Radius"};
// The sockets' defaults in Blender 3.4, for inputs the add-on did not send.
constexpr float kInputDefaults[] = {0.0f, 0.0f, 5.0f, 1.0f, 0.5f, 1.0f};

bool parse_dimensions(const std::string& s, uint32_t* dims) {
  if (s.size() != 2 || s[1] != 'D' || s[0] < '1' || s[0] > '4') return false;
  *dims = static_cast<uint32_t>(s[0] - '0');
  return true;
}

// Blender's enum identifiers, in the order of voronoi::Feature and voronoi::Metric.
constexpr const char* kFeatureNames[] = {"F1", "F2", "SMOOTH_F1", "DISTANCE_TO_EDGE",
                                         "N_SPHERE_RADIUS"};
constexpr const char* kMetricNames[] = {"EUCLIDEAN", "MANHATTAN", "CHEBYCHEV", "MINKOWSKI"};

template <size_t Count>
bool parse_enum(const std::string& s, const char* const (&names)[Count], uint32_t* value) {
  for (size_t i = 0; i < Count; ++i)
    if (s == names[i]) {
      *value = static_cast<uint32_t>(i);
      return true;
    }
  return false;
}

float input1(const Instruction& ins, const float* r, int i) {
  return ins.in[i] >= 0 ? load1(r, ins.in[i]) : kInputDefaults[i];
}

// Cycles' safe_divide: zero when dividing by zero (a Scale of 0).
inline float safe_divide(float a, float b) {
  return b != 0.0f ? a / b : 0.0f;
}

}  // namespace

CompileStatus compile_voronoi_node(const NodeDesc& desc, ShaderProgram* /*program*/,
                                   Instruction* out, std::string* error) {
  if (desc.type != "ShaderNodeTexVoronoi") return CompileStatus::kUnknownNode;
  const std::string dims_name = enum_value(desc, "voronoi_dimensions", "3D");
  const std::string feature_name = enum_value(desc, "feature", "F1");
  const std::string metric_name = enum_value(desc, "distance", "EUCLIDEAN");
  uint32_t dims = 3, feature = 0, metric = 0;
  if (!parse_dimensions(dims_name, &dims)) {
    *error = "Voronoi Texture: unknown dimensions '" + dims_name + "'";
    return CompileStatus::kError;
  }
  if (!parse_enum(feature_name, kFeatureNames, &feature)) {
    *error = "Voronoi Texture: unknown feature '" + feature_name + "'";
    return CompileStatus::kError;
  }
  if (!parse_enum(metric_name, kMetricNames, &metric)) {
    *error = "Voronoi Texture: unknown distance metric '" + metric_name + "'";
    return CompileStatus::kError;
  }
  Instruction ins;
  ins.family = NodeFamily::kVoronoi;
  ins.kind = 0;
  ins.mode = dims | (feature << 4) | (metric << 8);
  for (int i = 0; i < 6; ++i) ins.in[i] = input_register(desc, kInputNames[i]);
  for (int i = 0; i < 5; ++i) ins.out[i] = output_register(desc, kOutputNames[i]);
  *out = ins;
  return CompileStatus::kCompiled;
}

// Cycles' svm_node_tex_voronoi: clamp Randomness to [0, 1] and halve Smoothness into [0, 0.5],
// scale the coordinates, evaluate, and divide the feature position back by Scale.
void eval_voronoi_node(const Instruction& ins, const ShaderProgram& /*program*/,
                       const ShaderGlobals& /*globals*/, float* registers) {
  const uint32_t dims = ins.mode & 0xFu;
  voronoi::Params params;
  params.feature = static_cast<voronoi::Feature>((ins.mode >> 4) & 0xFu);
  params.metric = static_cast<voronoi::Metric>((ins.mode >> 8) & 0xFu);
  const Vec3 coord_in =
      ins.in[kVoronoiInVector] >= 0 ? load3(registers, ins.in[kVoronoiInVector]) : Vec3(0.0f);
  const float w_in = input1(ins, registers, kVoronoiInW);
  const float scale = input1(ins, registers, kVoronoiInScale);
  params.exponent = input1(ins, registers, kVoronoiInExponent);
  params.randomness = std::clamp(input1(ins, registers, kVoronoiInRandomness), 0.0f, 1.0f);
  params.smoothness = std::clamp(input1(ins, registers, kVoronoiInSmoothness) / 2.0f, 0.0f, 0.5f);
  const Vec3 coord = coord_in * scale;
  const float w = w_in * scale;

  voronoi::Result r;
  Vec3 position(0.0f);
  float w_out = 0.0f;
  // Vectors divide as Cycles' float-vector division does: by multiplying with 1 / Scale.
  const float inv_scale = scale != 0.0f ? 1.0f / scale : 0.0f;
  switch (dims) {
    case 1:
      r = voronoi::voronoi_1d(w, params);
      w_out = safe_divide(r.position[3], scale);
      break;
    case 2:
      r = voronoi::voronoi_2d(coord.x, coord.y, params);
      position = Vec3(r.position[0] * inv_scale, r.position[1] * inv_scale, 0.0f);
      break;
    case 3:
      r = voronoi::voronoi_3d(coord, params);
      position = Vec3(r.position[0], r.position[1], r.position[2]) * inv_scale;
      break;
    case 4:
      r = voronoi::voronoi_4d(coord, w, params);
      position = Vec3(r.position[0], r.position[1], r.position[2]) * inv_scale;
      w_out = r.position[3] * inv_scale;
      break;
    default:
      break;
  }
  store1(registers, ins.out[kVoronoiOutDistance], r.distance);
  store3(registers, ins.out[kVoronoiOutColor], r.color);
  store3(registers, ins.out[kVoronoiOutPosition], position);
  store1(registers, ins.out[kVoronoiOutW], w_out);
  store1(registers, ins.out[kVoronoiOutRadius], r.radius);
}

}  // namespace photon
