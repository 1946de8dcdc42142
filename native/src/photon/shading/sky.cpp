// Sky Texture models; see sky.h. The Nishita table reproduces Blender 3.4's intern/sky
// precomputation step by step in float (same quadratures, same operation order) so that Photon's
// sky matches Cycles' to float rounding.
#include "photon/shading/sky.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "photon/shading/sky_hosek_data.h"

namespace photon {
namespace {

constexpr float kHalfPi = 0.5f * kPi;
constexpr float kTwoPi = 2.0f * kPi;

// ---- CIE XYZ to scene-linear Rec.709, as Cycles 3.4 does with Blender 3.4's OCIO config ----
// The inverse of the config's srgb_to_xyz.spimtx (linear Rec.709 to D65 XYZ, IEC 61966-2-1),
// evaluated in double; rows give R, G, B. Cycles' renders of every sky case in
// test_scenes/nodes/pattern.json match it to 1e-4 (routing XYZ through the config's ACES2065-1
// interchange instead would give some 10% more blue).
constexpr float kXyzToRgb[3][3] = {
    {3.240454836f, -1.5371388501f, -0.4985315469f},
    {-0.9692663899f, 1.8760109288f, 0.0415560823f},
    {0.0556434196f, -0.2040258543f, 1.0572251625f},
};

Vec3 xyz_to_rgb_clamped(const Vec3& xyz) {  // negative channels (out of gamut) clamp to 0
  Vec3 rgb;
  for (int i = 0; i < 3; ++i)
    rgb[i] =
        std::max(kXyzToRgb[i][0] * xyz.x + kXyzToRgb[i][1] * xyz.y + kXyzToRgb[i][2] * xyz.z, 0.0f);
  return rgb;
}

// Cycles' spherical coordinates of a direction: theta from +Z, phi = atan2(x, y).
Vec2 direction_to_spherical(const Vec3& d) {
  return Vec2(std::acos(std::clamp(d.z, -1.0f, 1.0f)), std::atan2(d.x, d.y));
}

// Angle between two directions, accurate for small angles (the sun disc).
float precise_angle(const Vec3& a, const Vec3& b) {
  return 2.0f * std::atan2(length(a - b), length(a + b));
}

// ---- Nishita: Blender's constants (intern/sky/source/sky_nishita.cpp) ----
constexpr float kRayleighScale = 8e3f;  // Rayleigh scale height (m)
constexpr float kMieScale = 1.2e3f;     // Mie scale height (m)
constexpr float kMieCoeff = 2e-5f;      // Mie scattering coefficient (1/m)
constexpr float kMieG = 0.76f;          // aerosol anisotropy
constexpr float kMieG2 = kMieG * kMieG;
constexpr float kEarthRadius = 6360e3f;       // m
constexpr float kAtmosphereRadius = 6420e3f;  // m
constexpr int kSteps = 32;                    // segments of a view ray
constexpr int kWavelengths = 21;              // 380 nm to 780 nm in 20 nm steps
constexpr float kStepLambda = 20.0f;

// Sun spectral irradiance at the top of the atmosphere (W m^-2 nm^-1).
constexpr float kIrradiance[kWavelengths] = {
    1.45756829855592995315f, 1.56596305559738380175f, 1.65148449067670455293f,
    1.71496242737209314555f, 1.75797983805020541226f, 1.78256407885924539336f,
    1.79095108475838560302f, 1.78541550133410664714f, 1.76815554864306845317f,
    1.74122069647250410362f, 1.70647127164943679389f, 1.66556087452739887134f,
    1.61993437242451854274f, 1.57083597368892080581f, 1.51932335059305478886f,
    1.46628494965214395407f, 1.41245852740172450623f, 1.35844961970384092709f,
    1.30474913844739281998f, 1.25174963272610817455f, 1.19975998755420620867f};
// Rayleigh scattering coefficients at sea level (1/m).
constexpr float kRayleighCoeff[kWavelengths] = {
    0.00005424820087636473f, 0.00004418549866505454f, 0.00003635151910165377f,
    0.00003017929012024763f, 0.00002526320226989157f, 0.00002130859310621843f,
    0.00001809838025320633f, 0.00001547057129129042f, 0.00001330284977336850f,
    0.00001150184784075764f, 0.00000999557429990163f, 0.00000872799973630707f,
    0.00000765513700977967f, 0.00000674217203751443f, 0.00000596134125832052f,
    0.00000529034598065810f, 0.00000471115687557433f, 0.00000420910481110487f,
    0.00000377218381260133f, 0.00000339051255477280f, 0.00000305591531679811f};
// Ozone absorption coefficients (1/m).
constexpr float kOzoneCoeff[kWavelengths] = {
    0.00000000325126849861f, 0.00000000585395365047f, 0.00000001977191155085f,
    0.00000007309568762914f, 0.00000020084561514287f, 0.00000040383958096161f,
    0.00000063551335912363f, 0.00000096707041180970f, 0.00000154797400424410f,
    0.00000209038647223331f, 0.00000246128056164565f, 0.00000273551299461512f,
    0.00000215125863128643f, 0.00000159051840791988f, 0.00000112356197979857f,
    0.00000073527551487574f, 0.00000046450130357806f, 0.00000033096079921048f,
    0.00000022512612292678f, 0.00000014879129266490f, 0.00000016828623364192f};
// CIE 1931 colour matching functions at the same wavelengths.
constexpr float kCmf[kWavelengths][3] = {{0.00136800000f, 0.00003900000f, 0.00645000100f},
                                         {0.01431000000f, 0.00039600000f, 0.06785001000f},
                                         {0.13438000000f, 0.00400000000f, 0.64560000000f},
                                         {0.34828000000f, 0.02300000000f, 1.74706000000f},
                                         {0.29080000000f, 0.06000000000f, 1.66920000000f},
                                         {0.09564000000f, 0.13902000000f, 0.81295010000f},
                                         {0.00490000000f, 0.32300000000f, 0.27200000000f},
                                         {0.06327000000f, 0.71000000000f, 0.07824999000f},
                                         {0.29040000000f, 0.95400000000f, 0.02030000000f},
                                         {0.59450000000f, 0.99500000000f, 0.00390000000f},
                                         {0.91630000000f, 0.87000000000f, 0.00165000100f},
                                         {1.06220000000f, 0.63100000000f, 0.00080000000f},
                                         {0.85444990000f, 0.38100000000f, 0.00019000000f},
                                         {0.44790000000f, 0.17500000000f, 0.00002000000f},
                                         {0.16490000000f, 0.06100000000f, 0.00000000000f},
                                         {0.04677000000f, 0.01700000000f, 0.00000000000f},
                                         {0.01135916000f, 0.00410200000f, 0.00000000000f},
                                         {0.00289932700f, 0.00104700000f, 0.00000000000f},
                                         {0.00069007860f, 0.00024920000f, 0.00000000000f},
                                         {0.00016615050f, 0.00006000000f, 0.00000000000f},
                                         {0.00004150994f, 0.00001499000f, 0.00000000000f}};

// Optical depth towards the sun by 8-point Gauss-Laguerre quadrature (nodes and weights, with
// exp(x) folded into the weights, rescaled so the last node lies inside the atmosphere).
constexpr int kQuadratureSteps = 8;
constexpr float kQuadratureNodes[kQuadratureSteps] = {
    0.006811185292f, 0.03614807107f, 0.09004346519f, 0.1706680068f,
    0.2818362161f,   0.4303406404f,  0.6296271457f,  0.9145252695f};
constexpr float kQuadratureWeights[kQuadratureSteps] = {
    0.01750893642f, 0.04135477391f, 0.06678839063f, 0.09507698807f,
    0.1283416365f,  0.1707430204f,  0.2327233347f,  0.3562490486f};

// Plain float arithmetic in Blender's order (Vec3's dot sums x, y, z left to right).
float dot3(const Vec3& a, const Vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
float len3(const Vec3& a) {
  return std::sqrt(dot3(a, a));
}
float sum3(const Vec3& a) {
  return a.x + a.y + a.z;
}

Vec3 geographical_to_direction(float lat, float lon) {
  return Vec3(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
}

Vec3 spectrum_to_xyz(const float* spectrum) {
  Vec3 xyz(0.0f);
  for (int i = 0; i < kWavelengths; ++i) {
    xyz.x += kCmf[i][0] * spectrum[i];
    xyz.y += kCmf[i][1] * spectrum[i];
    xyz.z += kCmf[i][2] * spectrum[i];
  }
  return xyz * kStepLambda;
}

// Relative densities at a height above sea level (m): exponential Rayleigh and Mie layers, and
// ozone as a tent between 10 km and 40 km peaking at 25 km.
float density_rayleigh(float h) {
  return std::exp(-h / kRayleighScale);
}
float density_mie(float h) {
  return std::exp(-h / kMieScale);
}
float density_ozone(float h) {
  if (h >= 10000.0f && h < 25000.0f) return 1.0f / 15000.0f * h - 2.0f / 3.0f;
  if (h >= 25000.0f && h < 40000.0f) return -(1.0f / 15000.0f * h - 8.0f / 3.0f);
  return 0.0f;
}

float phase_rayleigh(float mu) {
  return 3.0f / (16.0f * kPi) * (1.0f + mu * mu);
}
// Cornette-Shanks phase function (Henyey-Greenstein made to fit Mie scattering).
float phase_mie(float mu) {
  return (3.0f * (1.0f - kMieG2) * (1.0f + mu * mu)) /
         (8.0f * kPi * (2.0f + kMieG2) * std::pow(1.0f + kMieG2 - 2.0f * kMieG * mu, 1.5f));
}

bool hits_ground(const Vec3& pos, const Vec3& dir) {
  if (dir.z >= 0.0f) return false;
  const float b = -2.0f * dot3(dir, -pos);
  const float c = dot3(pos, pos) - kEarthRadius * kEarthRadius;
  return b * b - 4.0f * c >= 0.0f;
}

Vec3 atmosphere_exit(const Vec3& pos, const Vec3& dir) {
  const float b = -2.0f * dot3(dir, -pos);
  const float c = dot3(pos, pos) - kAtmosphereRadius * kAtmosphereRadius;
  const float t = (-b + std::sqrt(b * b - 4.0f * c)) / 2.0f;
  return Vec3(pos.x + dir.x * t, pos.y + dir.y * t, pos.z + dir.z * t);
}

// (Rayleigh, Mie, ozone) optical depth factors from `origin` to the top of the atmosphere.
Vec3 ray_optical_depth(const Vec3& origin, const Vec3& dir) {
  const float ray_length = len3(origin - atmosphere_exit(origin, dir));
  const Vec3 segment = dir * ray_length;
  Vec3 depth(0.0f);
  for (int i = 0; i < kQuadratureSteps; ++i) {
    const Vec3 p = origin + segment * kQuadratureNodes[i];
    const float h = len3(p) - kEarthRadius;
    depth += Vec3(density_rayleigh(h), density_mie(h), density_ozone(h)) * kQuadratureWeights[i];
  }
  return depth * ray_length;
}

// Single in-scattered spectral radiance along a view ray (Nishita et al. 1993, eq. 3 with the
// sun's transmittance of eq. 4): midpoint rule over kSteps segments.
void single_scattering(const Vec3& dir, const Vec3& sun_dir, const Vec3& origin,
                       const Vec3& density_scale, float* spectrum) {
  const float ray_length = len3(origin - atmosphere_exit(origin, dir));
  const float segment_length = ray_length / kSteps;
  const Vec3 segment = dir * segment_length;
  Vec3 optical_depth(0.0f);
  std::fill(spectrum, spectrum + kWavelengths, 0.0f);
  const float mu = dot3(dir, sun_dir);
  const Vec3 phase(phase_rayleigh(mu), phase_mie(mu), 0.0f);
  Vec3 p = origin + segment * 0.5f;
  for (int i = 0; i < kSteps; ++i) {
    const float h = len3(p) - kEarthRadius;
    const Vec3 density =
        density_scale * Vec3(density_rayleigh(h), density_mie(h), density_ozone(h));
    optical_depth += density * segment_length;
    if (!hits_ground(p, sun_dir)) {
      const Vec3 total = optical_depth + density_scale * ray_optical_depth(p, sun_dir);
      for (int wl = 0; wl < kWavelengths; ++wl) {
        const Vec3 extinction =
            total * Vec3(kRayleighCoeff[wl], 1.11f * kMieCoeff, kOzoneCoeff[wl]);
        const float attenuation = std::exp(-sum3(extinction));
        const Vec3 scattering = density * Vec3(kRayleighCoeff[wl], kMieCoeff, 0.0f);
        spectrum[wl] += attenuation * sum3(phase * scattering) * kIrradiance[wl] * segment_length;
      }
    }
    p += segment;
  }
}

// Radiance of the sun disc seen along `dir`: irradiance through the atmosphere spread over the
// disc's solid angle.
Vec3 sun_radiance_xyz(const Vec3& dir, float altitude, float air, float dust, float solid_angle) {
  const Vec3 depth = ray_optical_depth(Vec3(0.0f, 0.0f, kEarthRadius + altitude), dir);
  float spectrum[kWavelengths];
  for (int i = 0; i < kWavelengths; ++i) {
    const float tau = kRayleighCoeff[i] * depth.x * air + 1.11f * kMieCoeff * depth.y * dust;
    spectrum[i] = kIrradiance[i] * std::exp(-tau) / solid_angle;
  }
  return spectrum_to_xyz(spectrum);
}

// Bilinear lookup with clamped edges (Cycles' linear interpolation, EXTEND).
Vec3 table_lookup(const float* table, float x, float y) {
  const float fx = x * kNishitaWidth - 0.5f, fy = y * kNishitaHeight - 0.5f;
  const float flx = std::floor(fx), fly = std::floor(fy);
  const float tx = fx - flx, ty = fy - fly;
  const int ix = static_cast<int>(flx), iy = static_cast<int>(fly);
  const int x0 = std::clamp(ix, 0, kNishitaWidth - 1),
            x1 = std::clamp(ix + 1, 0, kNishitaWidth - 1);
  const int y0 = std::clamp(iy, 0, kNishitaHeight - 1),
            y1 = std::clamp(iy + 1, 0, kNishitaHeight - 1);
  auto texel = [table](int px, int py) {
    const float* t = table + (static_cast<size_t>(py) * kNishitaWidth + px) * 3;
    return Vec3(t[0], t[1], t[2]);
  };
  return texel(x0, y0) * ((1.0f - ty) * (1.0f - tx)) + texel(x1, y0) * ((1.0f - ty) * tx) +
         texel(x0, y1) * (ty * (1.0f - tx)) + texel(x1, y1) * (ty * tx);
}

// ---- Nishita evaluation. data: bottom xyz, top xyz, elevation, rotation, diameter, intensity ----
constexpr int kNishitaHeader = 10;

Vec3 eval_nishita(const float* d, const Vec3& dir) {
  const Vec3 bottom(d[0], d[1], d[2]), top(d[3], d[4], d[5]);
  const float sun_elevation = d[6], sun_rotation = d[7], diameter = d[8], intensity = d[9];
  const float* table = d + kNishitaHeader;
  const Vec2 sph = direction_to_spherical(dir);
  Vec3 xyz(0.0f);
  // The table's x runs around the horizon starting opposite the sun.
  float x = (sph.y + kPi + sun_rotation) / kTwoPi;
  if (x > 1.0f) x -= 1.0f;
  if (dir.z >= 0.0f) {
    const Vec3 sun_dir = geographical_to_direction(sun_elevation, sun_rotation + kHalfPi);
    const float angle = precise_angle(dir, sun_dir);
    const float half = diameter / 2.0f;
    const float elevation = kHalfPi - sph.x;
    if (diameter >= 0.0f && angle < half) {
      // Across the disc, radiance goes from its bottom edge's to its top edge's (the bottom
      // edge clamped to the horizon when the sun is setting).
      if (sun_elevation - half > 0.0f) {
        const float y = (elevation - sun_elevation) / diameter + 0.5f;
        xyz = (bottom + (top - bottom) * y) * intensity;
      } else if (sun_elevation + half > 0.0f) {
        const float y = elevation / (sun_elevation + half);
        xyz = (bottom + (top - bottom) * y) * intensity;
      }
      const float r = angle / half;  // limb darkening with coefficient 0.6
      xyz *= 1.0f - 0.6f * (1.0f - std::sqrt(1.0f - r * r));
    } else {
      // Rows were tabulated at latitude ~ (row / height)^2: undo that mapping.
      const float y = std::sqrt(std::max(elevation / kHalfPi, 0.0f));
      xyz = table_lookup(table, x, y);
    }
  } else if (dir.z >= -0.4f) {
    // Below the horizon the horizon row fades to black at dir.z = -0.4.
    float fade = 1.0f + dir.z * 2.5f;
    fade = fade * fade * fade;
    xyz = table_lookup(table, x, -0.5f) * fade;
  }
  return xyz_to_rgb_clamped(xyz);
}

// ---- Preetham. data: sun phi, sun theta, zenith (Y, x, y), Perez coefficients for Y, x, y ----
float perez(const float* lam, float theta, float gamma) {
  const float cg = std::cos(gamma);
  return (1.0f + lam[0] * std::exp(lam[1] / std::cos(theta))) *
         (1.0f + lam[2] * std::exp(lam[3] * gamma) + lam[4] * cg * cg);
}

Vec3 eval_preetham(const float* d, const Vec3& dir) {
  const float sun_phi = d[0], sun_theta = d[1];
  const Vec2 sph = direction_to_spherical(dir);
  float theta = sph.x;
  const float phi = sph.y;
  const float cos_gamma = std::sin(theta) * std::sin(sun_theta) * std::cos(sun_phi - phi) +
                          std::cos(theta) * std::cos(sun_theta);
  const float gamma = std::acos(std::clamp(cos_gamma, -1.0f, 1.0f));
  theta = std::min(theta, kHalfPi - 0.001f);  // below the horizon, repeat the horizon
  const float cx = d[3] * perez(d + 5 + 5, theta, gamma);
  const float cy = d[4] * perez(d + 5 + 10, theta, gamma);
  const float lum = d[2] * perez(d + 5, theta, gamma);
  // CIE xyY to XYZ.
  const float big_x = cy != 0.0f ? (cx / cy) * lum : 0.0f;
  const float big_z = (cy != 0.0f && lum != 0.0f) ? (1.0f - cx - cy) / cy * lum : 0.0f;
  return xyz_to_rgb_clamped(Vec3(big_x, lum, big_z));
}

void precompute_preetham(const Vec3& sun, float turbidity, float* d) {
  const float theta = std::acos(std::clamp(sun.z, -1.0f, 1.0f));
  const float phi = std::atan2(sun.x, sun.y);
  const float t2 = theta * theta, t3 = t2 * theta;
  const float T = turbidity, T2 = T * T;
  d[0] = phi;
  d[1] = theta;
  // Zenith luminance (kcd/m^2, scaled by 0.06 as Cycles does) and chromaticity (Preetham
  // et al. 1999, A.2).
  const float chi = (4.0f / 9.0f - T / 120.0f) * (kPi - 2.0f * theta);
  d[2] = ((4.0453f * T - 4.9710f) * std::tan(chi) - 0.2155f * T + 2.4192f) * 0.06f;
  d[3] = (0.00166f * t3 - 0.00375f * t2 + 0.00209f * theta) * T2 +
         (-0.02903f * t3 + 0.06377f * t2 - 0.03202f * theta + 0.00394f) * T +
         (0.11693f * t3 - 0.21196f * t2 + 0.06052f * theta + 0.25886f);
  d[4] = (0.00275f * t3 - 0.00610f * t2 + 0.00317f * theta) * T2 +
         (-0.04214f * t3 + 0.08970f * t2 - 0.04153f * theta + 0.00516f) * T +
         (0.15346f * t3 - 0.26756f * t2 + 0.06670f * theta + 0.26688f);
  float* lum = d + 5;
  float* cx = d + 10;
  float* cy = d + 15;
  const float lum_coeffs[5] = {0.1787f * T - 1.4630f, -0.3554f * T + 0.4275f,
                               -0.0227f * T + 5.3251f, 0.1206f * T - 2.5771f,
                               -0.0670f * T + 0.3703f};
  const float x_coeffs[5] = {-0.0193f * T - 0.2592f, -0.0665f * T + 0.0008f, -0.0004f * T + 0.2125f,
                             -0.0641f * T - 0.8989f, -0.0033f * T + 0.0452f};
  const float y_coeffs[5] = {-0.0167f * T - 0.2608f, -0.0950f * T + 0.0092f, -0.0079f * T + 0.2102f,
                             -0.0441f * T - 1.6537f, -0.0109f * T + 0.0529f};
  std::copy(lum_coeffs, lum_coeffs + 5, lum);
  std::copy(x_coeffs, x_coeffs + 5, cx);
  std::copy(y_coeffs, y_coeffs + 5, cy);
  // Normalise so the zenith gets the zenith values: F(0, theta_sun).
  d[2] /= perez(lum, 0.0f, theta);
  d[3] /= perez(cx, 0.0f, theta);
  d[4] /= perez(cy, 0.0f, theta);
}
constexpr int kPreethamSize = 20;

// ---- Hosek-Wilkie (Hosek & Wilkie 2012, eq. 9) ----
// data: sun phi, sun theta, radiance X, Y, Z, then the nine parameters A..I for X, Y and Z.
constexpr int kHosekSize = 5 + 27;

float hosek_distribution(const float* c, float theta, float gamma) {
  const float cos_theta = std::cos(theta), cos_gamma = std::cos(gamma);
  const float exp_m = std::exp(c[4] * gamma);
  const float ray_m = cos_gamma * cos_gamma;
  const float mie_m = (1.0f + ray_m) / std::pow(1.0f + c[8] * c[8] - 2.0f * c[8] * cos_gamma, 1.5f);
  const float zenith = std::sqrt(cos_theta);
  return (1.0f + c[0] * std::exp(c[1] / (cos_theta + 0.01f))) *
         (c[2] + c[3] * exp_m + c[5] * ray_m + c[6] * mie_m + c[7] * zenith);
}

Vec3 eval_hosek(const float* d, const Vec3& dir) {
  const float sun_phi = d[0], sun_theta = d[1];
  const Vec2 sph = direction_to_spherical(dir);
  float theta = sph.x;
  const float cos_gamma = std::sin(theta) * std::sin(sun_theta) * std::cos(sun_phi - sph.y) +
                          std::cos(theta) * std::cos(sun_theta);
  const float gamma = std::acos(std::clamp(cos_gamma, -1.0f, 1.0f));
  theta = std::min(theta, kHalfPi - 0.001f);
  const Vec3 xyz(hosek_distribution(d + 5, theta, gamma) * d[2],
                 hosek_distribution(d + 14, theta, gamma) * d[3],
                 hosek_distribution(d + 23, theta, gamma) * d[4]);
  // The model's XYZ are radiometric (W m^-2 sr^-1 summed over the observer's curves); Cycles
  // scales them by 2 pi / 683.
  return xyz_to_rgb_clamped(xyz) * (kTwoPi / 683.0f);
}

// A quantity fitted over (albedo, turbidity, elevation): quintic Bezier in
// (elevation / (pi / 2))^(1/3) over the six control points of `stride`-spaced values, linear in
// turbidity between the tables of floor(T) and floor(T) + 1, linear in albedo (Hosek & Wilkie
// 2012, section 5).
double hosek_cook(const double* dataset, int stride, int index, double turbidity, double albedo,
                  double elevation) {
  const int t_int = static_cast<int>(turbidity);
  const double t_rem = turbidity - t_int;
  const double s = std::pow(elevation / (M_PI / 2.0), 1.0 / 3.0);
  auto bezier = [&](const double* m) {
    return std::pow(1.0 - s, 5.0) * m[index] +
           5.0 * std::pow(1.0 - s, 4.0) * s * m[index + stride] +
           10.0 * std::pow(1.0 - s, 3.0) * std::pow(s, 2.0) * m[index + 2 * stride] +
           10.0 * std::pow(1.0 - s, 2.0) * std::pow(s, 3.0) * m[index + 3 * stride] +
           5.0 * (1.0 - s) * std::pow(s, 4.0) * m[index + 4 * stride] +
           std::pow(s, 5.0) * m[index + 5 * stride];
  };
  const int block = 6 * stride;  // one (albedo, turbidity) table
  double v = (1.0 - albedo) * (1.0 - t_rem) * bezier(dataset + block * (t_int - 1));
  v += albedo * (1.0 - t_rem) * bezier(dataset + block * 10 + block * (t_int - 1));
  if (t_int == 10) return v;
  v += (1.0 - albedo) * t_rem * bezier(dataset + block * t_int);
  v += albedo * t_rem * bezier(dataset + block * 10 + block * t_int);
  return v;
}

void precompute_hosek(const Vec3& sun, float turbidity, float albedo, float* d) {
  float theta = std::acos(std::clamp(sun.z, -1.0f, 1.0f));
  const float phi = std::atan2(sun.x, sun.y);
  theta = std::clamp(theta, 0.0f, kHalfPi);  // the model is fitted for suns above the horizon
  d[0] = phi;
  d[1] = theta;
  const double elevation = static_cast<double>(kHalfPi - theta);
  const double* datasets[3] = {hosek::kDatasetX, hosek::kDatasetY, hosek::kDatasetZ};
  const double* radiances[3] = {hosek::kRadianceX, hosek::kRadianceY, hosek::kRadianceZ};
  for (int c = 0; c < 3; ++c) {
    for (int i = 0; i < 9; ++i)
      d[5 + 9 * c + i] =
          static_cast<float>(hosek_cook(datasets[c], 9, i, turbidity, albedo, elevation));
    d[2 + c] = static_cast<float>(hosek_cook(radiances[c], 1, 0, turbidity, albedo, elevation));
  }
}

float clamped_number(const NodeDesc& desc, const char* key, double fallback, double lo, double hi) {
  const double v = number_value(desc, key, fallback);
  return static_cast<float>(std::isfinite(v) ? std::clamp(v, lo, hi) : fallback);
}

}  // namespace

std::vector<float> nishita_sky_table(float sun_elevation, float altitude, float air_density,
                                     float dust_density, float ozone_density) {
  std::vector<float> table(static_cast<size_t>(kNishitaWidth) * kNishitaHeight * 3);
  const Vec3 origin(0.0f, 0.0f, kEarthRadius + altitude);
  const Vec3 sun_dir = geographical_to_direction(sun_elevation, 0.0f);
  const Vec3 density_scale(air_density, dust_density, ozone_density);
  const float latitude_step = kHalfPi / kNishitaHeight;
  const float longitude_step = kTwoPi / kNishitaWidth;
  const float half_lat_step = latitude_step / 2.0f;
  // Rows are independent: the table does not depend on how TBB splits them.
  tbb::parallel_for(0, kNishitaHeight, [&](int y) {
    const float v = static_cast<float>(y) / kNishitaHeight;
    const float latitude = (kHalfPi + half_lat_step) * (v * v);  // denser near the horizon
    float spectrum[kWavelengths];
    float* row = table.data() + static_cast<size_t>(y) * kNishitaWidth * 3;
    for (int x = 0; x < kNishitaWidth / 2; ++x) {
      const float longitude = longitude_step * x - kPi;
      single_scattering(geographical_to_direction(latitude, longitude), sun_dir, origin,
                        density_scale, spectrum);
      const Vec3 xyz = spectrum_to_xyz(spectrum);
      // The sky is symmetric about the sun's vertical plane.
      for (int px : {x, kNishitaWidth - x - 1}) {
        row[px * 3 + 0] = xyz.x;
        row[px * 3 + 1] = xyz.y;
        row[px * 3 + 2] = xyz.z;
      }
    }
  });
  return table;
}

void nishita_sun_pixels(float sun_elevation, float angular_diameter, float altitude,
                        float air_density, float dust_density, Vec3* bottom, Vec3* top) {
  const float half = angular_diameter / 2.0f;
  const float solid_angle = kTwoPi * (1.0f - std::cos(half));
  const float lo = std::max(sun_elevation - half, 0.0f);
  const float hi = std::max(sun_elevation + half, 0.0f);
  *bottom = sun_radiance_xyz(geographical_to_direction(lo, 0.0f), altitude, air_density,
                             dust_density, solid_angle);
  *top = sun_radiance_xyz(geographical_to_direction(hi, 0.0f), altitude, air_density, dust_density,
                          solid_angle);
}

CompileStatus compile_sky_node(const NodeDesc& desc, ShaderProgram* program, Instruction* ins,
                               std::string* error) {
  ins->in[0] = input_register(desc, "Vector");  // -1: the ray direction (see eval)
  ins->out[0] = output_register(desc, "Color");
  const std::string type = enum_value(desc, "sky_type", "NISHITA");
  ins->data = static_cast<int32_t>(program->data.size());
  if (type == "NISHITA") {
    ins->mode = static_cast<uint32_t>(SkyModel::kNishita);
    // Blender's ranges; Cycles clamps the altitude to [1 m, 59999 m] and the sun to at least
    // 0.0005 rad across.
    const float elevation = clamped_number(desc, "sun_elevation", 0.2617994, -kHalfPi, kHalfPi);
    float rotation = clamped_number(desc, "sun_rotation", 0.0, -1e6, 1e6);
    const float size = std::max(clamped_number(desc, "sun_size", 0.009512, 0.0, kHalfPi), 0.0005f);
    const float intensity = clamped_number(desc, "sun_intensity", 1.0, 0.0, 1e6);
    const float altitude = clamped_number(desc, "altitude", 0.0, 1.0, 59999.0);
    const float air = clamped_number(desc, "air_density", 1.0, 0.0, 10.0);
    const float dust = clamped_number(desc, "dust_density", 1.0, 0.0, 10.0);
    const float ozone = clamped_number(desc, "ozone_density", 1.0, 0.0, 10.0);
    const bool disc = enum_value(desc, "sun_disc", "True") == "True";
    Vec3 bottom, top;
    nishita_sun_pixels(elevation, size, altitude, air, dust, &bottom, &top);
    // Cycles turns the rotation into [0, 2 pi) and measures it the other way round.
    rotation = std::fmod(rotation, kTwoPi);
    if (rotation < 0.0f) rotation += kTwoPi;
    rotation = kTwoPi - rotation;
    const float header[kNishitaHeader] = {
        bottom.x, bottom.y, bottom.z, top.x, top.y, top.z, elevation, rotation, disc ? size : -1.0f,
        intensity};
    program->data.insert(program->data.end(), header, header + kNishitaHeader);
    const std::vector<float> table = nishita_sky_table(elevation, altitude, air, dust, ozone);
    program->data.insert(program->data.end(), table.begin(), table.end());
  } else if (type == "PREETHAM" || type == "HOSEK_WILKIE") {
    const bool preetham = type == "PREETHAM";
    ins->mode = static_cast<uint32_t>(preetham ? SkyModel::kPreetham : SkyModel::kHosekWilkie);
    // Blender passes the normalised sun_direction vector (numbers "sun_direction[0..2]").
    Vec3 sun(static_cast<float>(number_value(desc, "sun_direction[0]", 0.0)),
             static_cast<float>(number_value(desc, "sun_direction[1]", 0.0)),
             static_cast<float>(number_value(desc, "sun_direction[2]", 1.0)));
    if (!(std::isfinite(sun.x) && std::isfinite(sun.y) && std::isfinite(sun.z)) ||
        length_squared(sun) == 0.0f) {
      *error = "Sky Texture: the sun direction must be a finite, non-zero vector";
      return CompileStatus::kError;
    }
    sun = sun / len3(sun);
    const float turbidity = clamped_number(desc, "turbidity", 2.2, 1.0, 10.0);
    if (preetham) {
      float d[kPreethamSize];
      precompute_preetham(sun, turbidity, d);
      program->data.insert(program->data.end(), d, d + kPreethamSize);
    } else {
      float d[kHosekSize];
      precompute_hosek(sun, turbidity, clamped_number(desc, "ground_albedo", 0.3, 0.0, 1.0), d);
      program->data.insert(program->data.end(), d, d + kHosekSize);
    }
  } else {
    *error = "Sky Texture: unknown sky type '" + type + "'";
    return CompileStatus::kError;
  }
  ins->data_size = static_cast<int32_t>(program->data.size()) - ins->data;
  return CompileStatus::kCompiled;
}

Vec3 eval_sky(const Instruction& ins, const ShaderProgram& program, const Vec3& dir_in) {
  // Like Cycles, the vector is used as given (a linked vector need not be unit length).
  if (!(std::isfinite(dir_in.x) && std::isfinite(dir_in.y) && std::isfinite(dir_in.z)))
    return Vec3(0.0f);
  const Vec3& dir = dir_in;
  const float* d = program.data.data() + ins.data;
  switch (static_cast<SkyModel>(ins.mode)) {
    case SkyModel::kNishita:
      return eval_nishita(d, dir);
    case SkyModel::kPreetham:
      return eval_preetham(d, dir);
    case SkyModel::kHosekWilkie:
      return eval_hosek(d, dir);
  }
  return Vec3(0.0f);
}

}  // namespace photon
