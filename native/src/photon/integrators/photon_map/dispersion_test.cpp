// Dispersion through the photon map's caustic photons (spectral mode, one wavelength per
// photon): a prism spreads a narrow beam into a spectrum on a wall at the angles Snell's law
// gives with Cauchy's indices, and a glass ball's caustic keeps its power while its colours
// separate. Each test traces caustic photons only (no image), in well under a second.
#include "photon/spectral/dispersion.h"

#include <gtest/gtest.h>

#include <cmath>

#include "photon/base/optics.h"
#include "photon/integrators/photon_map/photon_tracer.h"
#include "photon/session/scene_resources.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace dispersion_test {
namespace {

struct Traced {
  std::vector<Photon> caustic;
  bool spectral = false;
};

Traced trace_caustics(const Scene& scene, uint64_t photons, bool spectral) {
  RenderSettings settings;
  std::vector<std::string> warnings;
  const SceneResources resources(scene, settings, &warnings);
  const PhotonSources sources(resources.context());
  PhotonTraceSettings trace;
  trace.global_photons = 0;
  trace.caustic_photons = photons;
  trace.seed = 11;
  trace.spectral = spectral;
  PrepareControl control;
  PhotonTraceResult r = trace_photons(resources.context(), sources, trace, control);
  return {std::move(r.caustic), r.spectral};
}

// A light of type `type` at `position` shining along `direction` (its local -Z).
Light aimed_light(LightType type, const Vec3& position, const Vec3& direction) {
  const Vec3 z = -normalize(direction);
  const Vec3 x = normalize(cross(Vec3(0.3f, 0.1f, 1.0f), z));
  const Vec3 y = cross(z, x);
  const float rows[12] = {x.x, y.x,        z.x, position.x, x.y, y.y,
                          z.y, position.y, x.z, y.z,        z.z, position.z};
  Light l;
  l.type = type;
  l.light_to_world = Transform::from_rows(rows);
  return l;
}

// An equilateral glass prism (apex up, edges along x, side kSide), a narrow spot beam meeting
// its left face at kIncidence, and a white wall at y = kWall. Looking along +x the beam goes
// right; the prism bends it down towards its base.
constexpr float kSide = 0.3f;
constexpr float kIncidence = 0.87266f;  // 50 degrees
constexpr float kWall = 2.0f;
constexpr float kIor = 1.5f;

// The left face's outward normal in (y, z) and the beam's direction: the inward normal turned up
// by the incidence angle.
Vec3 face1_normal() {
  return {0.0f, -std::sqrt(3.0f) / 2.0f, 0.5f};
}
Vec3 beam_direction() {
  const float a = -kPi / 6.0f + kIncidence;  // the inward normal points 30 degrees down
  return {0.0f, std::cos(a), std::sin(a)};
}
Vec3 beam_target() {  // the middle of the left face
  return {0.0f, -kSide / 4.0f, kSide * std::sqrt(3.0f) / 4.0f};
}

Scene prism_scene(float abbe) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.8f), "wall"));
  add_mesh_instance(&scene, make_quad({-2, kWall, -4}, {4, 0, 0}, {0, 0, 6}), 0);
  Material glass = Material::glass(kIor);
  glass.closures[0].abbe = abbe;
  scene.materials.push_back(glass);
  Mesh prism;
  const float h = kSide * std::sqrt(3.0f) / 2.0f, hx = 0.1f;
  prism.positions = {{-hx, -kSide / 2, 0}, {-hx, kSide / 2, 0}, {-hx, 0, h},
                     {hx, -kSide / 2, 0},  {hx, kSide / 2, 0},  {hx, 0, h}};
  // Outward-facing triangles: two ends, the base and the two slanted faces.
  prism.indices = {0, 2, 1, 3, 4, 5, 0, 1, 4, 0, 4, 3, 0, 3, 5, 0, 5, 2, 1, 2, 5, 1, 5, 4};
  add_mesh_instance(&scene, prism, 1);
  Light spot =
      aimed_light(LightType::kSpot, beam_target() - beam_direction() * 3.0f, beam_direction());
  spot.power = 1000.0f;
  spot.spot_size = 0.0175f;  // 1 degree: a beam about 5 cm wide at the prism
  spot.spot_blend = 0.0f;
  scene.lights.push_back(spot);
  return scene;
}

