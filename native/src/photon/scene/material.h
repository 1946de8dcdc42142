// Plain-data material description: what the add-on reads out of a Blender node tree. A material
// is a flat list of closures (BSDF and emission nodes); Mix Shader and Add Shader nodes become
// each closure's weight, a product of mix factors. Every colour or scalar input is a constant or
// an image texture lookup. material_eval.h turns this into a Bsdf at a hit point.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "photon/base/math.h"
#include "photon/scene/shader_program.h"

namespace photon {

class TexturePixels;  // texture_convert.h: pixels of an image that exists only in memory

enum class TextureExtension : uint8_t { kRepeat, kExtend, kClip };
enum class TextureInterpolation : uint8_t { kClosest, kLinear, kCubic };
// What happens to an image's alpha as Cycles loads it: colour images with straight or
// premultiplied alpha are stored premultiplied (associated), Non-Color and Channel Packed images
// as they are, and images whose alpha mode is None get alpha 1.
enum class TextureAlpha : uint8_t { kKeep, kAssociate, kIgnore };

// An Image Texture node's image and sampling settings (Scene::textures).
struct ImageTexture {
  // A file OpenImageIO can read (packed images are written out by the add-on); with `pixels`,
  // the image's name (for messages).
  std::string path;
  bool srgb = true;  // colour space: sRGB (converted to linear) or Non-Color / linear data
  TextureExtension extension = TextureExtension::kRepeat;
  TextureInterpolation interpolation = TextureInterpolation::kLinear;
  std::shared_ptr<TexturePixels> pixels;  // instead of `path`: a generated image's pixels
  TextureAlpha alpha = TextureAlpha::kKeep;
  // An associated image read by a node whose Alpha output is used: lookups divide the colour
  // by alpha (Cycles' NODE_IMAGE_ALPHA_UNASSOCIATE); otherwise the colour stays premultiplied.
  bool unassociate = false;
};

enum class TextureChannel : uint8_t { kColor, kAlpha };

// A shader input socket: a constant, an image texture read at the hit's UV coordinates (the
// mesh's active UV layer), or a register of the material's shader program (any expression of
// nodes: one float for a scalar, three for a colour). Scalars use value.x.
struct Input {
  Vec3 value{0.0f};
  int32_t texture = -1;  // Scene::textures index, or -1 for the constant
  TextureChannel channel = TextureChannel::kColor;
  int32_t reg = -1;  // Material::program register, or -1

  bool is_constant() const { return texture < 0 && reg < 0; }

