#include "photon/scene/material_params.h"

#include <cstring>

#include "photon/base/check.h"

namespace photon {
namespace {

// Emission colours and strengths may exceed 1, up to a finite bound (see emitter_range()).
constexpr float kHuge = 1e6f;
constexpr ParamRange kUnit{0.0f, 1.0f};
constexpr ParamRange kEmissive{0.0f, kHuge};
// IOR stays positive and bounded (100 already reflects almost everything).
constexpr ParamRange kIorRange{1e-3f, 100.0f};
// A rotation in turns (Anisotropic Rotation): any finite value, bounded so sin/cos stay exact.
constexpr ParamRange kTurns{-1e4f, 1e4f};

constexpr ParamKind S = ParamKind::kScalar;
constexpr ParamKind C = ParamKind::kColor;

ClosureParamSpec color(float default_value, ParamRange range = kUnit) {
  return {Param::kColor, "color", {"Color", nullptr}, C, default_value, range};
}
ClosureParamSpec roughness(float default_value) {
  return {Param::kRoughness, "roughness", {"Roughness", nullptr}, S, default_value, kUnit};
}
ClosureParamSpec ior() {
  return {Param::kIor, "ior", {"IOR", nullptr}, S, 1.45f, kIorRange};
}

std::vector<ClosureSpec> make_table() {
  // Blender 3.4's node defaults (nodes/shader/nodes/node_shader_*.cc); 4.x socket names second.
  std::vector<ClosureParamSpec> principled = {
      {Param::kColor, "color", {"Base Color", nullptr}, C, 0.8f, kUnit},
      {Param::kMetallic, "metallic", {"Metallic", nullptr}, S, 0.0f, kUnit},
      {Param::kRoughness, "roughness", {"Roughness", nullptr}, S, 0.5f, kUnit},
      // Specular 0.5 is F0 = 0.04 (0.08 x specular, Cycles' Principled v1); up to 10 is kept.
      {Param::kSpecular, "specular", {"Specular", nullptr}, S, 0.5f, {0.0f, 10.0f}},
      {Param::kSpecularTint, "specular_tint", {"Specular Tint", nullptr}, S, 0.0f, kUnit},
      {Param::kTransmission, "transmission", {"Transmission", nullptr}, S, 0.0f, kUnit},
      {Param::kIor, "ior", {"IOR", nullptr}, S, 1.45f, kIorRange},
      {Param::kEmission, "emission", {"Emission", nullptr}, C, 0.0f, kEmissive},
      {Param::kStrength, "strength", {"Emission Strength", nullptr}, S, 1.0f, kEmissive},
      {Param::kAlpha, "alpha", {"Alpha", nullptr}, S, 1.0f, kUnit},
      {Param::kClearcoat, "clearcoat", {"Clearcoat", nullptr}, S, 0.0f, kUnit},
      {Param::kClearcoatRoughness,
       "clearcoat_roughness",
       {"Clearcoat Roughness", nullptr},
       S,
       0.03f,
       kUnit},
      {Param::kSubsurface, "subsurface", {"Subsurface", nullptr}, S, 0.0f, kUnit},
      {Param::kSubsurfaceColor, "subsurface_color", {"Subsurface Color", nullptr}, C, 0.8f, kUnit},
      {Param::kSheen, "sheen", {"Sheen", nullptr}, S, 0.0f, kUnit},
      {Param::kSheenTint, "sheen_tint", {"Sheen Tint", nullptr}, S, 0.5f, kUnit},
      {Param::kAnisotropic, "anisotropic", {"Anisotropic", nullptr}, S, 0.0f, kUnit},
      // Rotation in turns: program-fed values beyond [0, 1] wrap around as in Cycles.
      {Param::kAnisotropicRotation,
       "anisotropic_rotation",
       {"Anisotropic Rotation", nullptr},
       S,
       0.0f,
       kTurns},
      {Param::kTransmissionRoughness,
       "transmission_roughness",
       {"Transmission Roughness", nullptr},
       S,
       0.0f,
       kUnit},
  };
  // Blender 4.0+'s Principled BSDF (v2): its own sockets and defaults (nodes/shader/nodes/
  // node_shader_bsdf_principled.cc of 4.x); Cycles clamps the weights and roughnesses to [0, 1].
  constexpr ParamRange kLevel{0.0f, 100.0f};
  std::vector<ClosureParamSpec> principled_v2 = {
      {Param::kColor, "color", {"Base Color", nullptr}, C, 0.8f, kUnit},
      {Param::kMetallic, "metallic", {"Metallic", nullptr}, S, 0.0f, kUnit},
      {Param::kRoughness, "roughness", {"Roughness", nullptr}, S, 0.5f, kUnit},
      {Param::kIor, "ior", {"IOR", nullptr}, S, 1.5f, kIorRange},
      {Param::kAlpha, "alpha", {"Alpha", nullptr}, S, 1.0f, kUnit},
      {Param::kDiffuseRoughness,
       "diffuse_roughness",
       {"Diffuse Roughness", nullptr},
       S,
       0.0f,
       kUnit},
      {Param::kSubsurface, "subsurface", {"Subsurface Weight", nullptr}, S, 0.0f, kUnit},
      {Param::kSpecularIorLevel,
       "specular_ior_level",
       {"Specular IOR Level", nullptr},
       S,
       0.5f,
       kLevel},
      {Param::kSpecularTintColor,
       "specular_tint_color",
       {"Specular Tint", nullptr},
       C,
       1.0f,
       kLevel},
      {Param::kAnisotropic, "anisotropic", {"Anisotropic", nullptr}, S, 0.0f, kUnit},
      {Param::kAnisotropicRotation,
       "anisotropic_rotation",
       {"Anisotropic Rotation", nullptr},
       S,
       0.0f,
       kTurns},
      {Param::kTransmission, "transmission", {"Transmission Weight", nullptr}, S, 0.0f, kUnit},
      {Param::kCoatWeight, "coat_weight", {"Coat Weight", nullptr}, S, 0.0f, kUnit},
      {Param::kCoatRoughness, "coat_roughness", {"Coat Roughness", nullptr}, S, 0.03f, kUnit},
      {Param::kCoatIor, "coat_ior", {"Coat IOR", nullptr}, S, 1.5f, {1.0f, 100.0f}},
      {Param::kCoatTint, "coat_tint", {"Coat Tint", nullptr}, C, 1.0f, kUnit},
      {Param::kSheenWeight, "sheen_weight", {"Sheen Weight", nullptr}, S, 0.0f, kUnit},
      {Param::kSheenRoughness, "sheen_roughness", {"Sheen Roughness", nullptr}, S, 0.5f, kUnit},
      {Param::kSheenTintColor, "sheen_tint_color", {"Sheen Tint", nullptr}, C, 1.0f, kLevel},
      {Param::kEmission, "emission", {"Emission Color", nullptr}, C, 1.0f, kEmissive},
      {Param::kStrength, "strength", {"Emission Strength", nullptr}, S, 0.0f, kEmissive},
      {Param::kThinFilmThickness,
       "thin_film_thickness",
       {"Thin Film Thickness", nullptr},
       S,
       0.0f,
       {0.0f, 100000.0f}},
      {Param::kThinFilmIor, "thin_film_ior", {"Thin Film IOR", nullptr}, S, 1.33f, kIorRange},
  };
  return {
      {ClosureType::kDiffuse, "DIFFUSE", "BSDF_DIFFUSE", {color(0.8f), roughness(0.0f)}},
      {ClosureType::kPrincipled, "PRINCIPLED", "BSDF_PRINCIPLED", principled},
      {ClosureType::kGlossy, "GLOSSY", "BSDF_GLOSSY", {color(0.8f), roughness(0.5f)}},
      {ClosureType::kGlass, "GLASS", "BSDF_GLASS", {color(1.0f), roughness(0.0f), ior()}},
      {ClosureType::kRefraction,
       "REFRACTION",
       "BSDF_REFRACTION",
       {color(1.0f), roughness(0.0f), ior()}},
      {ClosureType::kTransparent, "TRANSPARENT", "BSDF_TRANSPARENT", {color(1.0f)}},
      {ClosureType::kTranslucent, "TRANSLUCENT", "BSDF_TRANSLUCENT", {color(0.8f)}},
      {ClosureType::kEmission,
       "EMISSION",
       "EMISSION",
       {color(1.0f, kEmissive),
        {Param::kStrength, "strength", {"Strength", nullptr}, S, 1.0f, kEmissive}}},
      // Cuts a hole in the image where camera rays meet it (integrators/matte.h); no inputs.
      {ClosureType::kHoldout, "HOLDOUT", "HOLDOUT", {}},
      // Anisotropy in [-1, 1] (Cycles clamps it to +-0.99).
      {ClosureType::kAnisotropic,
       "ANISOTROPIC",
       "BSDF_ANISOTROPIC",
       {color(0.8f),
        roughness(0.5f),
        {Param::kAnisotropic, "anisotropic", {"Anisotropy", nullptr}, S, 0.5f, {-1.0f, 1.0f}},
        {Param::kAnisotropicRotation,
         "anisotropic_rotation",
         {"Rotation", nullptr},
         S,
         0.0f,
         kTurns}}},
      {ClosureType::kPrincipledV2, "PRINCIPLED_V2", "BSDF_PRINCIPLED", principled_v2},
      {ClosureType::kVelvet,
       "VELVET",
       "BSDF_VELVET",
       // Blender 4's Sheen BSDF with the Ashikhmin distribution reads Roughness as Sigma.
       {color(0.8f), {Param::kSigma, "sigma", {"Sigma", "Roughness"}, S, 1.0f, kUnit}}},
  };
}

const ClosureParamSpec* find_in(const ClosureSpec& closure, Param p) {
  for (const ClosureParamSpec& spec : closure.params)
    if (spec.param == p) return &spec;
  return nullptr;
}

}  // namespace

const std::vector<ClosureSpec>& closure_specs() {
  static const std::vector<ClosureSpec> table = make_table();
  return table;
}

const ClosureSpec& closure_spec(ClosureType type) {
  return closure_specs()[static_cast<size_t>(type)];
}

const ClosureSpec* find_closure(const char* name) {
  for (const ClosureSpec& c : closure_specs())
    if (std::strcmp(c.name, name) == 0) return &c;
  return nullptr;
}

const ClosureParamSpec& param_spec(ClosureType type, Param p) {
  if (const ClosureParamSpec* own = find_in(closure_spec(type), p)) return *own;
  if (const ClosureParamSpec* v1 = find_in(closure_spec(ClosureType::kPrincipled), p)) return *v1;
  if (const ClosureParamSpec* v2 = find_in(closure_spec(ClosureType::kPrincipledV2), p)) return *v2;
  // A parameter only one other closure has (Velvet's Sigma).
  for (const ClosureSpec& c : closure_specs())
    if (const ClosureParamSpec* other = find_in(c, p)) return *other;
  check_failed("some closure has every material parameter", __FILE__, __LINE__);
}

const ClosureParamSpec* find_param(const char* key) {
  // The Principled BSDFs first (they hold every shared key), then the keys of one closure only.
  for (ClosureType t : {ClosureType::kPrincipled, ClosureType::kPrincipledV2})
    for (const ClosureParamSpec& spec : closure_spec(t).params)
      if (std::strcmp(spec.key, key) == 0) return &spec;
  for (const ClosureSpec& c : closure_specs())
    for (const ClosureParamSpec& spec : c.params)
      if (std::strcmp(spec.key, key) == 0) return &spec;
  return nullptr;
}

ParamRange param_range(ClosureType type, Param p) {
  return param_spec(type, p).range;
}

ParamRange emitter_range() {
  return {0.0f, kHuge * kHuge};
}

std::array<Input, static_cast<size_t>(Param::kCount)> default_params(ClosureType type) {
  std::array<Input, static_cast<size_t>(Param::kCount)> p;
  for (size_t i = 0; i < p.size(); ++i)
    p[i] = Input::constant(param_spec(type, static_cast<Param>(i)).default_value);
  return p;
}

}  // namespace photon
