// Pure colour functions behind the colour nodes (shading/color_nodes.*), computed the way
// Cycles 3.4's SVM kernel computes them so procedural materials match Cycles to float
// rounding: HSV/HSL conversions, the 18 blend modes of Mix/MixRGB, the blackbody fit, the
// CIE 1931 wavelength table and the baked ramp/curve table lookups.
#pragma once

#include <cstdint>

#include "photon/base/math.h"

namespace photon {

// Blender's blend_type items, in Blender's enum order.
enum class BlendMode : uint32_t {
  kMix,
  kDarken,
  kMultiply,
  kBurn,
  kLighten,
  kScreen,
  kDodge,
  kAdd,
  kOverlay,
  kSoftLight,
  kLinearLight,
  kDifference,
  kSubtract,
  kDivide,
  kHue,
  kSaturation,
  kColor,
  kValue,
  kExclusion,  // Blender 4.x (after DIFFERENCE in its enum; here last, as modes match by name)
  kCount,
};

// BlendMode of a blend_type identifier ("SOFT_LIGHT"); false when unknown.
bool parse_blend_mode(const char* name, BlendMode* mode);

// Blends `b` over `a` with factor t (not clamped here; the nodes clamp it when asked).
Vec3 blend_colors(BlendMode mode, float t, const Vec3& a, const Vec3& b);

// Smith's hexcone model (h in [0, 1)); hsv_to_rgb wraps h = 1 to 0 and takes any other h
// outside [0, 1) to the last sextant, as Cycles does.
Vec3 rgb_to_hsv(const Vec3& rgb);
Vec3 hsv_to_rgb(const Vec3& hsv);
Vec3 rgb_to_hsl(const Vec3& rgb);
Vec3 hsl_to_rgb(const Vec3& hsl);

// Luminance weights of the scene-linear space (Rec.709 primaries, Blender's default OCIO
// config, luts/srgb_to_xyz.spimtx row Y): Cycles' rgb_to_y, used by RGB to BW.
constexpr Vec3 kRgbToY{0.2126729f, 0.7151522f, 0.0721750f};
float rgb_to_gray(const Vec3& rgb);

// CIE XYZ (D65) to scene-linear Rec.709: the inverse of srgb_to_xyz.spimtx.
Vec3 xyz_to_linear_rec709(const Vec3& xyz);

// Blackbody emitter colour in linear Rec.709 (Cycles' piecewise rational/cubic fit on
// 800 K..12000 K, constant outside), not yet clamped (the fit can go negative).
Vec3 blackbody_rec709(float kelvin);

// The Wavelength node: CIE 1931 colour matching at `nanometres` (5 nm table from 380 nm,
// linearly interpolated), to Rec.709, scaled by 1/2.52 and clamped at 0.
Vec3 wavelength_to_rgb(float nanometres);

// Lookup in a table of `size` samples of `stride` floats covering [0, 1] (Cycles'
// rgb_ramp_lookup): linear between samples when `interpolate`, beyond [0, 1] either clamped or
// extended along the end segments when `extrapolate`. Writes `channels` floats to `out`.
void ramp_lookup(const float* table, int size, int stride, int channels, float f, bool interpolate,
                 bool extrapolate, float* out);

}  // namespace photon