  static Input constant(float v) { return Input{Vec3(v), -1, TextureChannel::kColor}; }
  static Input constant(const Vec3& v) { return Input{v, -1, TextureChannel::kColor}; }
};

enum class ClosureType : uint8_t {
  kDiffuse,      // Diffuse BSDF: Lambert, or Oren-Nayar when Roughness > 0 (as Cycles 3.4)
  kPrincipled,   // Principled BSDF (Cycles' 3.4 model, see material_eval.cpp)
  kGlossy,       // Glossy BSDF: sharp or GGX reflection, F = 1 tinted by colour
  kGlass,        // Glass BSDF: reflection + refraction
  kRefraction,   // Refraction BSDF
  kTransparent,  // Transparent BSDF
  kTranslucent,  // Translucent BSDF
  kEmission,     // Emission: colour x strength
  // Holdout: camera rays that meet it lose their weight's share of the pixel, colour and alpha
  // (Cycles' holdout closure); to every other ray it is black.
  kHoldout,
  // Anisotropic BSDF: anisotropic GGX along the UV tangent (Cycles 3.4's Anisotropic BSDF), and
  // Blender 4's merged Glossy BSDF (with `cycles4`).
  kAnisotropic,
  // Principled BSDF v2 (Blender 4.0+): Cycles 4's layered model (render/principled_v2.h).
  kPrincipledV2,
  // Velvet BSDF (Blender 3.x), and Blender 4's Sheen BSDF with the Ashikhmin distribution (what
  // a Velvet becomes there): Cycles' Ashikhmin velvet with Sigma, a glossy closure.
  kVelvet,
};

// The inputs a closure reads, by role; each closure type uses a subset (the rest keep their
// Blender defaults).
enum class Param : uint8_t {
  kColor,  // Base Color / Color
  kRoughness,
  kMetallic,
  kSpecular,
  kSpecularTint,
  kTransmission,
  kIor,
  kEmission,  // Principled Emission colour
  kStrength,  // Emission Strength (Principled) / Strength (Emission node)
  kAlpha,
  kClearcoat,
  kClearcoatRoughness,
  kSubsurface,           // Principled Subsurface weight (rendered as Cycles' diffuse fallback)
  kSubsurfaceColor,      // Principled Subsurface Color
  kSheen,                // Principled Sheen weight
  kSheenTint,            // Principled Sheen Tint
  kAnisotropic,          // Principled Anisotropic / Anisotropic BSDF Anisotropy
  kAnisotropicRotation,  // Principled Anisotropic Rotation / Anisotropic BSDF Rotation
  kTransmissionRoughness,
  // Principled v2 only (Blender 4.0+ sockets whose meaning has no v1 counterpart).
  kSpecularIorLevel,   // Specular IOR Level: F0 scale, 0.5 = the IOR's own
  kSpecularTintColor,  // Specular Tint (a colour in v2)
  kCoatWeight,
  kCoatRoughness,
  kCoatIor,
  kCoatTint,
  kSheenWeight,
  kSheenRoughness,
  kSheenTintColor,  // Sheen Tint (a colour in v2)
  kThinFilmThickness,
  kThinFilmIor,
  kDiffuseRoughness,
  kSigma,  // Velvet BSDF's Sigma
  kCount,
};

// A Normal Map node (tangent space) feeding a closure's Normal input.
struct NormalMap {
  int32_t texture = -1;  // -1: no normal map, use the interpolated normal
  float strength = 1.0f;
};

// One factor of a closure's weight: `fac` or (1 - fac) (the second input of a Mix Shader).
struct WeightFactor {
  Input fac;
  bool complement = false;
};

struct Closure {
  ClosureType type = ClosureType::kDiffuse;
  std::array<Input, static_cast<size_t>(Param::kCount)> params = default_params();
  bool sharp = false;  // Glossy / Glass / Refraction with the Sharp distribution
  // Glossy, Anisotropic, Glass or Refraction with the Beckmann distribution (GGX otherwise).
  bool beckmann = false;
  // The node comes from Blender 4.0+ and renders with Cycles 4's microfacet model (height-
  // correlated Smith G); Principled v2 always does.
  bool cycles4 = false;
  // Cycles 4's Multiscatter GGX distribution: single-scattering lobes scaled up by the energy
  // they lose (albedo scaling, render/microfacet_albedo.h). Only with `cycles4`.
  bool multiscatter = false;
  // Cycles 4.3+'s Oren-Nayar for a rough Diffuse BSDF: the multiple scattering between its
  // microfacets put back (render/bsdf_lobes.h oren_nayar). Principled v2 always has it.
  bool diffuse_multiscatter = false;
  // Abbe number of Glass, Refraction and Principled transmission (0: no dispersion): in
  // spectral mode the IOR, taken at the d line (587.6 nm), varies with the wavelength.
  float abbe = 0.0f;
  NormalMap normal;
  int32_t normal_reg = -1;  // a program register holding the Normal input (Bump, Normal Map...)
  // A program register holding the Principled Clearcoat Normal input, or -1 (the shading normal).
  int32_t clearcoat_normal_reg = -1;
  std::vector<WeightFactor> weight;  // empty: weight 1

