#include "photon/scene/material.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "photon/scene/material_params.h"
#include "photon/scene/shader_program.h"

namespace photon {
namespace {

bool constant_zero(const Input& in) {
  return in.is_constant() && max_component(in.value) <= 0.0f;
}

// A closure weight that is a product of constant factors, one of which is 0 (or 1 - 1).
bool weight_is_zero(const Closure& c) {
  for (const WeightFactor& f : c.weight) {
    if (!f.fac.is_constant()) continue;
    const float v = std::clamp(f.fac.value.x, 0.0f, 1.0f);
    if ((f.complement ? 1.0f - v : v) <= 0.0f) return true;
  }
  return false;
}

float clamp_or(float v, const ParamRange& r, float fallback) {
  return std::isfinite(v) ? std::clamp(v, r.lo, r.hi) : fallback;
}

// A constant clamped into `r` component-wise (non-finite components take `fallback`'s), or a
// texture lookup when the index names an existing texture, else `fallback`.
void sanitize_input(Input* in, const ParamRange& r, const Input& fallback, size_t texture_count,
                    size_t register_count) {
  if (in->reg >= 0 && static_cast<size_t>(in->reg) + 3 > register_count) in->reg = -1;
  if (in->reg < 0) in->reg = -1;
  if (in->texture >= 0 && static_cast<size_t>(in->texture) >= texture_count) {
    const int32_t reg = in->reg;
    *in = fallback;
    in->reg = reg;
  }
  if (in->texture < 0) in->texture = -1;
  in->value = {clamp_or(in->value.x, r, fallback.value.x),
               clamp_or(in->value.y, r, fallback.value.y),
               clamp_or(in->value.z, r, fallback.value.z)};
}

}  // namespace

void sanitize_material(Material* material, size_t texture_count, std::string* warning) {
  std::string error;
  if (!material->program.empty() && !validate_program(material->program, &error)) {
    if (warning)
      *warning = "Material '" + material->name + "': its node program is invalid (" + error +
                 "); its inputs use their constant values";
    material->program = ShaderProgram{};
  }
  const size_t registers = material->program.empty() ? 0 : material->program.registers.size();
  for (Closure& c : material->closures) {
    if (c.normal_reg >= 0 && static_cast<size_t>(c.normal_reg) + 3 > registers) c.normal_reg = -1;
    if (c.normal_reg < 0) c.normal_reg = -1;
    if (c.clearcoat_normal_reg >= 0 && static_cast<size_t>(c.clearcoat_normal_reg) + 3 > registers)
      c.clearcoat_normal_reg = -1;
    if (c.clearcoat_normal_reg < 0) c.clearcoat_normal_reg = -1;
    // Ranges and fallbacks from the one table (material_params.cpp): the node's own defaults.
    const auto defaults = default_params(c.type);
    for (size_t i = 0; i < defaults.size(); ++i)
      sanitize_input(&c.params[i], param_range(c.type, static_cast<Param>(i)), defaults[i],
                     texture_count, registers);
    if (c.normal.texture < 0 || static_cast<size_t>(c.normal.texture) >= texture_count)
      c.normal = NormalMap{};
    c.normal.strength =
        clamp_or(c.normal.strength, kNormalMapStrength.range, kNormalMapStrength.default_value);
    for (WeightFactor& f : c.weight)
      sanitize_input(&f.fac, kMixFactor.range, Input::constant(kMixFactor.default_value),
                     texture_count, registers);
  }
  for (MaterialAov& aov : material->aovs) sanitize_aov(&aov, texture_count, registers);
}

void sanitize_aov(MaterialAov* aov, size_t texture_count, size_t register_count) {
  // AOV values are written as the nodes compute them (Cycles clamps nothing), finite only.
  const ParamRange any{-std::numeric_limits<float>::max(), std::numeric_limits<float>::max()};
  sanitize_input(&aov->value, any, Input::constant(0.0f), texture_count, register_count);
}

std::array<Input, static_cast<size_t>(Param::kCount)> Closure::default_params() {
  return photon::default_params(ClosureType::kPrincipled);
}

namespace {

Material one_closure(const std::string& name, const Closure& c) {
  Material m;
  m.name = name;
  m.closures = {c};
  return m;
}

}  // namespace

Material Material::diffuse(const Vec3& color, const std::string& name) {
  Closure c;
  c.type = ClosureType::kDiffuse;
  c.params = photon::default_params(ClosureType::kDiffuse);  // Roughness 0: Lambert
  c[Param::kColor] = Input::constant(color);
  return one_closure(name, c);
}

Material Material::mirror(const Vec3& tint, const std::string& name) {
  Closure c;
  c.type = ClosureType::kGlossy;
  c.sharp = true;
  c[Param::kColor] = Input::constant(tint);
  c[Param::kRoughness] = Input::constant(0.0f);
  return one_closure(name, c);
}

Material Material::glass(float ior, const Vec3& tint, const std::string& name) {
  Closure c;
  c.type = ClosureType::kGlass;
  c.sharp = true;
  c[Param::kColor] = Input::constant(tint);
  c[Param::kRoughness] = Input::constant(0.0f);
  c[Param::kIor] = Input::constant(ior);
  return one_closure(name, c);
}

Material Material::emission(const Vec3& radiance, const std::string& name) {
  Closure c;
  c.type = ClosureType::kEmission;
  c[Param::kColor] = Input::constant(radiance);
  c[Param::kStrength] = Input::constant(1.0f);
  return one_closure(name, c);
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
    if ((c.type == ClosureType::kPrincipled || c.type == ClosureType::kPrincipledV2) &&
        !constant_zero(c[Param::kEmission]) && !constant_zero(c[Param::kStrength]))
      return true;
  }
  return false;
}

