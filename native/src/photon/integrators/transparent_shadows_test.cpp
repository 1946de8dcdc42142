// Light through surfaces that let it straight through (Transparent closures, alpha): direct
// lighting's shadow rays and BSDF rays cross them (render/shadow_ray.h), and camera paths do not
// count light met beyond such a pass-through from a non-delta bounce (path_walker.h), so a
// clear pane changes nothing and a grey one darkens by its colour, counted once.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "photon/lights/direct_lighting.h"
#include "photon/scene/material_params.h"
#include "photon/session/scene_resources.h"
#include "photon/testing/session_output.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace transparent_shadows_test {
namespace {

Material transparent(float value) {
  Closure c;
  c.type = ClosureType::kTransparent;
  c.params = default_params(ClosureType::kTransparent);
  c[Param::kColor] = Input::constant(Vec3(value));
  Material m;
  m.name = "pane";
  m.closures = {c};
  return m;
}

// Half diffuse, half rough glossy: light reaches it by light sampling and by BSDF sampling.
Material floor_material() {
  Material m = Material::diffuse(Vec3(0.6f), "floor");
  Closure glossy = Material::mirror(Vec3(0.8f)).closures[0];
  glossy.sharp = false;
  glossy[Param::kRoughness] = Input::constant(0.3f);
  m.closures[0].weight = {WeightFactor{Input::constant(0.5f), true}};
  glossy.weight = {WeightFactor{Input::constant(0.5f), false}};
  m.closures.push_back(glossy);
  return m;
}

enum class Lighting { kPointLamp, kAreaLamp, kEmissiveQuad };

// A 4 m floor at z = 0 under a light at z = 2, with (when pane >= 0) a 3 m pane at z = 1 of a
// Transparent BSDF of colour `pane` between them. The camera looks down at the floor at an
// angle, so its glossy lobe sees the light's reflection.
Scene floor_under_pane(Lighting lighting, float pane) {
  Scene scene;
  scene.materials.push_back(floor_material());
  add_mesh_instance(&scene, make_quad({-2, -2, 0}, {4, 0, 0}, {0, 4, 0}), 0);
  if (pane >= 0.0f) {
    scene.materials.push_back(transparent(pane));
    add_mesh_instance(&scene, make_quad({-1.5f, -1.5f, 1}, {3, 0, 0}, {0, 3, 0}),
                      static_cast<int32_t>(scene.materials.size() - 1));
  }
  switch (lighting) {
    case Lighting::kPointLamp:
    case Lighting::kAreaLamp: {
      Light light;
      light.type = lighting == Lighting::kPointLamp ? LightType::kPoint : LightType::kArea;
      light.power = 100.0f;
      light.size_x = light.size_y = 0.5f;
      light.light_to_world = Transform::translation(Vec3(0.0f, 0.3f, 2.0f));
      scene.lights.push_back(light);
      break;
    }
    case Lighting::kEmissiveQuad:
      scene.materials.push_back(Material::emission(Vec3(20.0f), "panel"));
      // Facing down (-z): the quad's edges wound clockwise seen from below.
      add_mesh_instance(&scene, make_quad({-0.25f, 0.05f, 2}, {0, 0.5f, 0}, {0.5f, 0, 0}),
                        static_cast<int32_t>(scene.materials.size() - 1));
      break;
  }
  scene.camera = make_look_at_camera({0.0f, -1.6f, 0.6f}, {0.0f, 0.4f, 0.0f}, 0.5f, 1.0f);
  return scene;
}

TEST(TransparentShadows, PointLampThroughAPaneIsDimmedByItsColour) {
  // A point lamp has only light samples: the same samples with and without the pane differ
  // by the pane's colour exactly.
  RenderSettings settings;
  const auto open = std::make_shared<Scene>(floor_under_pane(Lighting::kPointLamp, -1.0f));
  const auto covered = std::make_shared<Scene>(floor_under_pane(Lighting::kPointLamp, 0.25f));
  const SceneResources a(*open, settings, nullptr), b(*covered, settings, nullptr);
  EXPECT_FALSE(a.accel().has_transparent_shadows());
  EXPECT_TRUE(b.accel().has_transparent_shadows());
  for (int i = 0; i < 16; ++i) {
    SurfaceInteraction si = a.accel().interaction(Hit{});
    si.p = Vec3(-0.3f + 0.04f * i, 0.2f, 0.0f);
    si.ng = si.ns = Vec3(0.0f, 0.0f, 1.0f);
    Sampler s1(7, 0, static_cast<uint32_t>(i), 16), s2(7, 0, static_cast<uint32_t>(i), 16);
    const Vec3 e_open = direct_irradiance(a.context(), si, s1);
    const Vec3 e_covered = direct_irradiance(b.context(), si, s2);
    ASSERT_GT(e_open.x, 0.0f);
    for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(e_covered[k], 0.25f * e_open[k]);
  }
}

double mean_image(const Scene& scene, IntegratorType integrator, uint64_t seed,
                  bool spectral = false) {
  RenderSettings s;
  s.spectral = spectral;
  s.full_width = s.full_height = 16;
  s.x1 = s.y1 = 16;
  s.samples = 64;
  s.seed = seed;
  s.integrator = integrator;
  s.photons = 20000;
  s.caustic_photons = 2000;
  s.final_gather_rays = 16;
  return render_mean(std::make_shared<Scene>(scene), s);
}

std::string name_of(Lighting lighting) {
  switch (lighting) {
    case Lighting::kPointLamp:
      return "point lamp";
    case Lighting::kAreaLamp:
      return "area lamp";
    case Lighting::kEmissiveQuad:
      return "emissive quad";
  }
  return "";
}

TEST(TransparentShadows, AClearPaneChangesNothingAndAGreyOneDimsOnce) {
  // A white Transparent pane lets all light through: the image equals the one without it (light
  // counted twice, by the shadow ray and by the path through the pane, would be brighter;
  // counted by neither, darker). A pane of 0.5 halves the light from above, but not the light
  // the floor reflects to the camera below it: the image lies between half and all.
  for (IntegratorType integrator : {IntegratorType::kPhotonMap, IntegratorType::kRayTrace})
    for (Lighting lighting : {Lighting::kAreaLamp, Lighting::kEmissiveQuad}) {
      const double open = mean_image(floor_under_pane(lighting, -1.0f), integrator, 3);
      const double clear = mean_image(floor_under_pane(lighting, 1.0f), integrator, 3);
      const double grey = mean_image(floor_under_pane(lighting, 0.5f), integrator, 3);
      const std::string what =
          name_of(lighting) + ", integrator " + std::to_string(static_cast<int>(integrator));
      ASSERT_GT(open, 0.0) << what;
      EXPECT_NEAR(clear / open, 1.0, 0.03) << what;
      EXPECT_NEAR(grey / open, 0.5, 0.03) << what;
    }
}

TEST(TransparentShadows, SpectralPathsSeeThroughPanesToo) {
  // The pane's colour filters light at the path's wavelengths (a reflectance uplift).
  const Lighting lighting = Lighting::kEmissiveQuad;
  const double open =
      mean_image(floor_under_pane(lighting, -1.0f), IntegratorType::kPhotonMap, 3, true);
  const double clear =
      mean_image(floor_under_pane(lighting, 1.0f), IntegratorType::kPhotonMap, 3, true);
  const double grey =
      mean_image(floor_under_pane(lighting, 0.5f), IntegratorType::kPhotonMap, 3, true);
  ASSERT_GT(open, 0.0);
  EXPECT_NEAR(clear / open, 1.0, 0.04);
  EXPECT_NEAR(grey / open, 0.5, 0.03);
}

}  // namespace
}  // namespace transparent_shadows_test
}  // namespace photon
