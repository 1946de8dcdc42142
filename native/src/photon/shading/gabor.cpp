#include "photon/shading/gabor.h"

#include <algorithm>
#include <cmath>

#include "photon/shading/hash.h"

namespace photon::gabor {
namespace {

constexpr int kImpulses = 8;
constexpr float kPi = 3.14159265358979323846f;  // Cycles' M_PI_F
constexpr float kSqrt2 = 1.41421356237309504880f;

struct Phasor {
  float x = 0.0f, y = 0.0f;
};

Phasor kernel_2d(float px, float py, float frequency, float orientation) {
  const float d2 = px * px + py * py;
  const float hann = 0.5f + 0.5f * std::cos(kPi * d2);
  const float gauss = std::exp(-kPi * d2);
  const float envelope = gauss * hann;
  const float fx = frequency * std::cos(orientation), fy = frequency * std::sin(orientation);
  const float angle = 2.0f * kPi * (px * fx + py * fy);
  return {envelope * std::cos(angle), envelope * std::sin(angle)};
}

Phasor kernel_3d(const Vec3& p, float frequency, const Vec3& orientation) {
  const float d2 = dot(p, p);
  const float hann = 0.5f + 0.5f * std::cos(kPi * d2);
  const float gauss = std::exp(-kPi * d2);
  const float envelope = gauss * hann;
  const Vec3 f = orientation * frequency;
  const float angle = 2.0f * kPi * dot(p, f);
  return {envelope * std::cos(angle), envelope * std::sin(angle)};
}

Vec3 orientation_3d(const Vec3& o, float isotropy, const Vec3& seed, float seed_w) {
  if (isotropy == 0.0f) return o;
  float inclination = std::acos(o.z);
  float azimuth = (o.y < 0.0f ? -1.0f : 1.0f) * std::acos(o.x / std::sqrt(o.x * o.x + o.y * o.y));
  // hash_float4_to_float2: (h(x, y, z, w), h(z, x, w, y)).
  const float ra = hash::hash_float4_to_float(seed, seed_w) * kPi;
  const float rb = hash::hash_float4_to_float(Vec3(seed.z, seed.x, seed_w), seed.y) * kPi;
  inclination += ra * isotropy;
  azimuth += rb * isotropy;
  return Vec3(std::sin(inclination) * std::cos(azimuth), std::sin(inclination) * std::sin(azimuth),
              std::cos(inclination));
}

Result finish(const Phasor& s, float standard_deviation) {
  const float norm = 6.0f * standard_deviation;
  Result r;
  r.value = (s.y / norm) * 0.5f + 0.5f;
  r.phase = (std::atan2(s.y, s.x) + kPi) / (2.0f * kPi);
  r.intensity = std::sqrt(s.x * s.x + s.y * s.y) / norm;
  return r;
}

}  // namespace

Result gabor_2d(const Vec3& p, float frequency, float anisotropy, float orientation) {
  const float isotropy = 1.0f - std::clamp(anisotropy, 0.0f, 1.0f);
  frequency = std::max(0.001f, frequency);
  const float cx = std::floor(p.x), cy = std::floor(p.y);
  const float lx = p.x - cx, ly = p.y - cy;
  Phasor sum;
  for (int j = -1; j <= 1; ++j) {
    for (int i = -1; i <= 1; ++i) {
      const float cell_x = cx + float(i), cell_y = cy + float(j);
      const float px = lx - float(i), py = ly - float(j);
      Phasor cell;
      for (int k = 0; k < kImpulses; ++k) {
        const float z = float(k * 3);
        const float random_orientation =
            (hash::hash_float3_to_float(Vec3(cell_x, cell_y, z)) - 0.5f) * kPi;
        const float o = orientation + random_orientation * isotropy;
        // hash_float3_to_float2 of (x, y, z): (h(x, y, z), h(z, x, y)).
        const Vec3 seed(cell_x, cell_y, z + 1.0f);
        const float kx = hash::hash_float3_to_float(seed);
        const float ky = hash::hash_float3_to_float(Vec3(seed.z, seed.x, seed.y));
        const float qx = px - kx, qy = py - ky;
        if (qx * qx + qy * qy >= 1.0f) continue;
        const float weight =
            hash::hash_float3_to_float(Vec3(cell_x, cell_y, z + 2.0f)) < 0.5f ? -1.0f : 1.0f;
        const Phasor g = kernel_2d(qx, qy, frequency, o);
        cell.x += weight * g.x;
        cell.y += weight * g.y;
      }
      sum.x += cell.x;
      sum.y += cell.y;
    }
  }
  return finish(sum, std::sqrt(kImpulses * 0.5f * 0.25f));
}

Result gabor_3d(const Vec3& p, float frequency, float anisotropy, const Vec3& orientation_in) {
  const float isotropy = 1.0f - std::clamp(anisotropy, 0.0f, 1.0f);
  frequency = std::max(0.001f, frequency);
  const Vec3 orientation = orientation_in / length(orientation_in);
  const Vec3 c(std::floor(p.x), std::floor(p.y), std::floor(p.z));
  const Vec3 l = p - c;
  Phasor sum;
  for (int kz = -1; kz <= 1; ++kz) {
    for (int j = -1; j <= 1; ++j) {
      for (int i = -1; i <= 1; ++i) {
        const Vec3 offset(static_cast<float>(i), static_cast<float>(j), static_cast<float>(kz));
        const Vec3 cell_pos = c + offset;
        const Vec3 pos = l - offset;
        Phasor cell;
        for (int k = 0; k < kImpulses; ++k) {
          const float w = float(k * 3);
          const Vec3 o = orientation_3d(orientation, isotropy, cell_pos, w);
          // hash_float4_to_float3 of (x, y, z, w'): h(x,y,z,w'), h(z,x,w',y), h(w',z,y,x).
          const float w1 = w + 1.0f;
          const Vec3 center(
              hash::hash_float4_to_float(cell_pos, w1),
              hash::hash_float4_to_float(Vec3(cell_pos.z, cell_pos.x, w1), cell_pos.y),
              hash::hash_float4_to_float(Vec3(w1, cell_pos.z, cell_pos.y), cell_pos.x));
          const Vec3 q = pos - center;
          if (dot(q, q) >= 1.0f) continue;
          const float weight = hash::hash_float4_to_float(cell_pos, w + 2.0f) < 0.5f ? -1.0f : 1.0f;
          const Phasor g = kernel_3d(q, frequency, o);
          cell.x += weight * g.x;
          cell.y += weight * g.y;
        }
        sum.x += cell.x;
        sum.y += cell.y;
      }
    }
  }
  return finish(sum, std::sqrt(kImpulses * 0.5f * (1.0f / (4.0f * kSqrt2))));
}

}  // namespace photon::gabor