  Input& operator[](Param p) { return params[static_cast<size_t>(p)]; }
  const Input& operator[](Param p) const { return params[static_cast<size_t>(p)]; }
  // Blender's defaults for every Param (Principled BSDF's where the nodes differ).
  static std::array<Input, static_cast<size_t>(Param::kCount)> default_params();
};

// An AOV Output node whose name is one of the view layer's shader AOVs (Cycles' OutputAOVNode):
// its Color input for a colour AOV, its Value input for a value AOV (in value.x), written at the
// camera's first hits (integrators/data_passes.h).
struct MaterialAov {
  std::string name;
  bool color = true;
  Input value;
};

struct Material {
  std::string name;
  std::vector<Closure> closures;  // empty: black (Cycles renders an empty output black)
  // The node tree's program: evaluated once per shading point before the closures' inputs are
  // read (empty when every input is a constant or a plain image lookup).
  ShaderProgram program;
  float pass_index = 0.0f;            // Object Info's Material Index
  float cryptomatte_material = 0.0f;  // Cryptomatte ID from the name's hash (zero: none)
  std::vector<MaterialAov> aovs;

  // Single-closure materials for tests, the CLI and the built-in scenes.
  static Material diffuse(const Vec3& color, const std::string& name = "diffuse");
  static Material mirror(const Vec3& tint, const std::string& name = "mirror");
  static Material glass(float ior, const Vec3& tint = Vec3(1.0f),
                        const std::string& name = "glass");
  static Material emission(const Vec3& radiance, const std::string& name = "emission");
  // This material plus an Emission closure of radiance `radiance` (an Add Shader).
  Material with_emission(const Vec3& radiance) const;

  // Whether any closure could emit, and whether any could be non-diffuse (glossy, specular,
  // transmissive): a conservative answer without evaluating textures.
  bool may_emit() const;
  bool may_be_specular() const;
  // Whether light may pass straight through it: a Transparent closure, or a Principled alpha
  // below 1 (conservative, as may_emit). Shadow rays look through such surfaces.
  bool may_be_transparent() const;
  // Whether a closure may be anisotropic (so shading needs the UV tangent).
  bool needs_tangent() const;
};

// The range a closure input may take: Blender's socket ranges, except that emission colours and
// strengths may exceed 1 (up to a finite bound) and IOR stays positive. Constants are clamped to
// it when the material is built (sanitize_material), textured values after each lookup. Read
// from the one table of material inputs (material_params.h).
struct ParamRange {
  float lo, hi;
};
ParamRange param_range(ClosureType type, Param p);

// The range of a lamp's power (W; a sun's strength in W/m^2, both times its colour) and of the
// world's radiance: up to the brightest emission a material may have (colour x strength, each
// bounded by param_range). The bound keeps the sums a light enters finite: the largest factor a
// lamp's size adds to its radiance is 0.25 / area <= 2.5e11 for the smallest area light kept
// (1e-12 m^2) and 1 / (pi tan^2(half angle)) <= 3.2e11 for the narrowest sun, so lamp radiance
// stays under 1e24 and a pixel's sum of 2^20 samples under 1e31 (FLT_MAX is 3.4e38).
ParamRange emitter_range();

// Makes a material safe to render, whoever built it (the add-on through the Python binding, the
// CLI, tests): constants outside their Param's range are clamped and non-finite ones replaced by
// Blender's default for the closure's node; texture indices outside [0, texture_count) become the
// default constant (a normal map with such an index is dropped); normal-map strength is clamped to
// [0, 100] and mix factors to [0, 1] (0.5 when not finite). A program that names registers or
// tables outside itself is dropped (its inputs take their constants) and `warning` says why.
void sanitize_material(Material* material, size_t texture_count, std::string* warning = nullptr);
// An AOV output made safe the same way (registers checked against `register_count`): its value
// unclamped but finite.
void sanitize_aov(MaterialAov* aov, size_t texture_count, size_t register_count);

}  // namespace photon
