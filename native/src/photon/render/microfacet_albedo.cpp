#include "photon/render/microfacet_albedo.h"

#include <algorithm>
#include <cmath>

namespace photon::microfacet_albedo {
namespace {

// Linear interpolation along one axis of `size` points at x in [0, 1].
struct Axis {
  int i0, i1;
  float t;
  Axis(float x, int size) {
    x = std::clamp(std::isfinite(x) ? x : 0.0f, 0.0f, 1.0f) * static_cast<float>(size - 1);
    i0 = std::min(static_cast<int>(x), size - 1);
    i1 = std::min(i0 + 1, size - 1);
    t = x - static_cast<float>(i0);
  }
};

float read1(const float* table, float x, int size) {
  const Axis a(x, size);
  return (1.0f - a.t) * table[a.i0] + a.t * table[a.i1];
}

float read2(const float* table, float x, float y, int nx, int ny) {
  const Axis b(y, ny);
  return (1.0f - b.t) * read1(table + nx * b.i0, x, nx) + b.t * read1(table + nx * b.i1, x, nx);
}

float read3(const float* table, float x, float y, float z, int n) {
  const Axis c(z, n);
  return (1.0f - c.t) * read2(table + n * n * c.i0, x, y, n, n) +
         c.t * read2(table + n * n * c.i1, x, y, n, n);
}

// The IOR axis coordinate of an interface of relative IOR eta >= 1.
float ior_axis(float eta) {
  return std::sqrt(std::fabs((eta - 1.0f) / (eta + 1.0f)));
}

}  // namespace

float reflection_albedo(float r, float mu) {
  return read2(kReflectionE, r, mu, kReflectionSize, kReflectionSize);
}

float reflection_albedo_average(float r) {
  return read1(kReflectionEavg, r, kReflectionSize);
}

float glass_albedo(float r, float mu, float eta) {
  const bool inverted = eta < 1.0f;
  const float z = ior_axis(inverted ? 1.0f / eta : eta);
  return read3(inverted ? kGlassInvE : kGlassE, r, mu, z, kGlassSize);
}

float glass_albedo_average(float r, float eta) {
  const bool inverted = eta < 1.0f;
  const float z = ior_axis(inverted ? 1.0f / eta : eta);
  return read2(inverted ? kGlassInvEavg : kGlassEavg, r, z, kGlassSize, kGlassSize);
}

float schlick_ior_factor_average(float r, float mu, float eta) {
  return read3(kSchlickIorS, r, mu, ior_axis(eta), kGlassSize);
}

}  // namespace photon::microfacet_albedo
