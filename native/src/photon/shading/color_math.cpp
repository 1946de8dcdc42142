#include "photon/shading/color_math.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace photon {
namespace {

// The order of Blender's blend_type enum (rna_nodetree.c, ramp_blend_items).
constexpr const char* kBlendNames[] = {
    "MIX", "DARKEN",     "MULTIPLY",   "BURN",         "LIGHTEN",    "SCREEN",   "DODGE",
    "ADD", "OVERLAY",    "SOFT_LIGHT", "LINEAR_LIGHT", "DIFFERENCE", "SUBTRACT", "DIVIDE",
    "HUE", "SATURATION", "COLOR",      "VALUE",        "EXCLUSION"};
static_assert(sizeof(kBlendNames) / sizeof(kBlendNames[0]) ==
              static_cast<size_t>(BlendMode::kCount));

// Cycles' interp(a, b, t) = a + t (b - a).
Vec3 interp(const Vec3& a, const Vec3& b, float t) {
  return a + (b - a) * t;
}

Vec3 abs3(const Vec3& v) {
  return {std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)};
}
Vec3 min3(const Vec3& a, const Vec3& b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
Vec3 max3(const Vec3& a, const Vec3& b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}

// Overlay per channel: multiply below 0.5, screen above (Blender's ramp_blend).
float overlay(float t, float a, float b) {
  const float tm = 1.0f - t;
  if (a < 0.5f) return a * (tm + 2.0f * t * b);
  return 1.0f - (tm + 2.0f * t * (1.0f - b)) * (1.0f - a);
}

float divide(float t, float a, float b) {
  return b != 0.0f ? (1.0f - t) * a + t * a / b : a;
}

float dodge(float t, float a, float b) {
  if (a == 0.0f) return a;
  const float d = 1.0f - t * b;
  if (d <= 0.0f) return 1.0f;
  return std::min(a / d, 1.0f);
}

float burn(float t, float a, float b) {
  const float d = (1.0f - t) + t * b;
  if (d <= 0.0f) return 0.0f;
  return std::clamp(1.0f - (1.0f - a) / d, 0.0f, 1.0f);
}

Vec3 per_channel(float (*f)(float, float, float), float t, const Vec3& a, const Vec3& b) {
  return {f(t, a.x, b.x), f(t, a.y, b.y), f(t, a.z, b.z)};
}

// Hue, Saturation, Color and Value blend in HSV; a grey B leaves Hue and Color unchanged and
// a grey A leaves Saturation unchanged.
Vec3 blend_hue(float t, const Vec3& a, const Vec3& b) {
  const Vec3 hsv_b = rgb_to_hsv(b);
  if (hsv_b.y == 0.0f) return a;
  Vec3 hsv = rgb_to_hsv(a);
  hsv.x = hsv_b.x;
  return interp(a, hsv_to_rgb(hsv), t);
}

Vec3 blend_saturation(float t, const Vec3& a, const Vec3& b) {
  Vec3 hsv = rgb_to_hsv(a);
  if (hsv.y == 0.0f) return a;
  const Vec3 hsv_b = rgb_to_hsv(b);
  hsv.y = (1.0f - t) * hsv.y + t * hsv_b.y;
  return hsv_to_rgb(hsv);
}

Vec3 blend_value(float t, const Vec3& a, const Vec3& b) {
  Vec3 hsv = rgb_to_hsv(a);
  const Vec3 hsv_b = rgb_to_hsv(b);
  hsv.z = (1.0f - t) * hsv.z + t * hsv_b.z;
  return hsv_to_rgb(hsv);
}

Vec3 blend_color(float t, const Vec3& a, const Vec3& b) {
  const Vec3 hsv_b = rgb_to_hsv(b);
  if (hsv_b.y == 0.0f) return a;
  Vec3 hsv = rgb_to_hsv(a);
  hsv.x = hsv_b.x;
  hsv.y = hsv_b.y;
  return interp(a, hsv_to_rgb(hsv), t);
}

// CIE 1931 2-degree colour matching functions x, y, z from 380 nm to 780 nm in 5 nm steps,
// at the 4-digit precision Cycles tabulates them (kernel/tables.h).
constexpr float kCieColorMatch[81][3] = {
    {0.0014f, 0.0000f, 0.0065f}, {0.0022f, 0.0001f, 0.0105f}, {0.0042f, 0.0001f, 0.0201f},
    {0.0076f, 0.0002f, 0.0362f}, {0.0143f, 0.0004f, 0.0679f}, {0.0232f, 0.0006f, 0.1102f},
    {0.0435f, 0.0012f, 0.2074f}, {0.0776f, 0.0022f, 0.3713f}, {0.1344f, 0.0040f, 0.6456f},
    {0.2148f, 0.0073f, 1.0391f}, {0.2839f, 0.0116f, 1.3856f}, {0.3285f, 0.0168f, 1.6230f},
    {0.3483f, 0.0230f, 1.7471f}, {0.3481f, 0.0298f, 1.7826f}, {0.3362f, 0.0380f, 1.7721f},
    {0.3187f, 0.0480f, 1.7441f}, {0.2908f, 0.0600f, 1.6692f}, {0.2511f, 0.0739f, 1.5281f},
    {0.1954f, 0.0910f, 1.2876f}, {0.1421f, 0.1126f, 1.0419f}, {0.0956f, 0.1390f, 0.8130f},
    {0.0580f, 0.1693f, 0.6162f}, {0.0320f, 0.2080f, 0.4652f}, {0.0147f, 0.2586f, 0.3533f},
    {0.0049f, 0.3230f, 0.2720f}, {0.0024f, 0.4073f, 0.2123f}, {0.0093f, 0.5030f, 0.1582f},
    {0.0291f, 0.6082f, 0.1117f}, {0.0633f, 0.7100f, 0.0782f}, {0.1096f, 0.7932f, 0.0573f},
    {0.1655f, 0.8620f, 0.0422f}, {0.2257f, 0.9149f, 0.0298f}, {0.2904f, 0.9540f, 0.0203f},
    {0.3597f, 0.9803f, 0.0134f}, {0.4334f, 0.9950f, 0.0087f}, {0.5121f, 1.0000f, 0.0057f},
    {0.5945f, 0.9950f, 0.0039f}, {0.6784f, 0.9786f, 0.0027f}, {0.7621f, 0.9520f, 0.0021f},
    {0.8425f, 0.9154f, 0.0018f}, {0.9163f, 0.8700f, 0.0017f}, {0.9786f, 0.8163f, 0.0014f},
    {1.0263f, 0.7570f, 0.0011f}, {1.0567f, 0.6949f, 0.0010f}, {1.0622f, 0.6310f, 0.0008f},
    {1.0456f, 0.5668f, 0.0006f}, {1.0026f, 0.5030f, 0.0003f}, {0.9384f, 0.4412f, 0.0002f},
    {0.8544f, 0.3810f, 0.0002f}, {0.7514f, 0.3210f, 0.0001f}, {0.6424f, 0.2650f, 0.0000f},
    {0.5419f, 0.2170f, 0.0000f}, {0.4479f, 0.1750f, 0.0000f}, {0.3608f, 0.1382f, 0.0000f},
    {0.2835f, 0.1070f, 0.0000f}, {0.2187f, 0.0816f, 0.0000f}, {0.1649f, 0.0610f, 0.0000f},
    {0.1212f, 0.0446f, 0.0000f}, {0.0874f, 0.0320f, 0.0000f}, {0.0636f, 0.0232f, 0.0000f},
    {0.0468f, 0.0170f, 0.0000f}, {0.0329f, 0.0119f, 0.0000f}, {0.0227f, 0.0082f, 0.0000f},
    {0.0158f, 0.0057f, 0.0000f}, {0.0114f, 0.0041f, 0.0000f}, {0.0081f, 0.0029f, 0.0000f},
    {0.0058f, 0.0021f, 0.0000f}, {0.0041f, 0.0015f, 0.0000f}, {0.0029f, 0.0010f, 0.0000f},
    {0.0020f, 0.0007f, 0.0000f}, {0.0014f, 0.0005f, 0.0000f}, {0.0010f, 0.0004f, 0.0000f},
    {0.0007f, 0.0002f, 0.0000f}, {0.0005f, 0.0002f, 0.0000f}, {0.0003f, 0.0001f, 0.0000f},
    {0.0002f, 0.0001f, 0.0000f}, {0.0002f, 0.0001f, 0.0000f}, {0.0001f, 0.0000f, 0.0000f},
    {0.0001f, 0.0000f, 0.0000f}, {0.0001f, 0.0000f, 0.0000f}, {0.0000f, 0.0000f, 0.0000f}};

// Cycles' blackbody fit in linear Rec.709 (kernel/tables.h): on segment i, R and G are
// a/T + bT + c and B is ((aT + b)T + c)T + d. Segments start at 800 K and at kSegmentStart.
constexpr float kSegmentStart[6] = {965.0f, 1167.0f, 1449.0f, 1902.0f, 3315.0f, 6365.0f};
constexpr float kBlackbodyR[7][3] = {{1.61919106e+03f, -2.05010916e-03f, 5.02995757e+00f},
                                     {2.48845471e+03f, -1.11330907e-03f, 3.22621544e+00f},
                                     {3.34143193e+03f, -4.86551192e-04f, 1.76486769e+00f},
                                     {4.09461742e+03f, -1.27446582e-04f, 7.25731635e-01f},
                                     {4.67028036e+03f, 2.91258199e-05f, 1.26703442e-01f},
                                     {4.59509185e+03f, 2.87495649e-05f, 1.50345020e-01f},
                                     {3.78717450e+03f, 9.35907826e-06f, 3.99075871e-01f}};
constexpr float kBlackbodyG[7][3] = {{-4.88999748e+02f, 6.04330754e-04f, -7.55807526e-02f},
                                     {-7.55994277e+02f, 3.16730098e-04f, 4.78306139e-01f},
                                     {-1.02363977e+03f, 1.20223470e-04f, 9.36662319e-01f},
                                     {-1.26571316e+03f, 4.87340896e-06f, 1.27054498e+00f},
                                     {-1.42529332e+03f, -4.01150431e-05f, 1.43972784e+00f},
                                     {-1.17554822e+03f, -2.16378048e-05f, 1.30408023e+00f},
                                     {-5.00799571e+02f, -4.59832026e-06f, 1.09098763e+00f}};
constexpr float kBlackbodyB[7][4] = {
    {5.96945309e-11f, -4.85742887e-08f, -9.70622247e-05f, -4.07936148e-03f},
    {2.40430366e-11f, 5.55021075e-08f, -1.98503712e-04f, 2.89312858e-02f},
    {-1.40949732e-11f, 1.89878968e-07f, -3.56632824e-04f, 9.10767778e-02f},
    {-3.61460868e-11f, 2.84822009e-07f, -4.93211319e-04f, 1.56723440e-01f},
    {-1.97075738e-11f, 1.75359352e-07f, -2.50542825e-04f, -2.22783266e-02f},
    {-1.61997957e-13f, -1.64216008e-08f, 3.86216271e-04f, -7.38077418e-01f},
    {6.72650283e-13f, -2.73078809e-08f, 4.24098264e-04f, -7.52335691e-01f}};
// The colour at and above 12000 K, and below 800 K (where the emitter is too dim to matter
// and OSL stops), in linear Rec.709.
constexpr Vec3 kBlackbodyHot{0.8262954810464208f, 0.9945080501520986f, 1.566307710274283f};
constexpr Vec3 kBlackbodyCold{5.413294490189271f, -0.20319390035873933f, -0.0822535242887164f};

}  // namespace

