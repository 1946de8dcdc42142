#include "photon/shading/noise_nodes.h"

#include <cmath>
#include <utility>

#include "photon/shading/gabor.h"
#include "photon/shading/hash.h"
#include "photon/shading/noise.h"
#include "photon/shading/noise_fractal.h"

namespace photon {
namespace {

using noise::Point;

// Input slots of each node (Instruction::in), in Blender's socket order.
enum NoiseIn {
  kNoiseVector,
  kNoiseW,
  kNoiseScale,
  kNoiseDetail,
  kNoiseRoughness,
  kNoiseDistortion
};
enum MusgraveIn {
  kMusVector,
  kMusW,
  kMusScale,
  kMusDetail,
  kMusDimension,
  kMusLacunarity,
  kMusOffset,
  kMusGain
};
enum WhiteIn { kWhiteVector, kWhiteW };
enum WaveIn {
  kWaveVector,
  kWaveScale,
  kWaveDistortion,
  kWaveDetail,
  kWaveDetailScale,
  kWaveDetailRoughness,
  kWavePhase
};

enum MusgraveType { kMultifractal, kRidged, kHybrid, kFbm, kHeteroTerrain };
enum WaveType { kBands, kRings };
enum WaveProfile { kSin, kSaw, kTri };

// Instruction::mode: dimensions in bits 0-3, a type in 4-7, a direction in 8-11, a profile in
// 12-15.
uint32_t pack_mode(uint32_t dims, uint32_t type, uint32_t direction, uint32_t profile) {
  return dims | (type << 4) | (direction << 8) | (profile << 12);
}
uint32_t mode_dims(uint32_t mode) {
  return mode & 15u;
}
uint32_t mode_type(uint32_t mode) {
  return (mode >> 4) & 15u;
}
uint32_t mode_direction(uint32_t mode) {
  return (mode >> 8) & 15u;
}
uint32_t mode_profile(uint32_t mode) {
  return (mode >> 12) & 15u;
}

struct Socket {
  const char* identifier;
  float default_value;  // Blender's default, used when the add-on sent no register
};

// Binds the node's inputs to registers. Vector stays -1 when absent (eval reads the Generated
// coordinate then, as Cycles does for an unlinked texture vector); a missing float input gets a
// new register holding Blender's default so hand-built descriptions still evaluate.
void bind_inputs(const NodeDesc& desc, const Socket* sockets, int count, ShaderProgram* program,
                 Instruction* out) {
  for (int i = 0; i < count; ++i) {
    int32_t reg = input_register(desc, sockets[i].identifier);
    if (reg < 0 && std::string(sockets[i].identifier) != "Vector") {
      reg = static_cast<int32_t>(program->registers.size());
      program->registers.push_back(sockets[i].default_value);
    }
    out->in[i] = reg;
  }
}

// Looks `value` up in `names`; returns its index or -1.
int find_name(const std::string& value, std::initializer_list<const char*> names) {
  int i = 0;
  for (const char* name : names) {
    if (value == name) return i;
    ++i;
  }
  return -1;
}

bool parse_enum(const NodeDesc& desc, const char* property, const char* fallback,
                std::initializer_list<const char*> names, int* result, std::string* error) {
  std::string value = enum_value(desc, property, fallback);
  *result = find_name(value, names);
  if (*result < 0) {
    *error = desc.type + ": unknown " + property + " '" + value + "'";
    return false;
  }
  return true;
}

// ---- Noise Texture (Cycles' noise_texture_{1,2,3,4}d) ----

template <int N>
void noise_texture(Point<N> p, float detail, float roughness, float distortion, bool need_color,
                   float* value, Vec3* color) {
  if (distortion != 0.0f) {
    // Every axis is displaced by its own noise, all sampled at the undistorted point.
    Point<N> offset;
    for (int i = 0; i < N; ++i)
      offset[i] = noise::snoise<N>(p + noise::random_offset<N>(static_cast<float>(i))) * distortion;
    p = p + offset;
  }
  *value = noise::fractal_noise<N>(p, detail, roughness);
  if (need_color) {
    *color = Vec3(
        *value, noise::fractal_noise<N>(p + noise::random_offset<N>(float(N)), detail, roughness),
        noise::fractal_noise<N>(p + noise::random_offset<N>(float(N + 1)), detail, roughness));
  }
}

// ---- Musgrave Texture (Musgrave, "Texturing and Modeling", 3rd ed., ch. 16) ----

template <int N>
float musgrave_fbm(Point<N> p, float h, float lacunarity, float octaves) {
  float value = 0.0f, pwr = 1.0f, pw_hl = std::pow(lacunarity, -h);
  int whole = static_cast<int>(octaves);
  for (int i = 0; i < whole; ++i) {
    value += noise::snoise<N>(p) * pwr;
    pwr *= pw_hl;
    p = p * lacunarity;
  }
  float rmd = octaves - std::floor(octaves);
  if (rmd != 0.0f) value += rmd * noise::snoise<N>(p) * pwr;
  return value;
}

template <int N>
float musgrave_multifractal(Point<N> p, float h, float lacunarity, float octaves) {
  float value = 1.0f, pwr = 1.0f, pw_hl = std::pow(lacunarity, -h);
  int whole = static_cast<int>(octaves);
  for (int i = 0; i < whole; ++i) {
    value *= pwr * noise::snoise<N>(p) + 1.0f;
    pwr *= pw_hl;
    p = p * lacunarity;
  }
  float rmd = octaves - std::floor(octaves);
  if (rmd != 0.0f) value *= rmd * pwr * noise::snoise<N>(p) + 1.0f;
  return value;
}

template <int N>
float musgrave_hetero_terrain(Point<N> p, float h, float lacunarity, float octaves, float offset) {
  float pw_hl = std::pow(lacunarity, -h), pwr = pw_hl;
  // The first octave is unscaled; later ones are scaled by the value so far.
  float value = offset + noise::snoise<N>(p);
  p = p * lacunarity;
  int whole = static_cast<int>(octaves);
  for (int i = 1; i < whole; ++i) {
    value += (noise::snoise<N>(p) + offset) * pwr * value;
    pwr *= pw_hl;
    p = p * lacunarity;
  }
  float rmd = octaves - std::floor(octaves);
  if (rmd != 0.0f) value += rmd * ((noise::snoise<N>(p) + offset) * pwr * value);
  return value;
}

template <int N>
float musgrave_hybrid_multifractal(Point<N> p, float h, float lacunarity, float octaves,
                                   float offset, float gain) {
  float pw_hl = std::pow(lacunarity, -h);
  float pwr = 1.0f, value = 0.0f, weight = 1.0f;
  int whole = static_cast<int>(octaves);
  for (int i = 0; weight > 0.001f && i < whole; ++i) {
    weight = std::min(weight, 1.0f);
    float signal = (noise::snoise<N>(p) + offset) * pwr;
    pwr *= pw_hl;
    value += weight * signal;
    weight *= gain * signal;
    p = p * lacunarity;
  }
  float rmd = octaves - std::floor(octaves);
  if (rmd != 0.0f && weight > 0.001f) {
    weight = std::min(weight, 1.0f);
    value += rmd * weight * ((noise::snoise<N>(p) + offset) * pwr);
  }
  return value;
}

template <int N>
float musgrave_ridged_multifractal(Point<N> p, float h, float lacunarity, float octaves,
                                   float offset, float gain) {
  float pw_hl = std::pow(lacunarity, -h), pwr = pw_hl;
  float signal = offset - std::fabs(noise::snoise<N>(p));
  signal *= signal;
  float value = signal;
  int whole = static_cast<int>(octaves);
  for (int i = 1; i < whole; ++i) {
    p = p * lacunarity;
    float weight = std::clamp(signal * gain, 0.0f, 1.0f);
    signal = offset - std::fabs(noise::snoise<N>(p));
    signal *= signal;
    signal *= weight;
    value += signal * pwr;
    pwr *= pw_hl;
  }
  return value;
}

template <int N>
float musgrave(uint32_t type, const Point<N>& p, float h, float lacunarity, float octaves,
               float offset, float gain) {
  switch (type) {
    case kMultifractal:
      return musgrave_multifractal<N>(p, h, lacunarity, octaves);
    case kRidged:
      return musgrave_ridged_multifractal<N>(p, h, lacunarity, octaves, offset, gain);
    case kHybrid:
      return musgrave_hybrid_multifractal<N>(p, h, lacunarity, octaves, offset, gain);
    case kFbm:
      return musgrave_fbm<N>(p, h, lacunarity, octaves);
    default:
      return musgrave_hetero_terrain<N>(p, h, lacunarity, octaves, offset);
  }
}

// ---- White Noise: lookup3 of the coordinate's bits (Cycles' hash_floatN_to_float{,3}) ----

float white_value(uint32_t dims, const Vec3& v, float w) {
  switch (dims) {
    case 1:
      return hash::hash_float_to_float(w);
    case 2:
      return hash::hash_float2_to_float(v.x, v.y);
    case 3:
      return hash::hash_float3_to_float(v);
    default:
      return hash::hash_float4_to_float(v, w);
  }
}

Vec3 white_color(uint32_t dims, const Vec3& v, float w) {
  switch (dims) {
    case 1:
      return Vec3(hash::hash_float_to_float(w), hash::hash_float2_to_float(w, 1.0f),
                  hash::hash_float2_to_float(w, 2.0f));
    case 2:
      return Vec3(hash::hash_float2_to_float(v.x, v.y),
                  hash::hash_float3_to_float(Vec3(v.x, v.y, 1.0f)),
                  hash::hash_float3_to_float(Vec3(v.x, v.y, 2.0f)));
    case 3:
      return Vec3(hash::hash_float3_to_float(v), hash::hash_float4_to_float(v, 1.0f),
                  hash::hash_float4_to_float(v, 2.0f));
    default:
      // The 4D colour permutes the components for its second and third channels.
      return Vec3(hash::hash_float4_to_float(v, w),
                  hash::hash_float4_to_float(Vec3(v.z, v.x, w), v.y),
                  hash::hash_float4_to_float(Vec3(w, v.z, v.y), v.x));
  }
}

// ---- Wave Texture (Cycles' svm_wave) ----

float wave(uint32_t type, uint32_t direction, uint32_t profile, Vec3 p, float distortion,
           float detail, float detail_scale, float detail_roughness, float phase,
           bool cycles4 = false) {
  // Blender nudges the coordinate so unit coordinates do not land exactly on band edges.
  p = (p + Vec3(0.000001f)) * 0.999999f;
  float n;
  if (type == kBands) {
    switch (direction) {
      case 0:
        n = p.x * 20.0f;
        break;
      case 1:
        n = p.y * 20.0f;
        break;
      case 2:
        n = p.z * 20.0f;
        break;
      default:
        n = (p.x + p.y + p.z) * 10.0f;
        break;
    }
  } else {
    Vec3 rp = p;
    switch (direction) {
      case 0:
        rp *= Vec3(0.0f, 1.0f, 1.0f);
        break;
      case 1:
        rp *= Vec3(1.0f, 0.0f, 1.0f);
        break;
      case 2:
        rp *= Vec3(1.0f, 1.0f, 0.0f);
        break;
      default:
        break;  // spherical
    }
    n = length(rp) * 20.0f;
  }
  n += phase;
  if (distortion != 0.0f && cycles4)  // Cycles 4.x: noise_fbm, detail and roughness unclamped
    n += distortion *
         (noise::fbm_3d_4x(p * detail_scale, detail, detail_roughness, 2.0f, true) * 2.0f - 1.0f);
  else if (distortion != 0.0f)
    n += distortion *
         (noise::fractal_noise_3d(p * detail_scale, detail, detail_roughness) * 2.0f - 1.0f);
  constexpr float kTwoPi = 2.0f * kPi;
  switch (profile) {
    case kSin:
      return 0.5f + 0.5f * std::sin(n - 0.5f * kPi);
    case kSaw:
      n /= kTwoPi;
      return n - std::floor(n);
    default:
      n /= kTwoPi;
      return std::fabs(n - std::floor(n + 0.5f)) * 2.0f;
  }
}

Vec3 load_vector(const Instruction& ins, int slot, const ShaderGlobals& globals, const float* r) {
  return ins.in[slot] >= 0 ? load3(r, ins.in[slot]) : globals.generated;
}

// Detail as Blender clamps it; a NaN detail (bad input) counts as 0 octaves.
float clamp_octaves(float detail) {
  return detail >= 0.0f ? std::min(detail, 15.0f) : 0.0f;
}

void eval_noise(const Instruction& ins, const ShaderGlobals& globals, float* r) {
  float scale = load1(r, ins.in[kNoiseScale]);
  Vec3 v = load_vector(ins, kNoiseVector, globals, r) * scale;
  float w = load1(r, ins.in[kNoiseW]) * scale;
  float detail = load1(r, ins.in[kNoiseDetail]);
  float roughness = load1(r, ins.in[kNoiseRoughness]);
  float distortion = load1(r, ins.in[kNoiseDistortion]);
  bool need_color = ins.out[1] >= 0;
  float value = 0.0f;
  Vec3 color(0.0f);
  switch (mode_dims(ins.mode)) {
    case 1:
      noise_texture<1>({w}, detail, roughness, distortion, need_color, &value, &color);
      break;
    case 2:
      noise_texture<2>({v.x, v.y}, detail, roughness, distortion, need_color, &value, &color);
      break;
    case 3:
      noise_texture<3>(noise::point(v), detail, roughness, distortion, need_color, &value, &color);
      break;
    default:
      noise_texture<4>(noise::point(v, w), detail, roughness, distortion, need_color, &value,
                       &color);
      break;
  }
  store1(r, ins.out[0], value);
  store3(r, ins.out[1], color);
}

// Blender 4.x's Noise Texture (Cycles' svm_node_tex_noise of 4.1+). in[]: Vector, W, Scale,
// Detail, Roughness, Lacunarity, Offset, Gain; Distortion's register is program.data[ins.data].
// mode: dimensions in bits 0-3, noise::FractalType in 4-7, Normalize in bit 8.
enum Noise4xIn { k4Vector, k4W, k4Scale, k4Detail, k4Roughness, k4Lacunarity, k4Offset, k4Gain };

void eval_noise_4x(const Instruction& ins, const ShaderProgram& program,
                   const ShaderGlobals& globals, float* r) {
  const float scale = load1(r, ins.in[k4Scale]);
  const Vec3 v = load_vector(ins, k4Vector, globals, r) * scale;
  const float w = load1(r, ins.in[k4W]) * scale;
  noise::FractalParams f;
  f.type = static_cast<noise::FractalType>(mode_type(ins.mode));
  f.normalize = (ins.mode >> 8) & 1u;
  f.detail = clamp_octaves(load1(r, ins.in[k4Detail]));
  f.roughness = std::fmax(load1(r, ins.in[k4Roughness]), 0.0f);
  f.lacunarity = load1(r, ins.in[k4Lacunarity]);
  f.offset = load1(r, ins.in[k4Offset]);
  f.gain = load1(r, ins.in[k4Gain]);
  const float distortion = load1(r, static_cast<int32_t>(program.data[ins.data]));
  Vec3 color(0.0f);
  Vec3* want_color = ins.out[1] >= 0 ? &color : nullptr;
  float value;
  switch (mode_dims(ins.mode)) {
    case 1:
      value = noise::noise_texture_4x<1>({w}, f, distortion, want_color);
      break;
    case 2:
      value = noise::noise_texture_4x<2>({v.x, v.y}, f, distortion, want_color);
      break;
    case 3:
      value = noise::noise_texture_4x<3>(noise::point(v), f, distortion, want_color);
      break;
    default:
      value = noise::noise_texture_4x<4>(noise::point(v, w), f, distortion, want_color);
      break;
  }
  store1(r, ins.out[0], value);
  store3(r, ins.out[1], color);
}

// Blender 4.3's Gabor Texture. in[]: Vector, Scale, Frequency, Anisotropy, Orientation 2D,
// Orientation 3D; out[]: Value, Phase, Intensity; mode: 2 or 3 (dimensions).
void eval_gabor(const Instruction& ins, const ShaderGlobals& globals, float* r) {
  const Vec3 p = load_vector(ins, 0, globals, r) * load1(r, ins.in[1]);
  const float frequency = load1(r, ins.in[2]), anisotropy = load1(r, ins.in[3]);
  const gabor::Result g = mode_dims(ins.mode) == 2
                              ? gabor::gabor_2d(p, frequency, anisotropy, load1(r, ins.in[4]))
                              : gabor::gabor_3d(p, frequency, anisotropy, load3(r, ins.in[5]));
  store1(r, ins.out[0], g.value);
  store1(r, ins.out[1], g.phase);
  store1(r, ins.out[2], g.intensity);
}

void eval_musgrave(const Instruction& ins, const ShaderGlobals& globals, float* r) {
  float scale = load1(r, ins.in[kMusScale]);
  Vec3 v = load_vector(ins, kMusVector, globals, r) * scale;
  float w = load1(r, ins.in[kMusW]) * scale;
  float octaves = clamp_octaves(load1(r, ins.in[kMusDetail]));
  float h = std::fmax(load1(r, ins.in[kMusDimension]), 1e-5f);
  float lacunarity = std::fmax(load1(r, ins.in[kMusLacunarity]), 1e-5f);
  float offset = load1(r, ins.in[kMusOffset]);
  float gain = load1(r, ins.in[kMusGain]);
  uint32_t type = mode_type(ins.mode);
  float value;
  switch (mode_dims(ins.mode)) {
    case 1:
      value = musgrave<1>(type, {w}, h, lacunarity, octaves, offset, gain);
      break;
    case 2:
      value = musgrave<2>(type, {v.x, v.y}, h, lacunarity, octaves, offset, gain);
      break;
    case 3:
      value = musgrave<3>(type, noise::point(v), h, lacunarity, octaves, offset, gain);
      break;
    default:
      value = musgrave<4>(type, noise::point(v, w), h, lacunarity, octaves, offset, gain);
      break;
  }
  store1(r, ins.out[0], value);
}

void eval_white_noise(const Instruction& ins, const ShaderGlobals& globals, float* r) {
  Vec3 v = load_vector(ins, kWhiteVector, globals, r);
  float w = load1(r, ins.in[kWhiteW]);
  uint32_t dims = mode_dims(ins.mode);
  if (ins.out[0] >= 0) store1(r, ins.out[0], white_value(dims, v, w));
  if (ins.out[1] >= 0) store3(r, ins.out[1], white_color(dims, v, w));
}

void eval_wave(const Instruction& ins, const ShaderGlobals& globals, float* r,
               bool cycles4 = false) {
  Vec3 p = load_vector(ins, kWaveVector, globals, r) * load1(r, ins.in[kWaveScale]);
  float f = wave(mode_type(ins.mode), mode_direction(ins.mode), mode_profile(ins.mode), p,
                 load1(r, ins.in[kWaveDistortion]), load1(r, ins.in[kWaveDetail]),
                 load1(r, ins.in[kWaveDetailScale]), load1(r, ins.in[kWaveDetailRoughness]),
                 load1(r, ins.in[kWavePhase]), cycles4);
  if (!std::isfinite(f)) f = 0.0f;  // an infinite coordinate or phase: Cycles gives NaN here
  store3(r, ins.out[0], Vec3(f));
  store1(r, ins.out[1], f);
}

}  // namespace

CompileStatus compile_noise_node(const NodeDesc& desc, ShaderProgram* program, Instruction* out,
                                 std::string* error) {
  static const Socket kNoiseSockets[] = {{"Vector", 0.0f},    {"W", 0.0f},
                                         {"Scale", 5.0f},     {"Detail", 2.0f},
                                         {"Roughness", 0.5f}, {"Distortion", 0.0f}};
  static const Socket kMusgraveSockets[] = {
      {"Vector", 0.0f},    {"W", 0.0f},          {"Scale", 5.0f},  {"Detail", 2.0f},
      {"Dimension", 2.0f}, {"Lacunarity", 2.0f}, {"Offset", 0.0f}, {"Gain", 1.0f}};
  static const Socket kWhiteSockets[] = {{"Vector", 0.0f}, {"W", 0.0f}};
  static const Socket kWaveSockets[] = {{"Vector", 0.0f},       {"Scale", 5.0f},
                                        {"Distortion", 0.0f},   {"Detail", 2.0f},
                                        {"Detail Scale", 1.0f}, {"Detail Roughness", 0.5f},
                                        {"Phase Offset", 0.0f}};
  const auto dims = {"1D", "2D", "3D", "4D"};

  Instruction ins;
  ins.family = NodeFamily::kNoise;
  int d = 0, type = 0, direction = 0, profile = 0;
  const bool noise_4x = desc.type == "ShaderNodeTexNoise" &&
                        (desc.enums.count("noise_type") > 0 || desc.enums.count("normalize") > 0 ||
                         desc.inputs.count("Lacunarity") > 0);
  if (noise_4x) {
    static const Socket kNoise4xSockets[] = {
        {"Vector", 0.0f},    {"W", 0.0f},          {"Scale", 5.0f},  {"Detail", 2.0f},
        {"Roughness", 0.5f}, {"Lacunarity", 2.0f}, {"Offset", 0.0f}, {"Gain", 1.0f}};
    // Blender's identifiers, in the order of Cycles' NodeNoiseType (noise::FractalType).
    if (!parse_enum(desc, "noise_dimensions", "3D", dims, &d, error) ||
        !parse_enum(
            desc, "noise_type", "FBM",
            {"MULTIFRACTAL", "FBM", "HYBRID_MULTIFRACTAL", "RIDGED_MULTIFRACTAL", "HETERO_TERRAIN"},
            &type, error))
      return CompileStatus::kError;
    ins.kind = static_cast<uint16_t>(NoiseNodeKind::kNoise4x);
    bind_inputs(desc, kNoise4xSockets, 8, program, &ins);
    int32_t distortion = input_register(desc, "Distortion");
    if (distortion < 0) {
      distortion = static_cast<int32_t>(program->registers.size());
      program->registers.push_back(0.0f);
    }
    ins.data = static_cast<int32_t>(program->data.size());
    ins.data_size = 1;
    program->data.push_back(static_cast<float>(distortion));  // a register index (exact < 2^24)
    ins.out[0] = output_register(desc, "Fac");
    ins.out[1] = output_register(desc, "Color");
    const bool normalize = enum_value(desc, "normalize", "True") == "True";
    ins.mode = pack_mode(static_cast<uint32_t>(d + 1), static_cast<uint32_t>(type), 0, 0) |
               (normalize ? 1u << 8 : 0u);
    *out = ins;
    return CompileStatus::kCompiled;
  }
  if (desc.type == "ShaderNodeTexGabor") {
    if (!parse_enum(desc, "gabor_type", "2D", {"2D", "3D"}, &d, error))
      return CompileStatus::kError;
    ins.kind = static_cast<uint16_t>(NoiseNodeKind::kGabor);
    ins.in[0] = input_register(desc, "Vector");
    const std::pair<const char*, float> floats[] = {{"Scale", 5.0f},
                                                    {"Frequency", 2.0f},
                                                    {"Anisotropy", 1.0f},
                                                    {"Orientation 2D", 0.78539816339744830962f}};
    for (int i = 0; i < 4; ++i) {
      int32_t reg = input_register(desc, floats[i].first);
      if (reg < 0) {
        reg = static_cast<int32_t>(program->registers.size());
        program->registers.push_back(floats[i].second);
      }
      ins.in[1 + i] = reg;
    }
    ins.in[5] = input_register(desc, "Orientation 3D");
    if (ins.in[5] < 0) {
      ins.in[5] = static_cast<int32_t>(program->registers.size());
      program->registers.insert(program->registers.end(),
                                {1.41421356237309504880f, 1.41421356237309504880f, 0.0f});
    }
    ins.out[0] = output_register(desc, "Value");
    ins.out[1] = output_register(desc, "Phase");
    ins.out[2] = output_register(desc, "Intensity");
    ins.mode = pack_mode(static_cast<uint32_t>(d + 2), 0, 0, 0);
    *out = ins;
    return CompileStatus::kCompiled;
  }
  if (desc.type == "ShaderNodeTexNoise") {
    if (!parse_enum(desc, "noise_dimensions", "3D", dims, &d, error)) return CompileStatus::kError;
    ins.kind = static_cast<uint16_t>(NoiseNodeKind::kNoise);
    bind_inputs(desc, kNoiseSockets, 6, program, &ins);
    ins.out[0] = output_register(desc, "Fac");
    ins.out[1] = output_register(desc, "Color");
  } else if (desc.type == "ShaderNodeTexMusgrave") {
    if (!parse_enum(desc, "musgrave_dimensions", "3D", dims, &d, error) ||
        !parse_enum(
            desc, "musgrave_type", "FBM",
            {"MULTIFRACTAL", "RIDGED_MULTIFRACTAL", "HYBRID_MULTIFRACTAL", "FBM", "HETERO_TERRAIN"},
            &type, error))
      return CompileStatus::kError;
    ins.kind = static_cast<uint16_t>(NoiseNodeKind::kMusgrave);
    bind_inputs(desc, kMusgraveSockets, 8, program, &ins);
    ins.out[0] = output_register(desc, "Fac");
  } else if (desc.type == "ShaderNodeTexWhiteNoise") {
    if (!parse_enum(desc, "noise_dimensions", "3D", dims, &d, error)) return CompileStatus::kError;
    ins.kind = static_cast<uint16_t>(NoiseNodeKind::kWhiteNoise);
    bind_inputs(desc, kWhiteSockets, 2, program, &ins);
    ins.out[0] = output_register(desc, "Value");
    ins.out[1] = output_register(desc, "Color");
  } else if (desc.type == "ShaderNodeTexWave") {
    if (!parse_enum(desc, "wave_type", "BANDS", {"BANDS", "RINGS"}, &type, error) ||
        !parse_enum(desc, "wave_profile", "SIN", {"SIN", "SAW", "TRI"}, &profile, error))
      return CompileStatus::kError;
    bool ok = type == kBands ? parse_enum(desc, "bands_direction", "X", {"X", "Y", "Z", "DIAGONAL"},
                                          &direction, error)
                             : parse_enum(desc, "rings_direction", "X",
                                          {"X", "Y", "Z", "SPHERICAL"}, &direction, error);
    if (!ok) return CompileStatus::kError;
    d = 2;  // always 3D
    ins.kind =
        static_cast<uint16_t>(enum_value(desc, "photon_cycles", "3") >= "4" ? NoiseNodeKind::kWave4x
                                                                            : NoiseNodeKind::kWave);
    bind_inputs(desc, kWaveSockets, 7, program, &ins);
    ins.out[0] = output_register(desc, "Color");
    ins.out[1] = output_register(desc, "Fac");
  } else {
    return CompileStatus::kUnknownNode;
  }
  ins.mode = pack_mode(static_cast<uint32_t>(d + 1), static_cast<uint32_t>(type),
                       static_cast<uint32_t>(direction), static_cast<uint32_t>(profile));
  *out = ins;
  return CompileStatus::kCompiled;
}

void eval_noise_node(const Instruction& ins, const ShaderProgram& program,
                     const ShaderGlobals& globals, float* registers) {
  switch (static_cast<NoiseNodeKind>(ins.kind)) {
    case NoiseNodeKind::kNoise4x:
      eval_noise_4x(ins, program, globals, registers);
      break;
    case NoiseNodeKind::kWave4x:
      eval_wave(ins, globals, registers, /*cycles4=*/true);
      break;
    case NoiseNodeKind::kGabor:
      eval_gabor(ins, globals, registers);
      break;
    case NoiseNodeKind::kNoise:
      eval_noise(ins, globals, registers);
      break;
    case NoiseNodeKind::kMusgrave:
      eval_musgrave(ins, globals, registers);
      break;
    case NoiseNodeKind::kWhiteNoise:
      eval_white_noise(ins, globals, registers);
      break;
    case NoiseNodeKind::kWave:
      eval_wave(ins, globals, registers);
      break;
  }
}

}  // namespace photon