// Where the beam's central ray of wavelength `lambda` meets the wall (Snell's law at both faces
// with Cauchy's index), and the point it leaves the prism.
Vec3 analytic_hit(float abbe, float lambda, Vec3* exit) {
  const float n = spectral::CauchyDispersion::from_abbe(kIor, abbe).ior(lambda);
  const Vec3 d0 = beam_direction(), p0 = beam_target();
  const Vec3 n1 = face1_normal(), n2(0.0f, std::sqrt(3.0f) / 2.0f, 0.5f);
  Vec3 d1;
  EXPECT_TRUE(refract(-d0, n1, n, &d1));
  // Face 2 passes through (0, kSide / 2, 0) with outward normal n2.
  const Vec3 q(0.0f, kSide / 2.0f, 0.0f);
  const float t = dot(q - p0, n2) / dot(d1, n2);
  *exit = p0 + d1 * t;
  Vec3 d2;
  EXPECT_TRUE(refract(-d1, -n2, 1.0f / n, &d2));
  return *exit + d2 * ((kWall - exit->y) / d2.y);
}

struct Centroid {
  Vec3 p{0.0f};
  int count = 0;
};

// The centroid of the wall's photons of wavelength within 5 nm of `lambda` within 0.25 m of
// `around` (the beam's spot: photons reflected inside the prism land elsewhere).
Centroid wall_centroid(const Traced& t, float lambda, const Vec3& around) {
  Centroid c;
  for (const Photon& ph : t.caustic) {
    if (std::fabs(ph.pos().y - kWall) > 1e-3f || std::fabs(ph.wavelength() - lambda) > 5.0f ||
        length(ph.pos() - around) > 0.25f)
      continue;
    c.p += ph.pos();
    ++c.count;
  }
  if (c.count) c.p = c.p / static_cast<float>(c.count);
  return c;
}

// The angle at `apex` between the directions to a and b (radians).
float angle_between(const Vec3& apex, const Vec3& a, const Vec3& b) {
  return std::acos(std::clamp(dot(normalize(a - apex), normalize(b - apex)), -1.0f, 1.0f));
}

TEST(Dispersion, PrismSpreadsTheSpectrumAsSnellAndCauchySay) {
  float spread[3];
  const float abbes[3] = {0.0f, 20.0f, 40.0f};
  for (int k = 0; k < 3; ++k) {
    const float abbe = abbes[k];
    const Traced t = trace_caustics(prism_scene(abbe), 100000, true);
    ASSERT_TRUE(t.spectral);
    Vec3 exit_red, exit_blue;
    const Vec3 want_red = analytic_hit(abbe, 650.0f, &exit_red);
    const Vec3 want_blue = analytic_hit(abbe, 450.0f, &exit_blue);
    const Vec3 spot = (want_red + want_blue) * 0.5f;
    const Centroid red = wall_centroid(t, 650.0f, spot), blue = wall_centroid(t, 450.0f, spot);
    ASSERT_GT(red.count, 200) << abbe;
    ASSERT_GT(blue.count, 200) << abbe;
    const Vec3 exit = (exit_red + exit_blue) * 0.5f;
    spread[k] = angle_between(exit, red.p, blue.p);
    const float expected = angle_between(exit, want_red, want_blue);
    // Blue bends more than red: it lands lower on the wall.
    if (abbe > 0.0f) {
      EXPECT_LT(blue.p.z, red.p.z) << abbe;
      EXPECT_NEAR(spread[k], expected, 0.05f * expected) << "Abbe " << abbe;
      // The same from the prism formula (deviations at 50 degrees incidence, apex 60).
      const auto cauchy = spectral::CauchyDispersion::from_abbe(kIor, abbe);
      const double formula = spectral::prism_deviation(cauchy.ior(450.0f), kPi / 3.0, kIncidence) -
                             spectral::prism_deviation(cauchy.ior(650.0f), kPi / 3.0, kIncidence);
      EXPECT_NEAR(spread[k], formula, 0.05 * formula) << "Abbe " << abbe;
    }
    std::printf(
        "Abbe %g: red-blue angle %.4f rad (Snell + Cauchy %.4f), %d red / %d blue photons\n", abbe,
        spread[k], expected, red.count, blue.count);
  }
  // Abbe 0: no spread beyond the centroids' noise (the beam is 5 cm wide, a fraction of a
  // degree seen from the prism); Abbe 20 spreads about twice as far as Abbe 40.
  EXPECT_LT(spread[0], 0.05f * spread[2]);
  EXPECT_NEAR(spread[1] / spread[2], 2.0f, 0.2f);
}

