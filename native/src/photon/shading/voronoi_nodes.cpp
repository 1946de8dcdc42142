#include "photon/shading/voronoi_nodes.h"

#include <algorithm>
#include <cmath>

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

CompileStatus compile_voronoi_node(const NodeDesc& desc, ShaderProgram* program, Instruction* out,
                                   std::string* error) {
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
  const bool fractal = desc.enums.count("normalize") > 0 || desc.inputs.count("Detail") > 0;
  if (fractal) {  // Blender 4.x
    constexpr const char* kNames4x[] = {"Vector",    "W",          "Scale",      "Detail",
                                        "Roughness", "Lacunarity", "Smoothness", "Exponent"};
    constexpr float kDefaults4x[] = {0.0f, 0.0f, 5.0f, 0.0f, 0.5f, 2.0f, 1.0f, 0.5f};
    ins.kind = 1;
    const bool normalize = enum_value(desc, "normalize", "False") == "True";
    ins.mode = dims | (feature << 4) | (metric << 8) | (normalize ? 1u << 12 : 0u);
    for (int i = 0; i < 8; ++i) {
      int32_t reg = input_register(desc, kNames4x[i]);
      if (reg < 0 && i != kVoronoi4xInVector) {  // a hand-built description: Blender's default
        reg = static_cast<int32_t>(program->registers.size());
        program->registers.push_back(kDefaults4x[i]);
      }
      ins.in[i] = reg;
    }
    int32_t randomness = input_register(desc, "Randomness");
    if (randomness < 0) {
      randomness = static_cast<int32_t>(program->registers.size());
      program->registers.push_back(1.0f);
    }
    ins.data = static_cast<int32_t>(program->data.size());
    ins.data_size = 1;
    program->data.push_back(static_cast<float>(randomness));  // a register index
    for (int i = 0; i < 5; ++i) ins.out[i] = output_register(desc, kOutputNames[i]);
    *out = ins;
    return CompileStatus::kCompiled;
  }
  ins.kind = 0;
  ins.mode = dims | (feature << 4) | (metric << 8);
  for (int i = 0; i < 6; ++i) ins.in[i] = input_register(desc, kInputNames[i]);
  for (int i = 0; i < 5; ++i) ins.out[i] = output_register(desc, kOutputNames[i]);
  *out = ins;
  return CompileStatus::kCompiled;
}

