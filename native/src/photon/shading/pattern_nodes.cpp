// Checker, Gradient, Brick and Magic as Cycles 3.4 computes them (intern/cycles/kernel/svm/
// checker.h, gradient.h, brick.h, magic.h): the same float operations in the same order, so the
// textures match Cycles to float rounding. The Sky texture's models are in sky.cpp.
#include "photon/shading/pattern_nodes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>

#include "photon/shading/sky.h"

// SKYINC

namespace photon {
namespace {

// The register of an input, or a new register holding Blender's default when the add-on did not
// send the socket (a hidden or unavailable input), so evaluation never reads register -1.
int32_t input_or_default(const NodeDesc& desc, const char* identifier, ShaderProgram* program,
                         float v0, int components = 1, float v1 = 0.0f, float v2 = 0.0f) {
  int32_t reg = input_register(desc, identifier);
  if (reg >= 0) return reg;
  reg = static_cast<int32_t>(program->registers.size());
  const float values[3] = {v0, v1, v2};
  for (int i = 0; i < components; ++i) program->registers.push_back(values[i]);
  return reg;
}

bool registers_fit(const Instruction& ins, const ShaderProgram& program, std::string* error,
                   const std::string& type) {
  const int32_t count = static_cast<int32_t>(program.registers.size());
  auto bad = [count](int32_t r) { return r >= count; };
  for (int32_t r : ins.in)
    if (bad(r)) return *error = type + ": an input names a register past the program's end", false;
  for (int32_t r : ins.out)
    if (bad(r)) return *error = type + ": an output names a register past the program's end", false;
  return true;
}

float smoothstep_unit(float f) {  // 3f^2 - 2f^3 on f in [0, 1], as Cycles' smoothstepf
  const float ff = f * f;
  return 3.0f * ff - 2.0f * ff * f;
}

float saturate(float v) {
  return std::min(std::max(v, 0.0f), 1.0f);
}

// Cycles' brick tint: an integer hash (the "fast integer noise" of Blender's texture code).
float brick_noise(uint32_t n) {
  n = (n + 1013u) & 0x7fffffffu;
  n = (n >> 13) ^ n;
  const uint32_t nn = (n * (n * n * 60493u + 19990303u) + 1376312589u) & 0x7fffffffu;
  return 0.5f * (static_cast<float>(nn) / 1073741824.0f);
}

// floor() as an int. Out of range or NaN (huge or broken coordinates, a zero brick size) gives
// INT_MIN, what x86's truncating conversion returns to Cycles, without the C++ undefined
// behaviour of casting such a float.
int floor_to_int(float v) {
  const float f = std::floor(v);
  if (!(f >= -2147483648.0f && f < 2147483648.0f)) return std::numeric_limits<int>::min();
  return static_cast<int>(f);
}

}  // namespace

float checker_texture(const Vec3& p_in) {
  // Cycles nudges the point (+1e-6, then * 0.999999) so that integer coordinates, common on
  // unit-sized geometry, fall inside a cell rather than on its edge.
  // Cycles compares |cell| % 2 per axis; the parity of |i| is that of i (no abs(INT_MIN)).
  uint32_t odd[3];
  for (int i = 0; i < 3; ++i) {
    const float v = (p_in[i] + 0.000001f) * 0.999999f;
    odd[i] = static_cast<uint32_t>(floor_to_int(v)) & 1u;
  }
  const bool xy_same = odd[0] == odd[1];
  return (static_cast<uint32_t>(xy_same) == odd[2]) ? 1.0f : 0.0f;
}

float gradient_texture(const Vec3& p, GradientType type) {
  const float x = p.x, y = p.y, z = p.z;
  switch (type) {
    case GradientType::kLinear:
      return x;
    case GradientType::kQuadratic: {
      const float r = std::max(x, 0.0f);
      return r * r;
    }
    case GradientType::kEasing: {
      const float r = std::min(std::max(x, 0.0f), 1.0f);
      const float t = r * r;
      return 3.0f * t - 2.0f * t * r;
    }
    case GradientType::kDiagonal:
      return (x + y) * 0.5f;
    case GradientType::kRadial:
      return std::atan2(y, x) / (2.0f * kPi) + 0.5f;
    case GradientType::kQuadraticSphere:
    case GradientType::kSpherical: {
      // 0.999999 rather than 1: a unit-length point gives exactly 0, not rounding noise.
      const float r = std::max(0.999999f - std::sqrt(x * x + y * y + z * z), 0.0f);
      return type == GradientType::kSpherical ? r : r * r;
    }
  }
  return 0.0f;
}

Vec2 brick_texture(const Vec3& p, float mortar_size, float mortar_smooth, float bias,
                   float brick_width, float row_height, float offset_amount, int offset_frequency,
                   float squash_amount, int squash_frequency) {
  const int row = floor_to_int(p.y / row_height);
  float offset = 0.0f;
  // Every squash_frequency-th row is squashed and every offset_frequency-th row shifted; a zero
  // frequency disables both (as in Cycles).
  if (offset_frequency != 0 && squash_frequency != 0) {
    if (row % squash_frequency == 0) brick_width *= squash_amount;
    if (row % offset_frequency == 0) offset = brick_width * offset_amount;
  }
  const int brick = floor_to_int((p.x + offset) / brick_width);
  const float x = (p.x + offset) - brick_width * static_cast<float>(brick);
  const float y = p.y - row_height * static_cast<float>(row);

  const uint32_t seed =
      (static_cast<uint32_t>(row) << 16) + (static_cast<uint32_t>(brick) & 0xffffu);
  const float tint = saturate(brick_noise(seed) + bias);
  float min_dist = std::min(std::min(x, y), std::min(brick_width - x, row_height - y));

  float mortar;
  if (min_dist >= mortar_size) {
    mortar = 0.0f;
  } else if (mortar_smooth == 0.0f) {
    mortar = 1.0f;
  } else {
    min_dist = 1.0f - min_dist / mortar_size;
    mortar = (min_dist < mortar_smooth) ? smoothstep_unit(min_dist / mortar_smooth) : 1.0f;
  }
  return Vec2(tint, mortar);
}

Vec3 magic_texture(const Vec3& p, int n, float distortion) {
  // Blender's Magic texture: sines and cosines of sums of the coordinates, fed back into each
  // other once per depth level.
  float x = std::sin((p.x + p.y + p.z) * 5.0f);
  float y = std::cos((-p.x + p.y - p.z) * 5.0f);
  float z = -std::cos((-p.x - p.y + p.z) * 5.0f);
  if (n > 0) {
    x *= distortion;
    y *= distortion;
    z *= distortion;
    y = -std::cos(x - y + z) * distortion;
    if (n > 1) x = std::cos(x - y - z) * distortion;
    if (n > 2) z = std::sin(-x - y - z) * distortion;
    if (n > 3) x = -std::cos(-x + y - z) * distortion;
    if (n > 4) y = -std::sin(-x + y + z) * distortion;
    if (n > 5) y = -std::cos(-x + y + z) * distortion;
    if (n > 6) x = std::cos(x + y + z) * distortion;
    if (n > 7) z = std::sin(x + y - z) * distortion;
    if (n > 8) x = -std::cos(-x - y + z) * distortion;
    if (n > 9) y = -std::sin(x - y + z) * distortion;
  }
  if (distortion != 0.0f) {
    const float d = distortion * 2.0f;
    x /= d;
    y /= d;
    z /= d;
  }
  return Vec3(0.5f - x, 0.5f - y, 0.5f - z);
}

CompileStatus compile_pattern_node(const NodeDesc& desc, ShaderProgram* program, Instruction* out,
                                   std::string* error) {
  Instruction ins;
  ins.family = NodeFamily::kPattern;
  ins.in[0] = input_register(desc, "Vector");  // -1: Generated coordinates (see eval)
  ins.out[0] = output_register(desc, "Color");
  ins.out[1] = output_register(desc, "Fac");
  std::string name;
  if (desc.type == "ShaderNodeTexChecker") {
    name = "Checker Texture";
    ins.kind = static_cast<uint16_t>(PatternKind::kChecker);
    ins.in[1] = input_or_default(desc, "Color1", program, 0.8f, 3, 0.8f, 0.8f);
    ins.in[2] = input_or_default(desc, "Color2", program, 0.2f, 3, 0.2f, 0.2f);
    ins.in[3] = input_or_default(desc, "Scale", program, 5.0f);
  } else if (desc.type == "ShaderNodeTexGradient") {
    name = "Gradient Texture";
    ins.kind = static_cast<uint16_t>(PatternKind::kGradient);
    static const std::pair<const char*, GradientType> kTypes[] = {
        {"LINEAR", GradientType::kLinear},
        {"QUADRATIC", GradientType::kQuadratic},
        {"EASING", GradientType::kEasing},
        {"DIAGONAL", GradientType::kDiagonal},
        {"RADIAL", GradientType::kRadial},
        {"QUADRATIC_SPHERE", GradientType::kQuadraticSphere},
        {"SPHERICAL", GradientType::kSpherical},
    };
    const std::string type = enum_value(desc, "gradient_type", "LINEAR");
    bool found = false;
    for (const auto& [key, value] : kTypes)
      if (type == key) ins.mode = static_cast<uint32_t>(value), found = true;
    if (!found) {
      *error = "Gradient Texture: unknown gradient type '" + type + "'";
      return CompileStatus::kError;
    }
  } else if (desc.type == "ShaderNodeTexBrick") {
    name = "Brick Texture";
    ins.kind = static_cast<uint16_t>(PatternKind::kBrick);
    ins.in[1] = input_or_default(desc, "Color1", program, 0.8f, 3, 0.8f, 0.8f);
    ins.in[2] = input_or_default(desc, "Color2", program, 0.2f, 3, 0.2f, 0.2f);
    ins.in[3] = input_or_default(desc, "Mortar", program, 0.0f, 3);
    ins.in[4] = input_or_default(desc, "Scale", program, 5.0f);
    ins.in[5] = input_or_default(desc, "Mortar Size", program, 0.02f);
    ins.in[6] = input_or_default(desc, "Mortar Smooth", program, 0.1f);
    ins.in[7] = input_or_default(desc, "Bias", program, 0.0f);
    // Brick has ten inputs and an instruction eight slots: the last two registers go in data.
    const int32_t width = input_or_default(desc, "Brick Width", program, 0.5f);
    const int32_t height = input_or_default(desc, "Row Height", program, 0.25f);
    ins.data = static_cast<int32_t>(program->data.size());
    ins.data_size = 2;
    program->data.push_back(static_cast<float>(width));
    program->data.push_back(static_cast<float>(height));
    // Blender's ranges: offset [0, 1], squash [0, 99], both frequencies [1, 99].
    const auto property = [&](const char* key, double fallback, double lo, double hi) {
      const double v = number_value(desc, key, fallback);
      return std::isfinite(v) ? std::clamp(v, lo, hi) : fallback;
    };
    ins.param[0] = static_cast<float>(property("offset", 0.5, 0.0, 1.0));
    ins.param[1] = static_cast<float>(property("squash", 1.0, 0.0, 99.0));
    ins.mode = static_cast<uint32_t>(property("offset_frequency", 2.0, 1.0, 99.0)) |
               (static_cast<uint32_t>(property("squash_frequency", 2.0, 1.0, 99.0)) << 16);
  } else if (desc.type == "ShaderNodeTexMagic") {
    name = "Magic Texture";
    ins.kind = static_cast<uint16_t>(PatternKind::kMagic);
    ins.in[1] = input_or_default(desc, "Scale", program, 5.0f);
    ins.in[2] = input_or_default(desc, "Distortion", program, 1.0f);
    const double depth = number_value(desc, "turbulence_depth", 2.0);
    ins.mode = static_cast<uint32_t>(std::isfinite(depth) ? std::clamp(depth, 0.0, 10.0) : 2.0);
    // SKYCOMPILE
  } else if (desc.type == "ShaderNodeTexSky") {
    name = "Sky Texture";
    ins.kind = static_cast<uint16_t>(PatternKind::kSky);
    ins.out[1] = -1;
    const CompileStatus status = compile_sky_node(desc, program, &ins, error);
    if (status != CompileStatus::kCompiled) return status;
  } else {
    return CompileStatus::kUnknownNode;
  }
  if (!registers_fit(ins, *program, error, name)) return CompileStatus::kError;
  if (ins.kind == static_cast<uint16_t>(PatternKind::kBrick)) {  // extra input registers
    const ShaderProgram& p = *program;
    for (int i = 0; i < ins.data_size; ++i)
      if (p.data[ins.data + i] >= static_cast<float>(p.registers.size()))
        return *error = name + ": an input names a register past the program's end",
               CompileStatus::kError;
  }
  *out = ins;
  return CompileStatus::kCompiled;
}

void eval_pattern_node(const Instruction& ins, const ShaderProgram& program,
                       const ShaderGlobals& globals, float* r) {
  const auto kind = static_cast<PatternKind>(ins.kind);
  // SKYEVAL
  if (kind == PatternKind::kSky) {
    // Unlinked, the sky looks along the ray: a world shader's incoming points back along it.
    const Vec3 dir = ins.in[0] >= 0 ? load3(r, ins.in[0]) : -globals.incoming;
    store3(r, ins.out[0], eval_sky(ins, program, dir));
    return;
  }
  const Vec3 co = ins.in[0] >= 0 ? load3(r, ins.in[0]) : globals.generated;
  switch (kind) {
    case PatternKind::kChecker: {
      const float f = checker_texture(co * load1(r, ins.in[3]));
      store3(r, ins.out[0], f == 1.0f ? load3(r, ins.in[1]) : load3(r, ins.in[2]));
      store1(r, ins.out[1], f);
      break;
    }
    case PatternKind::kGradient: {
      const float f = saturate(gradient_texture(co, static_cast<GradientType>(ins.mode)));
      store3(r, ins.out[0], Vec3(f));
      store1(r, ins.out[1], f);
      break;
    }
    case PatternKind::kBrick: {
      const float* regs = program.data.data() + ins.data;
      const float width = load1(r, static_cast<int32_t>(regs[0]));
      const float height = load1(r, static_cast<int32_t>(regs[1]));
      const Vec2 tm = brick_texture(co * load1(r, ins.in[4]), load1(r, ins.in[5]),
                                    load1(r, ins.in[6]), load1(r, ins.in[7]), width, height,
                                    ins.param[0], static_cast<int>(ins.mode & 0xffffu),
                                    ins.param[1], static_cast<int>(ins.mode >> 16));
      const float tint = tm.x, mortar_fac = tm.y;
      Vec3 color = load3(r, ins.in[1]);
      if (mortar_fac != 1.0f) color = color * (1.0f - tint) + load3(r, ins.in[2]) * tint;
      store3(r, ins.out[0], color * (1.0f - mortar_fac) + load3(r, ins.in[3]) * mortar_fac);
      store1(r, ins.out[1], mortar_fac);
      break;
    }
    case PatternKind::kMagic: {
      const Vec3 c =
          magic_texture(co * load1(r, ins.in[1]), static_cast<int>(ins.mode), load1(r, ins.in[2]));
      store3(r, ins.out[0], c);
      store1(r, ins.out[1], (c.x + c.y + c.z) * (1.0f / 3.0f));
      break;
    }
    case PatternKind::kSky:
      break;
  }
}

}  // namespace photon
