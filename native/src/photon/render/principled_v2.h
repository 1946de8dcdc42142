// Blender 4.0+'s Principled BSDF (v2) as Cycles 4 renders it (intern/cycles/kernel/svm/
// closure.h, CLOSURE_BSDF_PRINCIPLED_ID): layers from the top down, each attenuating what lies
// below it by its own albedo seen from wo:
//   alpha       a Transparent lobe of weight 1 - alpha; the rest scales by alpha.
//   coat        GGX reflection with the exact dielectric Fresnel of Coat IOR (same on both sides),
//               weight Coat Weight, on the Coat Normal; below it the weight shrinks by
//               1 - coat_weight F(cos_o) (its smooth-surface albedo) and is tinted by
//               mix(1, Coat Tint^(1 / cos_t), coat_weight): Beer's law through a coat of unit
//               thickness along the refracted view direction (cos_t from Snell's law).
//   emission    Emission Color x Strength x the weight below sheen and coat.
//   metallic    GGX reflection with the F82-tint conductor Fresnel (F0 = Base Color, edge tint =
//               Specular Tint), weight Metallic; the rest scales by 1 - Metallic.
//   transmission one GGX dielectric lobe (Fresnel per microfacet, "real Fresnel remapped to
//               F0..1" with F0 = F0(IOR) Specular Tint; refraction tinted by sqrt(Base Color)),
//               weight Transmission Weight; the rest scales by 1 - Transmission Weight.
//   specular    GGX dielectric reflection of IOR eta whose F0 is Specular IOR Level x 2 x F0(IOR)
//               (level 0.5: the IOR's own), tinted at normal incidence by Specular Tint; below it
//               the weight shrinks by 1 - max(its directional albedo) (a table over roughness,
//               cos_o and eta).
//   diffuse     Lambert of Base Color, or at Diffuse Roughness > 0 Cycles 4.3's energy-preserving
//               Oren-Nayar of that sigma (render/bsdf_lobes.h oren_nayar) (Subsurface Weight's
//               share too: Photon has no subsurface scattering and renders it as diffuse, which
//               the add-on says).
// With the Multiscatter GGX distribution each of metallic, transmission and specular is scaled
// up by the energy single scattering loses, 1 + F_ms (1 - E(cos_o)) / E(cos_o) (Kulla & Conty
// 2017 as Cycles applies it: microfacet_albedo.h). Microfacet lobes use the height-correlated
// Smith G. Anisotropy: alpha_x = r^2 / aspect, alpha_y = r^2 aspect, aspect = sqrt(1 - 0.9
// Anisotropic), along the tangent turned by Anisotropic Rotation turns.
//
// Not rendered (the add-on warns): Sheen (Cycles' microfiber sheen), Thin Film, subsurface
// scattering itself.
#pragma once

#include "photon/base/math.h"
#include "photon/render/bsdf.h"

namespace photon {

// A Principled v2 closure's inputs at a shading point, already read and clamped.
struct PrincipledV2Inputs {
  Vec3 base_color{0.8f};
  float metallic = 0.0f;
  float roughness = 0.5f;
  float ior = 1.5f;
  float alpha = 1.0f;
  float subsurface = 0.0f;
  float diffuse_roughness = 0.0f;  // Oren-Nayar sigma of the diffuse layer (0: Lambert)
  float specular_ior_level = 0.5f;
  Vec3 specular_tint{1.0f};
  float anisotropic = 0.0f;
  float anisotropic_rotation = 0.0f;  // turns
  float transmission = 0.0f;
  float coat_weight = 0.0f;
  float coat_roughness = 0.03f;
  float coat_ior = 1.5f;
  Vec3 coat_tint{1.0f};
  Vec3 emission{1.0f};
  float emission_strength = 0.0f;
  bool multiscatter = true;  // the node's distribution is Multiscatter GGX (its default)
  float abbe = 0.0f;         // Photon's dispersion of the transmission (0: none)
};

// Where the closure shades, in the BSDF's orientation (normals facing wo).
struct PrincipledV2Geometry {
  Vec3 wo;                 // towards the viewer, unit length
  Vec3 n;                  // the closure's shading normal
  Vec3 lobe_n{0.0f};       // n when it differs from the BSDF's normal, else zero (Lobe::normal)
  Vec3 coat_n;             // the coat's normal
  Vec3 coat_lobe_n{0.0f};  // coat_n when it differs from the BSDF's normal, else zero
  Vec3 tangent{0.0f};      // the anisotropy's tangent before rotation, or zero (isotropic)
  bool front = true;       // wo is on the outward side (the IOR is not inverted)
};

// Adds the lobes of a Principled v2 closure of weight `w` to `bsdf` and returns its emitted
// radiance (the weight below coat and sheen times Emission Color x Strength). `bsdf` may be null
// to compute the emission alone.
Vec3 add_principled_v2(const PrincipledV2Inputs& in, float w, const PrincipledV2Geometry& geo,
                       Bsdf* bsdf);

// The parts of the model the tests check on their own.
namespace principled_v2 {
// A dielectric's reflectance at normal incidence, ((ior - 1) / (ior + 1))^2.
float f0_from_ior(float ior);
// The IOR of the specular layer: the one whose F0 is 2 x level x F0(ior) (level 0.5: ior).
float specular_eta(float ior, float level);
// The F82-tint conductor's multiple-scattering Fresnel average F_ss (Kulla & Conty's
// hemispherical average of F, in closed form for this model).
Vec3 f82_average(const Vec3& f0, const Vec3& tint);
// Albedo scaling's factor 1 + F_ms (1 - E) / E for single-scattering albedo E, its average
// E_avg and the Fresnel average F_ss.
Vec3 multiscatter_factor(float e, float e_avg, const Vec3& f_ss);
}  // namespace principled_v2

}  // namespace photon