bool parse_blend_mode(const char* name, BlendMode* mode) {
  for (uint32_t i = 0; i < static_cast<uint32_t>(BlendMode::kCount); ++i) {
    if (std::strcmp(name, kBlendNames[i]) == 0) {
      *mode = static_cast<BlendMode>(i);
      return true;
    }
  }
  return false;
}

Vec3 blend_colors(BlendMode mode, float t, const Vec3& a, const Vec3& b) {
  const Vec3 one(1.0f);
  switch (mode) {
    case BlendMode::kMix:
      return interp(a, b, t);
    case BlendMode::kDarken:
      return interp(a, min3(a, b), t);
    case BlendMode::kMultiply:
      return interp(a, a * b, t);
    case BlendMode::kBurn:
      return per_channel(burn, t, a, b);
    case BlendMode::kLighten:
      return interp(a, max3(a, b), t);
    case BlendMode::kScreen:
      return one - (Vec3(1.0f - t) + (one - b) * t) * (one - a);
    case BlendMode::kDodge:
      return per_channel(dodge, t, a, b);
    case BlendMode::kAdd:
      return interp(a, a + b, t);
    case BlendMode::kOverlay:
      return per_channel(overlay, t, a, b);
    case BlendMode::kSoftLight: {
      const Vec3 screen = one - (one - b) * (one - a);
      return a * (1.0f - t) + ((one - a) * b * a + a * screen) * t;
    }
    case BlendMode::kLinearLight:
      return a + (b * 2.0f - one) * t;
    case BlendMode::kDifference:
      return interp(a, abs3(a - b), t);
    case BlendMode::kExclusion:  // Cycles 4.x's svm_mix_exclusion
      return max3(interp(a, a + b - a * b * 2.0f, t), Vec3(0.0f));
    case BlendMode::kSubtract:
      return interp(a, a - b, t);
    case BlendMode::kDivide:
      return per_channel(divide, t, a, b);
    case BlendMode::kHue:
      return blend_hue(t, a, b);
    case BlendMode::kSaturation:
      return blend_saturation(t, a, b);
    case BlendMode::kColor:
      return blend_color(t, a, b);
    case BlendMode::kValue:
      return blend_value(t, a, b);
    case BlendMode::kCount:
      break;
  }
  return Vec3(0.0f);
}

