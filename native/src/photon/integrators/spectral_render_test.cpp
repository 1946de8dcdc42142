// Spectral mode end to end: a white furnace stays white and exact, grey scenes render as in RGB
// mode within noise for every integrator, coloured lamps and surfaces keep their colours, and the
// image does not depend on the thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "photon/integrators/spectral_path.h"
#include "photon/session/render_session.h"
#include "photon/spectral/colorimetry.h"
#include "photon/spectral/illuminants.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace spectral_render_test {
namespace {

RenderSettings settings_for(IntegratorType integrator, int size, int spp, bool spectral) {
  RenderSettings s;
  s.full_width = s.full_height = size;
  s.x1 = s.y1 = size;
  s.samples = spp;
  s.seed = 7;
  s.integrator = integrator;
  s.spectral = spectral;
  s.light_passes = true;
  s.photons = 60000;
  s.caustic_photons = 20000;
  s.final_gather_rays = 16;
  s.sppm_iterations = spp;
  s.vcm_iterations = spp;
  s.sppm_photons_per_iteration = 20000;
  s.vcm_light_paths = 20000;
  return s;
}

std::vector<float> render(const Scene& scene, const RenderSettings& s) {
  RenderSession session(std::make_shared<Scene>(scene), s);
  session.start();
  session.wait();
  return session.image();
}

Vec3 mean_rgb(const std::vector<float>& rgba) {
  double sum[3] = {0, 0, 0};
  for (size_t i = 0; i < rgba.size(); i += 4)
    for (int c = 0; c < 3; ++c) sum[c] += rgba[i + c];
  const double n = static_cast<double>(rgba.size() / 4);
  return Vec3(static_cast<float>(sum[0] / n), static_cast<float>(sum[1] / n),
              static_cast<float>(sum[2] / n));
}

Scene grey_cornell_box() {
  Scene scene = make_cornell_box();
  for (Material& m : scene.materials) m = Material::diffuse(Vec3(0.6f), m.name);
  return scene;
}

TEST(SpectralRender, WavelengthsDrawNoSamplerDimension) {
  RenderSettings s;
  s.spectral_samples = 3;
  Sampler a(1, 2, 3, 16), b(1, 2, 3, 16);
  const SampledWavelengths wl = sample_wavelengths(s, a);
  EXPECT_EQ(wl.active_count(), 3);
  EXPECT_EQ(a.get_1d(), b.get_1d());
  EXPECT_FALSE(spectral_mode(s));
  s.spectral = true;
  EXPECT_TRUE(spectral_mode(s));
  s.integrator = IntegratorType::kRadiosity;
  EXPECT_FALSE(spectral_mode(s));
}

// A sphere of albedo 0.8 under a uniform white world, seen by direct light only (ray tracing):
// every pixel on it is 0.8 in each channel (a convex object does not shadow itself), and the
// world around it 1. White is D65 in spectral mode, which comes back as white.
TEST(SpectralRender, WhiteFurnaceStaysWhite) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.8f)));
  add_mesh_instance(&scene, make_uv_sphere({0, 0, 0}, 1.0f, 64, 32), 0);
  scene.world = World::uniform(Vec3(1.0f));
  scene.camera = make_look_at_camera({0, -3.0f, 0}, {0, 0, 0}, 0.4f, 1.0f);
  for (int n : {1, 4}) {
    RenderSettings s = settings_for(IntegratorType::kRayTrace, 16, 64, true);
    s.spectral_samples = n;
    const std::vector<float> image = render(scene, s);
    // The centre 4 x 4 pixels see the sphere only.
    double sum[3] = {0, 0, 0};
    for (int y = 6; y < 10; ++y)
      for (int x = 6; x < 10; ++x)
        for (int c = 0; c < 3; ++c) sum[c] += image[(y * 16 + x) * 4 + c];
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(sum[c] / 16.0, 0.8, 0.01) << "channel " << c << " n " << n;
  }
}

// The emissive furnace (photon_map_integrator_test.cpp): walls emitting white 1 and reflecting
// 0.6 everywhere give L = 1 / (1 - 0.6) = 2.5 in every channel, photons, gathers and all.
TEST(SpectralRender, EmissiveFurnaceConvergesInSpectralMode) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.6f)).with_emission(Vec3(1.0f)));
  add_mesh_instance(&scene, make_box({-1, -1, -1}, {1, 1, 1}), 0);
  scene.camera = make_look_at_camera({0, -0.5f, 0}, {0, 1, 0.2f}, 1.2f, 1.0f);
  RenderSettings s = settings_for(IntegratorType::kPhotonMap, 16, 16, true);
  s.photons = 100000;
  const Vec3 m = mean_rgb(render(scene, s));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(m[c], 2.5, 0.08) << c;
}

// A grey scene has the same light at every wavelength: spectral and RGB renders agree within
// their noise, for each integrator that renders spectrally.
TEST(SpectralRender, GreyCornellBoxMatchesRgbForEveryIntegrator) {
  const Scene scene = grey_cornell_box();
  for (IntegratorType type : {IntegratorType::kRayTrace, IntegratorType::kPhotonMap,
                              IntegratorType::kSppm, IntegratorType::kVcm}) {
    // The iterative integrators share one set of wavelengths per iteration between all
    // pixels: their colour converges over iterations, not pixels.
    const bool iterative = type == IntegratorType::kSppm || type == IntegratorType::kVcm;
    RenderSettings s = settings_for(type, 16, iterative ? 48 : 16, false);
    s.sppm_photons_per_iteration = 5000;
    s.vcm_light_paths = 5000;
    s.photons = 30000;
    s.final_gather_rays = 8;
    const Vec3 rgb = mean_rgb(render(scene, s));
    s.spectral = true;
    const Vec3 spec = mean_rgb(render(scene, s));
    std::printf("integrator %d: RGB %.4f %.4f %.4f, spectral %.4f %.4f %.4f\n",
                static_cast<int>(type), rgb.x, rgb.y, rgb.z, spec.x, spec.y, spec.z);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(spec[c], rgb[c], 0.02f * rgb[c])
          << "integrator " << static_cast<int>(type) << " channel " << c;
  }
}