bool Material::may_be_transparent() const {
  for (const Closure& c : closures) {
    if (weight_is_zero(c)) continue;
    if (c.type == ClosureType::kTransparent && !constant_zero(c[Param::kColor])) return true;
    if (c.type == ClosureType::kPrincipled || c.type == ClosureType::kPrincipledV2) {
      const Input& alpha = c[Param::kAlpha];
      if (!alpha.is_constant() || alpha.value.x < 1.0f) return true;
    }
  }
  return false;
}

bool Material::needs_tangent() const {
  for (const Closure& c : closures) {
    if (c.type == ClosureType::kAnisotropic) return true;
    if ((c.type == ClosureType::kPrincipled || c.type == ClosureType::kPrincipledV2) &&
        !constant_zero(c[Param::kAnisotropic]))
      return true;
  }
  return false;
}

bool Material::may_be_specular() const {
  // Perfectly specular (delta) lobes form caustics; rough lobes are gathered instead.
  auto smooth = [](const Input& roughness) {
    return !roughness.is_constant() || roughness.value.x * roughness.value.x < 1e-4f;
  };
  for (const Closure& c : closures) {
    if (weight_is_zero(c)) continue;
    switch (c.type) {
      case ClosureType::kGlossy:
      case ClosureType::kGlass:
      case ClosureType::kRefraction:
      case ClosureType::kAnisotropic:
        if (c.sharp || smooth(c[Param::kRoughness])) return true;
        break;
      case ClosureType::kPrincipled:
        if (smooth(c[Param::kRoughness]) &&
            (!constant_zero(c[Param::kMetallic]) || !constant_zero(c[Param::kTransmission]) ||
             !constant_zero(c[Param::kSpecular])))
          return true;
        break;
      case ClosureType::kPrincipledV2:
        // Its specular layer is always there (unless the IOR is 1), and so is the coat's.
        if (smooth(c[Param::kRoughness])) return true;
        if (!constant_zero(c[Param::kCoatWeight]) && smooth(c[Param::kCoatRoughness])) return true;
        break;
      default:
        break;
    }
  }
  return false;
}

}  // namespace photon
