// Light carried from the lights through one refracting surface: camera paths see radiance
// unscaled through a refraction (as Cycles), so paths that carry power the other way (photons,
// VCM's light subpaths) take the adjoint BSDF's 1 / eta^2 (Bsdf::adjoint_scale), and every
// integrator renders a floor under a sheet of water alike.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "photon/render/bsdf.h"
#include "photon/render/spectral_bsdf.h"
#include "photon/scene/material_params.h"
#include "photon/testing/session_output.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace adjoint_refraction_test {
namespace {

constexpr float kIor = 1.33f;
constexpr float kAlbedo = 0.8f;
constexpr float kSunIrradiance = 2.0f;

Lobe refraction_lobe(float ior, float abbe = 0.0f) {
  Lobe l;
  l.type = LobeType::kGgxRefraction;
  l.ior = ior;
  l.abbe = abbe;
  return l;
}

TEST(AdjointScale, ARefractionScalesByTheIndicesOfItsTwoSides) {
  const Vec3 n(0.0f, 0.0f, 1.0f);
  const Vec3 wo = normalize(Vec3(0.3f, 0.0f, 1.0f)), below = normalize(Vec3(-0.2f, 0.1f, -1.0f));
  const Vec3 above = normalize(Vec3(-0.2f, 0.1f, 1.0f));
  Bsdf entering(n, n, true);
  entering.add(refraction_lobe(1.5f));
  EXPECT_FLOAT_EQ(entering.adjoint_scale(wo, below), 1.0f / (1.5f * 1.5f));
  EXPECT_FLOAT_EQ(entering.adjoint_scale(wo, above), 1.0f);  // a reflection
  Bsdf leaving(n, n, false);                                 // wo inside the glass
  leaving.add(refraction_lobe(1.5f));
  EXPECT_FLOAT_EQ(leaving.adjoint_scale(wo, below), 1.5f * 1.5f);
  // A glass lobe beside a Transparent one: the refraction still changes the medium.
  Bsdf glass(n, n, true);
  Lobe g = refraction_lobe(1.5f);
  g.type = LobeType::kGgxGlass;
  glass.add(g);
  Lobe clear;
  clear.type = LobeType::kTransparent;
  glass.add(clear);
  EXPECT_FLOAT_EQ(glass.adjoint_scale(wo, below), 1.0f / (1.5f * 1.5f));
}

TEST(AdjointScale, IsTheBtdfWithItsDirectionsSwappedOverTheBtdf) {
  // The adjoint BSDF is f*(wo, wi) = f(wi, wo): light carried from wo to wi must see what a
  // camera path from wi's side towards wo sees. For a rough refraction the ratio of the two is
  // the same 1 / eta^2 as for a sharp one (Walter et al. 2007, eq. 21 without the eta_o^2).
  // Cycles' Glass BSDF weighs its refraction by 1 - F(wo.z), which is not reciprocal: its
  // ratio strays from eta^2 by the two directions' Fresnel factors.
  const Vec3 n(0.0f, 0.0f, 1.0f);
  for (LobeType type : {LobeType::kGgxRefraction, LobeType::kGgxGlass, LobeType::kGgxDielectric})
    for (float ior : {1.33f, 1.5f, 1.0f / 1.5f})
      for (int k = 0; k < 8; ++k) {
        Lobe l = refraction_lobe(ior);
        l.type = type;
        l.alpha = 0.3f;
        Bsdf above(n, n, true), below(-n, -n, false);
        above.add(l);
        below.add(l);
        const Vec3 wo = normalize(Vec3(0.1f * k - 0.3f, 0.2f, 1.0f));
        const Vec3 wi = normalize(Vec3(0.25f - 0.05f * k, -0.1f * k, -1.0f));
        const Vec3 f = above.eval(wo, wi), f_swapped = below.eval(wi, wo);
        if (!(f.x > 1e-4f)) continue;
        const float tolerance = type == LobeType::kGgxGlass ? 0.08f : 2e-3f;
        EXPECT_NEAR(f_swapped.x / f.x, above.adjoint_scale(wo, wi),
                    tolerance * above.adjoint_scale(wo, wi))
            << static_cast<int>(type) << " ior " << ior << " k " << k;
      }
}

TEST(AdjointScale, NoScaleWhereTheMediumBehindIsNotOne) {
  const Vec3 n(0.0f, 0.0f, 1.0f);
  const Vec3 wo = normalize(Vec3(0.3f, 0.0f, 1.0f)), below = normalize(Vec3(-0.2f, 0.1f, -1.0f));
  Bsdf two_indices(n, n, true);
  two_indices.add(refraction_lobe(1.5f));
  two_indices.add(refraction_lobe(1.33f));
  EXPECT_FLOAT_EQ(two_indices.adjoint_scale(wo, below), 1.0f);
  Bsdf translucent(n, n, true);
  translucent.add(refraction_lobe(1.5f));
  Lobe t;
  t.type = LobeType::kTranslucent;
  translucent.add(t);
  EXPECT_FLOAT_EQ(translucent.adjoint_scale(wo, below), 1.0f);
  Bsdf diffuse(n, n, true);
  diffuse.add(Lobe{});
  EXPECT_FLOAT_EQ(diffuse.adjoint_scale(wo, below), 1.0f);
}

TEST(AdjointScale, ADispersiveRefractionScalesEachWavelengthByItsOwnIndex) {
  const Vec3 n(0.0f, 0.0f, 1.0f);
  const Vec3 wo = normalize(Vec3(0.3f, 0.0f, 1.0f)), below = normalize(Vec3(-0.2f, 0.1f, -1.0f));
  Bsdf bsdf(n, n, true);
  bsdf.add(refraction_lobe(1.5f, 30.0f));
  const SampledWavelengths wl = SampledWavelengths::sample_visible(0.3f);
  const SpectralBsdf spectral(bsdf, wl);
  const SampledSpectrum s = spectral.adjoint_scale(wo, below);
  for (int i = 0; i + 1 < kSpectrumSamples; ++i) {
    EXPECT_GT(s[i], 1.0f / (1.6f * 1.6f));
    EXPECT_LT(s[i], 1.0f / (1.4f * 1.4f));
    // Shorter wavelengths bend more: a larger index, a smaller scale.
    if (wl.lambda(i) < wl.lambda(i + 1)) EXPECT_LT(s[i], s[i + 1]);
    if (wl.lambda(i) > wl.lambda(i + 1)) EXPECT_GT(s[i], s[i + 1]);
  }
}

Material refraction_sheet(float roughness) {
  Closure c;
  c.type = ClosureType::kRefraction;
  c.params = default_params(ClosureType::kRefraction);
  c.sharp = roughness == 0.0f;
  c[Param::kColor] = Input::constant(Vec3(1.0f));
  c[Param::kRoughness] = Input::constant(roughness);
  c[Param::kIor] = Input::constant(kIor);
  Material m;
  m.name = "water";
  m.closures = {c};
  return m;
}

// A white floor at z = 0 under a sheet of water at z = 1 (one surface, facing up) and a sun
// straight down; the camera looks down through the sheet at the middle of the floor.
Scene floor_under_water(float roughness = 0.0f, float sun_angle = 0.0f) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(kAlbedo), "floor"));
  add_mesh_instance(&scene, make_quad({-2, -2, 0}, {4, 0, 0}, {0, 4, 0}), 0);
  scene.materials.push_back(refraction_sheet(roughness));
  add_mesh_instance(&scene, make_quad({-2, -2, 1}, {4, 0, 0}, {0, 4, 0}), 1);
  Light sun;
  sun.type = LightType::kSun;
  sun.power = kSunIrradiance;
  sun.sun_angle = sun_angle;
  scene.lights.push_back(sun);
  scene.camera = make_look_at_camera({0.0f, 0.0f, 3.0f}, {0.0f, 0.01f, 0.0f}, 0.3f, 1.0f);
  return scene;
}

