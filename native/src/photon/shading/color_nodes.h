// The colour and converter node family (NodeFamily::kColor): Mix (3.4's ShaderNodeMix, float,
// vector and colour), MixRGB, Hue/Saturation/Value, Invert, Gamma, Bright/Contrast, RGB to BW,
// Separate/Combine RGB, XYZ, HSV and Color, Blackbody, Wavelength, ColorRamp, RGB/Vector/Float
// Curves, computed as Cycles 3.4's SVM computes them (maths in shading/color_math.*).
// Ramps and curves read the table addon/photon/sync/node_tables.py bakes (layouts there).
#pragma once

#include <string>

#include "photon/shading/program.h"

namespace photon {

// Instruction::kind of the colour family.
enum class ColorNodeKind : uint16_t {
  kMixColor,             // mode: BlendMode | kMixClampFactor | kMixClampResult
  kMixFloat,             // mode: kMixClampFactor
  kMixVector,            // mode: kMixClampFactor
  kMixVectorNonUniform,  // mode: kMixClampFactor
  kHueSatVal,
  kInvert,
  kGamma,
  kBrightContrast,
  kRgbToBw,
  kSeparate,  // mode: ColorSpaceMode of the outputs
  kCombine,   // mode: ColorSpaceMode of the inputs
  kBlackbody,
  kWavelength,
  kColorRamp,     // mode: 1 interpolate; data: size RGBA samples
  kVectorCurves,  // RGB and Vector Curves; mode: 1 extrapolate; param: min_x, max_x
  kFloatCurve,    // mode: 1 extrapolate; param: min_x, max_x
};

constexpr uint32_t kMixBlendMask = 0xffu;
constexpr uint32_t kMixClampFactor = 1u << 8;
constexpr uint32_t kMixClampResult = 1u << 9;

enum ColorSpaceMode : uint32_t { kSpaceRgb = 0, kSpaceHsv = 1, kSpaceHsl = 2 };

CompileStatus compile_color_node(const NodeDesc& desc, ShaderProgram* program, Instruction* out,
                                 std::string* error);

void eval_color_node(const Instruction& ins, const ShaderProgram& program,
                     const ShaderGlobals& globals, float* registers);

}  // namespace photon