Vec3 rgb_to_hsv(const Vec3& rgb) {
  const float cmax = std::max(rgb.x, std::max(rgb.y, rgb.z));
  const float cmin = std::min(rgb.x, std::min(rgb.y, rgb.z));
  const float delta = cmax - cmin;
  const float s = cmax != 0.0f ? delta / cmax : 0.0f;
  float h = 0.0f;
  if (s != 0.0f) {
    const Vec3 c = (Vec3(cmax) - rgb) / Vec3(delta);
    if (rgb.x == cmax) {
      h = c.z - c.y;
    } else if (rgb.y == cmax) {
      h = 2.0f + c.x - c.z;
    } else {
      h = 4.0f + c.y - c.x;
    }
    h /= 6.0f;
    if (h < 0.0f) h += 1.0f;
  }
  return {h, s, cmax};
}

Vec3 hsv_to_rgb(const Vec3& hsv) {
  float h = hsv.x;
  const float s = hsv.y, v = hsv.z;
  if (s == 0.0f) return Vec3(v);
  if (h == 1.0f) h = 0.0f;
  h *= 6.0f;
  const float sextant = std::floor(h);
  const float f = h - sextant;
  const float p = v * (1.0f - s);
  const float q = v * (1.0f - s * f);
  const float t = v * (1.0f - s * (1.0f - f));
  if (sextant == 0.0f) return {v, t, p};
  if (sextant == 1.0f) return {q, v, p};
  if (sextant == 2.0f) return {p, v, t};
  if (sextant == 3.0f) return {p, q, v};
  if (sextant == 4.0f) return {t, p, v};
  return {v, p, q};
}