double mean_image(const Scene& scene, IntegratorType integrator, bool spectral, int samples,
                  VcmMode vcm_mode = VcmMode::kVcm) {
  RenderSettings s;
  s.vcm_mode = vcm_mode;
  s.spectral = spectral;
  s.full_width = s.full_height = 8;
  s.x1 = s.y1 = 8;
  s.samples = samples;
  s.seed = 11;
  s.integrator = integrator;
  s.photons = 20000;
  s.caustic_photons = 200000;
  s.sppm_iterations = s.vcm_iterations = 64;
  s.sppm_photons_per_iteration = 20000;
  s.vcm_light_paths = 4096;
  return render_mean(std::make_shared<Scene>(scene), s);
}

// Camera paths reach the sun through the sheet inside a cone eta^2 narrower than outside, and
// see its radiance unscaled: the floor's irradiance is E / eta^2 and its radiance
// albedo E / (pi eta^2).
double expected_floor() {
  return kAlbedo * kSunIrradiance / (kPi * kIor * kIor);
}

TEST(AdjointRefraction, PhotonsThroughASheetOfWaterLightTheFloorAsCameraPathsSeeIt) {
  const Scene scene = floor_under_water();
  for (bool spectral : {false, true})
    for (IntegratorType integrator :
         {IntegratorType::kPhotonMap, IntegratorType::kSppm, IntegratorType::kVcm}) {
      const double mean = mean_image(scene, integrator, spectral, 16);
      EXPECT_NEAR(mean / expected_floor(), 1.0, 0.05)
          << "integrator " << static_cast<int>(integrator) << (spectral ? " spectral" : " rgb");
    }
}

TEST(AdjointRefraction, VcmThroughARoughSheetWeighsItsTechniquesByBothSidesDensities) {
  // Through a rough sheet the techniques of VCM reach the floor's light: camera paths that meet
  // the (wide) sun through the sheet, light sampling from camera vertices on the sheet,
  // connections to light vertices on it, merges. Their weights need the densities of sampling
  // each direction from the other side of the sheet (Bsdf::pdf_reverse): with those 0, every
  // technique overweighed itself and the floor came out 2.2x too bright.
  const Scene scene = floor_under_water(0.3f, 20.0f * kPi / 180.0f);
  const double bpt = mean_image(scene, IntegratorType::kVcm, false, 16, VcmMode::kBpt);
  const double vcm = mean_image(scene, IntegratorType::kVcm, false, 16, VcmMode::kVcm);
  EXPECT_NEAR(bpt / expected_floor(), 1.0, 0.05);
  EXPECT_NEAR(vcm / expected_floor(), 1.0, 0.05);
}

}  // namespace
}  // namespace adjoint_refraction_test
}  // namespace photon