namespace {

// ---- Blender 4.x: fractal Voronoi (Cycles 4.x's fractal_voronoi_x_fx and
// fractal_voronoi_distance_to_edge) over the same per-octave cell searches ----

// Cycles' mix(a, b, t) = a + t (b - a).
inline float mix(float a, float b, float t) {
  return a + t * (b - a);
}

// The octave of a point of `dims` dimensions (coordinates already scaled).
voronoi::Result octave(uint32_t dims, const Vec3& p, float w, const voronoi::Params& params) {
  switch (dims) {
    case 1:
      return voronoi::voronoi_1d(w, params);
    case 2:
      return voronoi::voronoi_2d(p.x, p.y, params);
    case 3:
      return voronoi::voronoi_3d(p, params);
    default:
      return voronoi::voronoi_4d(p, w, params);
  }
}

// The distance from the origin to (c, c, ...) in `dims` dimensions under the metric (Cycles'
// voronoi_distance(zero, c)): the largest F1 distance, for Normalize.
float corner_distance(uint32_t dims, float c, const voronoi::Params& params) {
  if (dims == 1) return c;
  const float n = static_cast<float>(dims);
  switch (params.metric) {
    case voronoi::Metric::kEuclidean: {
      const float sq = c * c;
      float sum = sq;
      for (uint32_t i = 1; i < dims; ++i) sum += sq;
      if (dims == 4) sum = (sq + sq) + (sq + sq);
      return std::sqrt(sum);
    }
    case voronoi::Metric::kManhattan: {
      float sum = c;
      for (uint32_t i = 1; i < dims; ++i) sum += c;
      return sum;
    }
    case voronoi::Metric::kChebychev:
      return c;
    case voronoi::Metric::kMinkowski: {
      const float e = params.exponent;
      const float t = std::pow(c, e);
      float sum = t;
      for (uint32_t i = 1; i < dims; ++i) sum += t;
      (void)n;
      return std::pow(sum, 1.0f / e);
    }
  }
  return 0.0f;
}

void eval_voronoi_4x(const Instruction& ins, const ShaderProgram& program, float* r) {
  const uint32_t dims = ins.mode & 0xFu;
  const auto feature = static_cast<voronoi::Feature>((ins.mode >> 4) & 0xFu);
  voronoi::Params params;
  params.feature = feature;
  params.metric = static_cast<voronoi::Metric>((ins.mode >> 8) & 0xFu);
  const bool normalize = (ins.mode >> 12) & 1u;
  const Vec3 coord_in =
      ins.in[kVoronoi4xInVector] >= 0 ? load3(r, ins.in[kVoronoi4xInVector]) : Vec3(0.0f);
  const float scale = load1(r, ins.in[kVoronoi4xInScale]);
  float detail = load1(r, ins.in[kVoronoi4xInDetail]);
  detail = detail >= 0.0f ? std::min(detail, 15.0f) : 0.0f;
  float roughness = load1(r, ins.in[kVoronoi4xInRoughness]);
  roughness = roughness >= 0.0f ? std::min(roughness, 1.0f) : 0.0f;
  const float lacunarity = load1(r, ins.in[kVoronoi4xInLacunarity]);
  params.exponent = load1(r, ins.in[kVoronoi4xInExponent]);
  const float randomness = load1(r, static_cast<int32_t>(program.data[ins.data]));
  params.randomness = std::clamp(randomness, 0.0f, 1.0f);
  params.smoothness = std::clamp(load1(r, ins.in[kVoronoi4xInSmoothness]) / 2.0f, 0.0f, 0.5f);
  const Vec3 coord = coord_in * scale;
  const float w = load1(r, ins.in[kVoronoi4xInW]) * scale;
  const bool zero_input = detail == 0.0f || roughness == 0.0f;
  const float half = 0.5f + 0.5f * params.randomness;

  if (feature == voronoi::Feature::kNSphereRadius) {
    voronoi::Result o = octave(dims, coord, w, params);
    store1(r, ins.out[kVoronoiOutDistance], 0.0f);
    store3(r, ins.out[kVoronoiOutColor], Vec3(0.0f));
    store3(r, ins.out[kVoronoiOutPosition], Vec3(0.0f));
    store1(r, ins.out[kVoronoiOutW], 0.0f);
    store1(r, ins.out[kVoronoiOutRadius], o.radius);
    return;
  }
  if (feature == voronoi::Feature::kDistanceToEdge) {
    const float max_distance = half;
    float amplitude = 1.0f, max_amplitude = max_distance, octave_scale = 1.0f, distance = 8.0f;
    for (int i = 0; i <= std::ceil(detail); ++i) {
      const float d = octave(dims, coord * octave_scale, w * octave_scale, params).distance;
      if (zero_input) {
        distance = d;
        break;
      }
      if (i <= detail) {
        max_amplitude = mix(max_amplitude, max_distance / octave_scale, amplitude);
        distance = mix(distance, std::min(distance, d / octave_scale), amplitude);
        octave_scale *= lacunarity;
        amplitude *= roughness;
      } else {
        const float remainder = detail - std::floor(detail);
        if (remainder != 0.0f) {
          const float lerp_amplitude = mix(max_amplitude, max_distance / octave_scale, amplitude);
          max_amplitude = mix(max_amplitude, lerp_amplitude, remainder);
          const float lerp_distance =
              mix(distance, std::min(distance, d / octave_scale), amplitude);
          distance = mix(distance, std::min(distance, lerp_distance), remainder);
        }
      }
    }
    if (normalize) distance /= max_amplitude;
    store1(r, ins.out[kVoronoiOutDistance], distance);
    store3(r, ins.out[kVoronoiOutColor], Vec3(0.0f));
    store3(r, ins.out[kVoronoiOutPosition], Vec3(0.0f));
    store1(r, ins.out[kVoronoiOutW], 0.0f);
    store1(r, ins.out[kVoronoiOutRadius], 0.0f);
    return;
  }
  // F1, F2, Smooth F1 (which is F1 at Smoothness 0).
  if (feature == voronoi::Feature::kSmoothF1 && params.smoothness == 0.0f)
    params.feature = voronoi::Feature::kF1;
  const float max_distance =
      corner_distance(dims, half, params) * (feature == voronoi::Feature::kF2 ? 2.0f : 1.0f);
  float amplitude = 1.0f, max_amplitude = 0.0f, octave_scale = 1.0f;
  float distance = 0.0f;
  Vec3 color(0.0f);
  float position[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  for (int i = 0; i <= std::ceil(detail); ++i) {
    const voronoi::Result o = octave(dims, coord * octave_scale, w * octave_scale, params);
    if (zero_input) {
      max_amplitude = 1.0f;
      distance = o.distance;
      color = o.color;
      for (int k = 0; k < 4; ++k) position[k] = o.position[k];
      break;
    }
    if (i <= detail) {
      max_amplitude += amplitude;
      distance += o.distance * amplitude;
      color += o.color * amplitude;
      for (int k = 0; k < 4; ++k)
        position[k] = mix(position[k], o.position[k] / octave_scale, amplitude);
      octave_scale *= lacunarity;
      amplitude *= roughness;
    } else {
      const float remainder = detail - std::floor(detail);
      if (remainder != 0.0f) {
        max_amplitude = mix(max_amplitude, max_amplitude + amplitude, remainder);
        distance = mix(distance, distance + o.distance * amplitude, remainder);
        const Vec3 with = color + o.color * amplitude;
        color = Vec3(mix(color.x, with.x, remainder), mix(color.y, with.y, remainder),
                     mix(color.z, with.z, remainder));
        for (int k = 0; k < 4; ++k)
          position[k] = mix(position[k], mix(position[k], o.position[k] / octave_scale, amplitude),
                            remainder);
      }
    }
  }
  if (normalize) {
    distance /= max_amplitude * max_distance;
    color = color * (1.0f / max_amplitude);
  }
  for (float& c : position) c = safe_divide(c, scale);
  store1(r, ins.out[kVoronoiOutDistance], distance);
  store3(r, ins.out[kVoronoiOutColor], color);
  store3(r, ins.out[kVoronoiOutPosition],
         dims == 1 ? Vec3(0.0f) : Vec3(position[0], position[1], position[2]));
  store1(r, ins.out[kVoronoiOutW], position[3]);
  store1(r, ins.out[kVoronoiOutRadius], 0.0f);
}

}  // namespace

// Cycles' svm_node_tex_voronoi: clamp Randomness to [0, 1] and halve Smoothness into [0, 0.5],
// scale the coordinates, evaluate, and divide the feature position back by Scale.
void eval_voronoi_node(const Instruction& ins, const ShaderProgram& program,
                       const ShaderGlobals& /*globals*/, float* registers) {
  if (ins.kind == 1) {
    eval_voronoi_4x(ins, program, registers);
    return;
  }
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