Vec3 rgb_to_hsl(const Vec3& rgb) {
  const float cmax = std::max(rgb.x, std::max(rgb.y, rgb.z));
  const float cmin = std::min(rgb.x, std::min(rgb.y, rgb.z));
  const float l = std::min(1.0f, (cmax + cmin) / 2.0f);
  float h = 0.0f, s = 0.0f;
  if (cmax != cmin) {
    const float delta = cmax - cmin;
    s = l > 0.5f ? delta / (2.0f - cmax - cmin) : delta / (cmax + cmin);
    if (cmax == rgb.x) {
      h = (rgb.y - rgb.z) / delta + (rgb.y < rgb.z ? 6.0f : 0.0f);
    } else if (cmax == rgb.y) {
      h = (rgb.z - rgb.x) / delta + 2.0f;
    } else {
      h = (rgb.x - rgb.y) / delta + 4.0f;
    }
  }
  return {h / 6.0f, s, l};
}

Vec3 hsl_to_rgb(const Vec3& hsl) {
  const float h = hsl.x, s = hsl.y, l = hsl.z;
  const float r = std::clamp(std::fabs(h * 6.0f - 3.0f) - 1.0f, 0.0f, 1.0f);
  const float g = std::clamp(2.0f - std::fabs(h * 6.0f - 2.0f), 0.0f, 1.0f);
  const float b = std::clamp(2.0f - std::fabs(h * 6.0f - 4.0f), 0.0f, 1.0f);
  const float chroma = (1.0f - std::fabs(2.0f * l - 1.0f)) * s;
  return {(r - 0.5f) * chroma + l, (g - 0.5f) * chroma + l, (b - 0.5f) * chroma + l};
}

