#include "photon/scene/material.h"

#include <algorithm>
#include <cmath>

namespace photon {
namespace {

bool constant_zero(const Input& in) {
  return in.texture < 0 && max_component(in.value) <= 0.0f;
}

// A closure weight that is a product of constant factors, one of which is 0 (or 1 - 1).
bool weight_is_zero(const Closure& c) {
  for (const WeightFactor& f : c.weight) {
    if (f.fac.texture >= 0) continue;
    const float v = std::clamp(f.fac.value.x, 0.0f, 1.0f);
    if ((f.complement ? 1.0f - v : v) <= 0.0f) return true;
  }
  return false;
}

constexpr float kHuge = 1e6f;

float clamp_or(float v, const ParamRange& r, float fallback) {
  return std::isfinite(v) ? std::clamp(v, r.lo, r.hi) : fallback;
}

// A constant clamped into `r` component-wise (non-finite components take `fallback`'s), or a
// texture lookup when the index names an existing texture, else `fallback`.
void sanitize_input(Input* in, const ParamRange& r, const Input& fallback, size_t texture_count) {
  if (in->texture >= 0 && static_cast<size_t>(in->texture) >= texture_count) *in = fallback;
  if (in->texture < 0) in->texture = -1;
  in->value = {clamp_or(in->value.x, r, fallback.value.x),
               clamp_or(in->value.y, r, fallback.value.y),
               clamp_or(in->value.z, r, fallback.value.z)};
}

}  // namespace

ParamRange param_range(ClosureType type, Param p) {
  switch (p) {
    case Param::kColor:
      return type == ClosureType::kEmission ? ParamRange{0.0f, kHuge} : ParamRange{0.0f, 1.0f};
    case Param::kEmission:
    case Param::kStrength:
      return {0.0f, kHuge};
    case Param::kSpecular:
      return {0.0f, 10.0f};
    case Param::kIor:
      return {1e-3f, 100.0f};
    default:
      return {0.0f, 1.0f};
  }
}

ParamRange emitter_range() {
  return {0.0f, kHuge * kHuge};
}

void sanitize_material(Material* material, size_t texture_count) {
  static const auto kDefaults = Closure::default_params();
  for (Closure& c : material->closures) {
    for (size_t i = 0; i < kDefaults.size(); ++i)
      sanitize_input(&c.params[i], param_range(c.type, static_cast<Param>(i)), kDefaults[i],
                     texture_count);
    if (c.normal.texture < 0 || static_cast<size_t>(c.normal.texture) >= texture_count)
      c.normal = NormalMap{};
    c.normal.strength = clamp_or(c.normal.strength, {0.0f, 100.0f}, 1.0f);
    for (WeightFactor& f : c.weight)
      sanitize_input(&f.fac, {0.0f, 1.0f}, Input::constant(0.5f), texture_count);
  }
}

std::array<Input, static_cast<size_t>(Param::kCount)> Closure::default_params() {
  std::array<Input, static_cast<size_t>(Param::kCount)> p;
  auto set = [&p](Param k, const Vec3& v) { p[static_cast<size_t>(k)] = Input::constant(v); };
  set(Param::kColor, Vec3(0.8f));
  set(Param::kRoughness, Vec3(0.5f));
  set(Param::kMetallic, Vec3(0.0f));
  set(Param::kSpecular, Vec3(0.5f));
  set(Param::kSpecularTint, Vec3(0.0f));
  set(Param::kTransmission, Vec3(0.0f));
  set(Param::kIor, Vec3(1.45f));
  set(Param::kEmission, Vec3(0.0f));
  set(Param::kStrength, Vec3(1.0f));
  set(Param::kAlpha, Vec3(1.0f));
  set(Param::kClearcoat, Vec3(0.0f));
  set(Param::kClearcoatRoughness, Vec3(0.03f));
  return p;
}

Material Material::diffuse(const Vec3& color, const std::string& name) {
  Closure c;
  c.type = ClosureType::kDiffuse;
  c[Param::kColor] = Input::constant(color);
  return Material{name, {c}};
}

Material Material::mirror(const Vec3& tint, const std::string& name) {
  Closure c;
  c.type = ClosureType::kGlossy;
  c.sharp = true;
  c[Param::kColor] = Input::constant(tint);
  c[Param::kRoughness] = Input::constant(0.0f);
  return Material{name, {c}};
}

Material Material::glass(float ior, const Vec3& tint, const std::string& name) {
  Closure c;
  c.type = ClosureType::kGlass;
  c.sharp = true;
  c[Param::kColor] = Input::constant(tint);
  c[Param::kRoughness] = Input::constant(0.0f);
  c[Param::kIor] = Input::constant(ior);
  return Material{name, {c}};
}

Material Material::emission(const Vec3& radiance, const std::string& name) {
  Closure c;
  c.type = ClosureType::kEmission;
  c[Param::kColor] = Input::constant(radiance);
  c[Param::kStrength] = Input::constant(1.0f);
  return Material{name, {c}};
}

Material Material::with_emission(const Vec3& radiance) const {
  Material m = *this;
  m.closures.push_back(emission(radiance).closures.front());
  return m;
}

bool Material::may_emit() const {
  for (const Closure& c : closures) {
    if (weight_is_zero(c)) continue;
    if (c.type == ClosureType::kEmission && !constant_zero(c[Param::kColor]) &&
        !constant_zero(c[Param::kStrength]))
      return true;
    if (c.type == ClosureType::kPrincipled && !constant_zero(c[Param::kEmission]) &&
        !constant_zero(c[Param::kStrength]))
      return true;
  }
  return false;
}

bool Material::may_be_specular() const {
  // Perfectly specular (delta) lobes form caustics; rough lobes are gathered instead.
  auto smooth = [](const Input& roughness) {
    return roughness.texture >= 0 || roughness.value.x * roughness.value.x < 1e-4f;
  };
  for (const Closure& c : closures) {
    if (weight_is_zero(c)) continue;
    switch (c.type) {
      case ClosureType::kGlossy:
      case ClosureType::kGlass:
      case ClosureType::kRefraction:
        if (c.sharp || smooth(c[Param::kRoughness])) return true;
        break;
      case ClosureType::kPrincipled:
        if (smooth(c[Param::kRoughness]) &&
            (!constant_zero(c[Param::kMetallic]) || !constant_zero(c[Param::kTransmission]) ||
             !constant_zero(c[Param::kSpecular])))
          return true;
        break;
      default:
        break;
    }
  }
  return false;
}

}  // namespace photon