// A glass ball (IOR 1.5, radius 0.3) over a floor, lit from above: its caustic.
Scene ball_scene(float abbe) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.8f), "floor"));
  add_mesh_instance(&scene, make_quad({-3, -3, 0}, {6, 0, 0}, {0, 6, 0}), 0);
  Material glass = Material::glass(kIor);
  glass.closures[0].abbe = abbe;
  scene.materials.push_back(glass);
  add_mesh_instance(&scene, make_uv_sphere({0, 0, 1.0f}, 0.3f, 96, 48), 1);
  Light l;
  l.type = LightType::kPoint;
  l.power = 500.0f;
  l.radius = 0.01f;
  l.light_to_world = Transform::translation(Vec3(0, 0, 4.0f));
  scene.lights.push_back(l);
  return scene;
}

struct BallCaustic {
  Vec3 power{0.0f};                             // on the floor, Rec.709
  float red_radius = 0.0f, blue_radius = 0.0f;  // mean distance from the axis, 640-660 / 440-460 nm
};

BallCaustic ball_caustic(float abbe, bool spectral) {
  const Traced t = trace_caustics(ball_scene(abbe), 100000, spectral);
  BallCaustic b;
  b.power = total_power(t.caustic, kPhotonCaustic, t.spectral);
  if (!spectral) return b;
  double red = 0, blue = 0;
  int nr = 0, nb = 0;
  for (const Photon& ph : t.caustic) {
    const float r = std::hypot(ph.pos().x, ph.pos().y), lambda = ph.wavelength();
    if (std::fabs(lambda - 650.0f) < 10.0f) red += r, ++nr;
    if (std::fabs(lambda - 450.0f) < 10.0f) blue += r, ++nb;
  }
  b.red_radius = static_cast<float>(red / std::max(nr, 1));
  b.blue_radius = static_cast<float>(blue / std::max(nb, 1));
  return b;
}

TEST(Dispersion, GlassBallCausticKeepsItsPowerAndSplitsItsColours) {
  const BallCaustic rgb = ball_caustic(0.0f, false);
  const BallCaustic plain = ball_caustic(0.0f, true);
  const BallCaustic dispersive = ball_caustic(25.0f, true);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(dispersive.power[c], plain.power[c], 0.02f * plain.power[c]) << c;
    EXPECT_NEAR(plain.power[c], rgb.power[c], 0.02f * rgb.power[c]) << c;
  }
  // Past the focus, blue (more strongly refracted) spreads wider than red; without dispersion
  // both make the same disc.
  EXPECT_GT(dispersive.blue_radius, 1.03f * dispersive.red_radius);
  EXPECT_NEAR(plain.blue_radius, plain.red_radius, 0.02f * plain.red_radius);
  std::printf(
      "caustic power RGB %.3f, spectral %.3f, dispersive %.3f (G); radii red %.3f blue %.3f "
      "(dispersive), %.3f %.3f (plain)\n",
      rgb.power.y, plain.power.y, dispersive.power.y, dispersive.red_radius, dispersive.blue_radius,
      plain.red_radius, plain.blue_radius);
}

}  // namespace
}  // namespace dispersion_test
}  // namespace photon
