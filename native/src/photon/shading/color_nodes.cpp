#include "photon/shading/color_nodes.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>

#include "photon/shading/color_math.h"

namespace photon {
namespace {

float saturate(float v) {
  return v > 0.0f ? std::min(v, 1.0f) : 0.0f;
}
Vec3 saturate3(const Vec3& v) {
  return {saturate(v.x), saturate(v.y), saturate(v.z)};
}
Vec3 max0(const Vec3& v) {
  return {std::max(v.x, 0.0f), std::max(v.y, 0.0f), std::max(v.z, 0.0f)};
}

// The register of an input; an input the add-on did not send reads a constant holding the
// socket's Blender default, appended to the register file.
int32_t input(const NodeDesc& desc, ShaderProgram* program, const char* identifier,
              std::initializer_list<float> fallback) {
  const int32_t reg = input_register(desc, identifier);
  if (reg >= 0) return reg;
  const auto first = static_cast<int32_t>(program->registers.size());
  program->registers.insert(program->registers.end(), fallback.begin(), fallback.end());
  return first;
}

bool flag(const NodeDesc& desc, const char* name, bool fallback) {
  return enum_value(desc, name, fallback ? "True" : "False") == "True";
}

bool parse_space(const std::string& name, uint32_t* mode) {
  if (name == "RGB")
    *mode = kSpaceRgb;
  else if (name == "HSV")
    *mode = kSpaceHsv;
  else if (name == "HSL")
    *mode = kSpaceHsl;
  else
    return false;
  return true;
}

CompileStatus compile_mix(const NodeDesc& desc, ShaderProgram* program, Instruction* ins,
                          std::string* error) {
  const std::string data_type = enum_value(desc, "data_type", "FLOAT");
  const bool clamp_factor = flag(desc, "clamp_factor", true);
  ins->mode = clamp_factor ? kMixClampFactor : 0u;
  if (data_type == "RGBA") {
    BlendMode blend;
    const std::string blend_name = enum_value(desc, "blend_type", "MIX");
    if (!parse_blend_mode(blend_name.c_str(), &blend)) {
      *error = "Mix node: unknown blend type '" + blend_name + "'";
      return CompileStatus::kError;
    }
    ins->kind = static_cast<uint16_t>(ColorNodeKind::kMixColor);
    ins->mode |= static_cast<uint32_t>(blend);
    if (flag(desc, "clamp_result", false)) ins->mode |= kMixClampResult;
    ins->in[0] = input(desc, program, "Factor_Float", {0.5f});
    ins->in[1] = input(desc, program, "A_Color", {0.5f, 0.5f, 0.5f});
    ins->in[2] = input(desc, program, "B_Color", {0.5f, 0.5f, 0.5f});
    ins->out[0] = output_register(desc, "Result_Color");
  } else if (data_type == "FLOAT") {
    ins->kind = static_cast<uint16_t>(ColorNodeKind::kMixFloat);
    ins->in[0] = input(desc, program, "Factor_Float", {0.5f});
    ins->in[1] = input(desc, program, "A_Float", {0.0f});
    ins->in[2] = input(desc, program, "B_Float", {0.0f});
    ins->out[0] = output_register(desc, "Result_Float");
  } else if (data_type == "VECTOR") {
    const std::string factor_mode = enum_value(desc, "factor_mode", "UNIFORM");
    if (factor_mode == "NON_UNIFORM") {
      ins->kind = static_cast<uint16_t>(ColorNodeKind::kMixVectorNonUniform);
      ins->in[0] = input(desc, program, "Factor_Vector", {0.5f, 0.5f, 0.5f});
    } else if (factor_mode == "UNIFORM") {
      ins->kind = static_cast<uint16_t>(ColorNodeKind::kMixVector);
      ins->in[0] = input(desc, program, "Factor_Float", {0.5f});
    } else {
      *error = "Mix node: unknown factor mode '" + factor_mode + "'";
      return CompileStatus::kError;
    }
    ins->in[1] = input(desc, program, "A_Vector", {0.0f, 0.0f, 0.0f});
    ins->in[2] = input(desc, program, "B_Vector", {0.0f, 0.0f, 0.0f});
    ins->out[0] = output_register(desc, "Result_Vector");
  } else {
    *error = "Mix node: data type '" + data_type + "' is not a shader type (FLOAT, VECTOR, RGBA)";
    return CompileStatus::kError;
  }
  return CompileStatus::kCompiled;
}

CompileStatus compile_mix_rgb(const NodeDesc& desc, ShaderProgram* program, Instruction* ins,
                              std::string* error) {
  BlendMode blend;
  const std::string blend_name = enum_value(desc, "blend_type", "MIX");
  if (!parse_blend_mode(blend_name.c_str(), &blend)) {
    *error = "MixRGB node: unknown blend type '" + blend_name + "'";
    return CompileStatus::kError;
  }
  // The legacy node always clamps its factor (Cycles' svm_mix_clamped_factor).
  ins->kind = static_cast<uint16_t>(ColorNodeKind::kMixColor);
  ins->mode = static_cast<uint32_t>(blend) | kMixClampFactor;
  if (flag(desc, "use_clamp", false)) ins->mode |= kMixClampResult;
  ins->in[0] = input(desc, program, "Fac", {0.5f});
  ins->in[1] = input(desc, program, "Color1", {0.5f, 0.5f, 0.5f});
  ins->in[2] = input(desc, program, "Color2", {0.5f, 0.5f, 0.5f});
  ins->out[0] = output_register(desc, "Color");
  return CompileStatus::kCompiled;
}

// Separate/Combine nodes: one colour/vector socket and three float sockets.
struct SplitNode {
  const char* type;
  bool combine;
  const char* vector;
  const char* parts[3];
  float vector_default;
};
constexpr SplitNode kSplitNodes[] = {
    {"ShaderNodeSeparateRGB", false, "Image", {"R", "G", "B"}, 0.8f},
    {"ShaderNodeCombineRGB", true, "Image", {"R", "G", "B"}, 0.0f},
    {"ShaderNodeSeparateXYZ", false, "Vector", {"X", "Y", "Z"}, 0.0f},
    {"ShaderNodeCombineXYZ", true, "Vector", {"X", "Y", "Z"}, 0.0f},
    {"ShaderNodeSeparateHSV", false, "Color", {"H", "S", "V"}, 0.8f},
    {"ShaderNodeCombineHSV", true, "Color", {"H", "S", "V"}, 0.0f},
    {"ShaderNodeSeparateColor", false, "Color", {"Red", "Green", "Blue"}, 0.8f},
    {"ShaderNodeCombineColor", true, "Color", {"Red", "Green", "Blue"}, 0.0f},
};

CompileStatus compile_split(const SplitNode& node, const NodeDesc& desc, ShaderProgram* program,
                            Instruction* ins, std::string* error) {
  uint32_t space = kSpaceRgb;
  const std::string type = node.type;
  if (type == "ShaderNodeSeparateHSV" || type == "ShaderNodeCombineHSV") {
    space = kSpaceHsv;
  } else if (type == "ShaderNodeSeparateColor" || type == "ShaderNodeCombineColor") {
    const std::string mode = enum_value(desc, "mode", "RGB");
    if (!parse_space(mode, &space)) {
      *error = type.substr(10) + " node: unknown mode '" + mode + "'";
      return CompileStatus::kError;
    }
  }
  ins->mode = space;
  if (node.combine) {
    ins->kind = static_cast<uint16_t>(ColorNodeKind::kCombine);
    for (int i = 0; i < 3; ++i) ins->in[i] = input(desc, program, node.parts[i], {0.0f});
    ins->out[0] = output_register(desc, node.vector);
  } else {
    ins->kind = static_cast<uint16_t>(ColorNodeKind::kSeparate);
    const float d = node.vector_default;
    ins->in[0] = input(desc, program, node.vector, {d, d, d});
    for (int i = 0; i < 3; ++i) ins->out[i] = output_register(desc, node.parts[i]);
  }
  return CompileStatus::kCompiled;
}

// Ramp and curve tables (layouts in addon/photon/sync/node_tables.py).
CompileStatus compile_table_node(const NodeDesc& desc, ShaderProgram* program, Instruction* ins,
                                 std::string* error) {
  const std::vector<float>& table = desc.table;
  const bool ramp = desc.type == "ShaderNodeValToRGB";
  const int header = ramp ? 1 : 3;
  const int stride = ramp ? 4 : (desc.type == "ShaderNodeFloatCurve" ? 1 : 3);
  const int samples = static_cast<int>(table.size()) - header;
  if (samples < 2 * stride || samples % stride != 0) {
    *error = desc.type.substr(10) + " node: its " + (ramp ? "colour ramp" : "curve mapping") +
             " table is missing or malformed (" + std::to_string(table.size()) + " values)";
    return CompileStatus::kError;
  }
  for (float v : table) {
    if (!std::isfinite(v)) {
      *error = desc.type.substr(10) + " node: its table holds a non-finite value";
      return CompileStatus::kError;
    }
  }
  ins->data = static_cast<int32_t>(program->data.size());
  ins->data_size = samples;
  program->data.insert(program->data.end(), table.begin() + header, table.end());
  if (ramp) {
    ins->kind = static_cast<uint16_t>(ColorNodeKind::kColorRamp);
    ins->mode = table[0] != 0.0f ? 1u : 0u;
    ins->in[0] = input(desc, program, "Fac", {0.5f});
    ins->out[0] = output_register(desc, "Color");
    ins->out[1] = output_register(desc, "Alpha");
    return CompileStatus::kCompiled;
  }
  ins->param[0] = table[0];  // min_x
  ins->param[1] = table[1];  // max_x
  ins->mode = table[2] != 0.0f ? 1u : 0u;
  if (desc.type == "ShaderNodeFloatCurve") {
    ins->kind = static_cast<uint16_t>(ColorNodeKind::kFloatCurve);
    ins->in[0] = input(desc, program, "Factor", {1.0f});
    ins->in[1] = input(desc, program, "Value", {1.0f});
    ins->out[0] = output_register(desc, "Value");
  } else {
    const bool rgb = desc.type == "ShaderNodeRGBCurve";
    const char* socket = rgb ? "Color" : "Vector";
    const float d = rgb ? 1.0f : 0.0f;
    ins->kind = static_cast<uint16_t>(ColorNodeKind::kVectorCurves);
    ins->in[0] = input(desc, program, "Fac", {1.0f});
    ins->in[1] = input(desc, program, socket, {d, d, d});
    ins->out[0] = output_register(desc, socket);
  }
  return CompileStatus::kCompiled;
}

Vec3 to_space(uint32_t space, const Vec3& rgb) {
  if (space == kSpaceHsv) return rgb_to_hsv(rgb);
  if (space == kSpaceHsl) return rgb_to_hsl(rgb);
  return rgb;
}

Vec3 from_space(uint32_t space, const Vec3& v) {
  if (space == kSpaceHsv) return hsv_to_rgb(v);
  if (space == kSpaceHsl) return hsl_to_rgb(v);
  return v;
}

// Hue/Saturation/Value: hue shifted by Hue - 0.5 (wrapped), saturation scaled and clamped
// to [0, 1], value scaled; mixed with the input by Fac; negative results clamped to 0.
Vec3 hue_sat_val(const Vec3& color, float hue, float sat, float val, float fac) {
  Vec3 hsv = rgb_to_hsv(color);
  const float h = hsv.x + hue + 0.5f;
  hsv.x = h - std::floor(h);
  hsv.y = saturate(hsv.y * sat);
  hsv.z *= val;
  const Vec3 rgb = hsv_to_rgb(hsv);
  return max0(rgb * fac + color * (1.0f - fac));
}

Vec3 gamma(const Vec3& color, float g) {
  if (g == 0.0f) return Vec3(1.0f);
  Vec3 c = color;
  for (int i = 0; i < 3; ++i) {
    if (c[i] > 0.0f) c[i] = std::pow(c[i], g);
  }
  return c;
}

}  // namespace

CompileStatus compile_color_node(const NodeDesc& desc, ShaderProgram* program, Instruction* out,
                                 std::string* error) {
  Instruction ins;
  ins.family = NodeFamily::kColor;
  CompileStatus status = CompileStatus::kCompiled;
  const std::string& type = desc.type;
  auto set = [&ins](ColorNodeKind kind) { ins.kind = static_cast<uint16_t>(kind); };
  if (type == "ShaderNodeMix") {
    status = compile_mix(desc, program, &ins, error);
  } else if (type == "ShaderNodeMixRGB") {
    status = compile_mix_rgb(desc, program, &ins, error);
  } else if (type == "ShaderNodeHueSaturation") {
    set(ColorNodeKind::kHueSatVal);
    ins.in[0] = input(desc, program, "Hue", {0.5f});
    ins.in[1] = input(desc, program, "Saturation", {1.0f});
    ins.in[2] = input(desc, program, "Value", {1.0f});
    ins.in[3] = input(desc, program, "Fac", {1.0f});
    ins.in[4] = input(desc, program, "Color", {0.8f, 0.8f, 0.8f});
    ins.out[0] = output_register(desc, "Color");
  } else if (type == "ShaderNodeInvert") {
    set(ColorNodeKind::kInvert);
    ins.in[0] = input(desc, program, "Fac", {1.0f});
    ins.in[1] = input(desc, program, "Color", {0.0f, 0.0f, 0.0f});
    ins.out[0] = output_register(desc, "Color");
  } else if (type == "ShaderNodeGamma") {
    set(ColorNodeKind::kGamma);
    ins.in[0] = input(desc, program, "Color", {1.0f, 1.0f, 1.0f});
    ins.in[1] = input(desc, program, "Gamma", {1.0f});
    ins.out[0] = output_register(desc, "Color");
  } else if (type == "ShaderNodeBrightContrast") {
    set(ColorNodeKind::kBrightContrast);
    ins.in[0] = input(desc, program, "Color", {1.0f, 1.0f, 1.0f});
    ins.in[1] = input(desc, program, "Bright", {0.0f});
    ins.in[2] = input(desc, program, "Contrast", {0.0f});
    ins.out[0] = output_register(desc, "Color");
  } else if (type == "ShaderNodeRGBToBW") {
    set(ColorNodeKind::kRgbToBw);
    ins.in[0] = input(desc, program, "Color", {0.5f, 0.5f, 0.5f});
    ins.out[0] = output_register(desc, "Val");
  } else if (type == "ShaderNodeBlackbody") {
    set(ColorNodeKind::kBlackbody);
    ins.in[0] = input(desc, program, "Temperature", {1500.0f});
    ins.out[0] = output_register(desc, "Color");
  } else if (type == "ShaderNodeWavelength") {
    set(ColorNodeKind::kWavelength);
    ins.in[0] = input(desc, program, "Wavelength", {500.0f});
    ins.out[0] = output_register(desc, "Color");
  } else if (type == "ShaderNodeValToRGB" || type == "ShaderNodeRGBCurve" ||
             type == "ShaderNodeVectorCurve" || type == "ShaderNodeFloatCurve") {
    status = compile_table_node(desc, program, &ins, error);
  } else {
    const SplitNode* split = nullptr;
    for (const SplitNode& node : kSplitNodes) {
      if (type == node.type) split = &node;
    }
    if (split == nullptr) return CompileStatus::kUnknownNode;
    status = compile_split(*split, desc, program, &ins, error);
  }
  if (status == CompileStatus::kCompiled) *out = ins;
  return status;
}

void eval_color_node(const Instruction& ins, const ShaderProgram& program,
                     const ShaderGlobals& /*globals*/, float* r) {
  switch (static_cast<ColorNodeKind>(ins.kind)) {
    case ColorNodeKind::kMixColor: {
      float t = load1(r, ins.in[0]);
      if (ins.mode & kMixClampFactor) t = saturate(t);
      const auto blend = static_cast<BlendMode>(ins.mode & kMixBlendMask);
      Vec3 c = blend_colors(blend, t, load3(r, ins.in[1]), load3(r, ins.in[2]));
      if (ins.mode & kMixClampResult) c = saturate3(c);
      store3(r, ins.out[0], c);
      break;
    }
    case ColorNodeKind::kMixFloat: {
      float t = load1(r, ins.in[0]);
      if (ins.mode & kMixClampFactor) t = saturate(t);
      store1(r, ins.out[0], load1(r, ins.in[1]) * (1.0f - t) + load1(r, ins.in[2]) * t);
      break;
    }
    case ColorNodeKind::kMixVector:
    case ColorNodeKind::kMixVectorNonUniform: {
      Vec3 t = static_cast<ColorNodeKind>(ins.kind) == ColorNodeKind::kMixVector
                   ? Vec3(load1(r, ins.in[0]))
                   : load3(r, ins.in[0]);
      if (ins.mode & kMixClampFactor) t = saturate3(t);
      store3(r, ins.out[0], load3(r, ins.in[1]) * (Vec3(1.0f) - t) + load3(r, ins.in[2]) * t);
      break;
    }
    case ColorNodeKind::kHueSatVal:
      store3(r, ins.out[0],
             hue_sat_val(load3(r, ins.in[4]), load1(r, ins.in[0]), load1(r, ins.in[1]),
                         load1(r, ins.in[2]), load1(r, ins.in[3])));
      break;
    case ColorNodeKind::kInvert: {
      const float fac = load1(r, ins.in[0]);
      const Vec3 c = load3(r, ins.in[1]);
      store3(r, ins.out[0], (Vec3(1.0f) - c) * fac + c * (1.0f - fac));
      break;
    }
    case ColorNodeKind::kGamma:
      store3(r, ins.out[0], gamma(load3(r, ins.in[0]), load1(r, ins.in[1])));
      break;
    case ColorNodeKind::kBrightContrast: {
      // Cycles' svm_brightness_contrast: slope 1 + contrast about 0.5, offset by brightness.
      const float bright = load1(r, ins.in[1]), contrast = load1(r, ins.in[2]);
      const float a = 1.0f + contrast;
      const float b = bright - contrast * 0.5f;
      store3(r, ins.out[0], max0(load3(r, ins.in[0]) * a + Vec3(b)));
      break;
    }
    case ColorNodeKind::kRgbToBw:
      store1(r, ins.out[0], rgb_to_gray(load3(r, ins.in[0])));
      break;
    case ColorNodeKind::kSeparate: {
      const Vec3 v = to_space(ins.mode, load3(r, ins.in[0]));
      for (int i = 0; i < 3; ++i) store1(r, ins.out[i], v[i]);
      break;
    }
    case ColorNodeKind::kCombine: {
      const Vec3 v(load1(r, ins.in[0]), load1(r, ins.in[1]), load1(r, ins.in[2]));
      store3(r, ins.out[0], from_space(ins.mode, v));
      break;
    }
    case ColorNodeKind::kBlackbody:
      // Scene linear is Rec.709 in Blender's default configuration.
      store3(r, ins.out[0], max0(blackbody_rec709(load1(r, ins.in[0]))));
      break;
    case ColorNodeKind::kWavelength:
      store3(r, ins.out[0], wavelength_to_rgb(load1(r, ins.in[0])));
      break;
    case ColorNodeKind::kColorRamp: {
      float rgba[4];
      ramp_lookup(program.data.data() + ins.data, ins.data_size / 4, 4, 4, load1(r, ins.in[0]),
                  ins.mode != 0, false, rgba);
      store3(r, ins.out[0], Vec3(rgba[0], rgba[1], rgba[2]));
      store1(r, ins.out[1], rgba[3]);
      break;
    }
    case ColorNodeKind::kVectorCurves: {
      // Each channel looks up its own curve at its position in the table's x range.
      const float fac = load1(r, ins.in[0]);
      const Vec3 c = load3(r, ins.in[1]);
      const float min_x = ins.param[0], range = ins.param[1] - ins.param[0];
      const float* table = program.data.data() + ins.data;
      const int size = ins.data_size / 3;
      Vec3 mapped;
      for (int i = 0; i < 3; ++i) {
        ramp_lookup(table + i, size, 3, 1, (c[i] - min_x) / range, true, ins.mode != 0, &mapped[i]);
      }
      store3(r, ins.out[0], c * (1.0f - fac) + mapped * fac);
      break;
    }
    case ColorNodeKind::kFloatCurve: {
      const float fac = load1(r, ins.in[0]);
      const float v = load1(r, ins.in[1]);
      const float rel = (v - ins.param[0]) / (ins.param[1] - ins.param[0]);
      float mapped;
      ramp_lookup(program.data.data() + ins.data, ins.data_size, 1, 1, rel, true, ins.mode != 0,
                  &mapped);
      store1(r, ins.out[0], (1.0f - fac) * v + fac * mapped);
      break;
    }
  }
}

}  // namespace photon