float rgb_to_gray(const Vec3& rgb) {
  return dot(rgb, kRgbToY);
}

Vec3 xyz_to_linear_rec709(const Vec3& xyz) {
  // Inverse of srgb_to_xyz.spimtx (computed in double precision, rounded to float).
  return {3.240454836f * xyz.x - 1.53713885f * xyz.y - 0.498531547f * xyz.z,
          -0.96926639f * xyz.x + 1.876010929f * xyz.y + 0.041556082f * xyz.z,
          0.05564342f * xyz.x - 0.204025854f * xyz.y + 1.057225162f * xyz.z};
}

Vec3 blackbody_rec709(float kelvin) {
  if (kelvin >= 12000.0f) return kBlackbodyHot;
  if (!(kelvin >= 800.0f)) return kBlackbodyCold;  // NaN too
  int i = 0;
  while (i < 6 && kelvin >= kSegmentStart[i]) ++i;
  const float* r = kBlackbodyR[i];
  const float* g = kBlackbodyG[i];
  const float* b = kBlackbodyB[i];
  const float inv = 1.0f / kelvin;
  return {r[0] * inv + r[1] * kelvin + r[2], g[0] * inv + g[1] * kelvin + g[2],
          ((b[0] * kelvin + b[1]) * kelvin + b[2]) * kelvin + b[3]};
}

Vec3 wavelength_to_rgb(float nanometres) {
  // Truncation toward zero, as Cycles' float_to_int: a wavelength up to 5 nm below 380 nm
  // extrapolates the first segment instead of going black.
  const float position = (nanometres - 380.0f) * (1.0f / 5.0f);
  Vec3 xyz(0.0f);
  if (position > -1.0f && position < 80.0f) {
    const int i = static_cast<int>(position);
    const float f = position - static_cast<float>(i);
    const Vec3 a(kCieColorMatch[i][0], kCieColorMatch[i][1], kCieColorMatch[i][2]);
    const Vec3 b(kCieColorMatch[i + 1][0], kCieColorMatch[i + 1][1], kCieColorMatch[i + 1][2]);
    xyz = interp(a, b, f);
  }
  // 1/2.52: Cycles' (OSL's) empirical scale that keeps every component <= 1.
  const Vec3 rgb = xyz_to_linear_rec709(xyz) * (1.0f / 2.52f);
  return max3(rgb, Vec3(0.0f));
}

void ramp_lookup(const float* table, int size, int stride, int channels, float f, bool interpolate,
                 bool extrapolate, float* out) {
  if (extrapolate && (f < 0.0f || f > 1.0f)) {
    // Continue the end segment's slope (Cycles' rgb_ramp_lookup extrapolation).
    const float* end = f < 0.0f ? table : table + (size - 1) * stride;
    const float* next = f < 0.0f ? table + stride : table + (size - 2) * stride;
    const float distance = (f < 0.0f ? -f : f - 1.0f) * static_cast<float>(size - 1);
    for (int c = 0; c < channels; ++c) out[c] = end[c] + (end[c] - next[c]) * distance;
    return;
  }
  const float x = (f > 0.0f ? std::min(f, 1.0f) : 0.0f) * static_cast<float>(size - 1);
  const int i = std::clamp(static_cast<int>(x), 0, size - 1);
  const float t = x - static_cast<float>(i);
  const float* a = table + i * stride;
  for (int c = 0; c < channels; ++c) out[c] = a[c];
  if (interpolate && t > 0.0f) {
    const float* b = a + stride;
    for (int c = 0; c < channels; ++c) out[c] = (1.0f - t) * a[c] + t * b[c];
  }
}

}  // namespace photon