// The coloured Cornell box: spectral reflections of reflections differ a little from RGB
// products, but the walls keep their colours.
TEST(SpectralRender, ColouredCornellBoxKeepsItsColours) {
  const Scene scene = make_cornell_box();
  const Vec3 rgb = mean_rgb(render(scene, settings_for(IntegratorType::kPhotonMap, 24, 16, false)));
  const Vec3 spec = mean_rgb(render(scene, settings_for(IntegratorType::kPhotonMap, 24, 16, true)));
  std::printf("RGB %.4f %.4f %.4f, spectral %.4f %.4f %.4f\n", rgb.x, rgb.y, rgb.z, spec.x, spec.y,
              spec.z);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(spec[c], rgb[c], 0.05f * rgb[c]) << c;
}

// Lamps of a blackbody or standard illuminant spectrum: both modes render the spectrum's
// colour (RGB mode its Rec.709 chromaticity).
TEST(SpectralRender, BlackbodyLampHasItsColourInBothModes) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.5f)));
  add_mesh_instance(&scene, make_quad({-5, -5, 0}, {10, 0, 0}, {0, 10, 0}), 0);
  Light sun;
  sun.type = LightType::kSun;
  sun.power = 2.0f;
  sun.spectrum = LightSpectrum::kBlackbody;
  sun.temperature = 3000.0f;
  scene.lights.push_back(sun);
  scene.camera.projection = Projection::kOrthographic;
  scene.camera.set_camera_to_world(Transform::translation(Vec3(0, 0, 3)));
  const Vec3 chroma = spectral::blackbody_rec709_chroma(3000.0f);
  for (bool spectral : {false, true}) {
    const Vec3 m =
        mean_rgb(render(scene, settings_for(IntegratorType::kRayTrace, 8, 64, spectral)));
    // Irradiance 2 from overhead on albedo 0.5: L = 2 x 0.5 / pi, coloured by the chroma.
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(m[c], chroma[c] / kPi, 0.02f * chroma[0] / kPi) << spectral << " " << c;
  }
}

// An 800 K lamp's light lies outside the Rec.709 gamut (its colour there is 5.4, -0.20, -0.08 at
// luminance 1): its pixels averaged to negative green and blue in 70-84% of the Cornell box.
// They resolve into the gamut, as red as the gamut allows at their luminance.
TEST(SpectralRender, DeepRedLampGivesNoNegativeChannels) {
  Scene scene = make_cornell_box();
  for (Light& l : scene.lights) {
    l.spectrum = LightSpectrum::kBlackbody;
    l.temperature = 800.0f;
  }
  for (IntegratorType type : {IntegratorType::kRayTrace, IntegratorType::kPhotonMap}) {
    const std::vector<float> rgba = render(scene, settings_for(type, 24, 8, true));
    size_t negative = 0;
    for (size_t i = 0; i < rgba.size(); i += 4)
      negative += rgba[i] < 0.0f || rgba[i + 1] < 0.0f || rgba[i + 2] < 0.0f;
    EXPECT_EQ(negative, 0u) << static_cast<int>(type);
    const Vec3 m = mean_rgb(rgba);
    EXPECT_GT(m.x, 5.0f * (m.y + m.z)) << static_cast<int>(type);
  }
}

// Dispersion moves light without creating or losing any: the caustic box's image mean with a
// dispersive glass ball equals the plain ball's. A wrong weight on terminated wavelengths (the
// hero counted once per subpath instead of once per path, in SPPM's and VCM's joins) would
// change the dispersed share by a factor of 4.
TEST(SpectralRender, DispersionKeepsTheCausticBoxsLight) {
  for (IntegratorType type :
       {IntegratorType::kPhotonMap, IntegratorType::kSppm, IntegratorType::kVcm}) {
    Scene scene = make_caustic_box();
    RenderSettings s = settings_for(type, 16, type == IntegratorType::kPhotonMap ? 8 : 32, true);
    s.sppm_photons_per_iteration = 15000;
    s.vcm_light_paths = 15000;
    s.final_gather_rays = 8;
    const Vec3 plain = mean_rgb(render(scene, s));
    scene.materials[3].closures[0].abbe = 20.0f;
    const Vec3 dispersive = mean_rgb(render(scene, s));
    std::printf("integrator %d: plain %.4f %.4f %.4f, dispersive %.4f %.4f %.4f\n",
                static_cast<int>(type), plain.x, plain.y, plain.z, dispersive.x, dispersive.y,
                dispersive.z);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(dispersive[c], plain[c], 0.03f * plain[c])
          << "integrator " << static_cast<int>(type) << " channel " << c;
  }
}

TEST(SpectralRender, ImageDoesNotDependOnTheThreadCount) {
  Scene scene = make_caustic_box();
  scene.materials[3].closures[0].abbe = 25.0f;  // the glass ball disperses
  for (IntegratorType type :
       {IntegratorType::kPhotonMap, IntegratorType::kSppm, IntegratorType::kVcm}) {
    RenderSettings a = settings_for(type, 16, 4, true);
    a.threads = 1;
    RenderSettings b = a;
    b.threads = 2;
    b.tile_size = 8;
    EXPECT_EQ(render(scene, a), render(scene, b)) << static_cast<int>(type);
  }
}

}  // namespace
}  // namespace spectral_render_test
}  // namespace photon
