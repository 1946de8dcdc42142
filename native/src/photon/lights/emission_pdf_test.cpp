// The densities emitters give bidirectional estimators (emitter.h), checked against
// numeric integration: emitted rays weighted by radiance cos / (pdf_pos pdf_dir) must carry the
// emitter's power; light samples weighted by radiance cos / direct_pdf must give the irradiance
// found by quadrature over the emitter; and the densities reported for a point a camera ray
// meets must be those of the light sample and emitted ray that would have produced it.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "photon/base/sampling.h"
#include "photon/integrators/vcm/vcm_common.h"
#include "photon/lights/emissive_lights.h"
#include "photon/lights/environment.h"
#include "photon/lights/ies_profile.h"
#include "photon/lights/lights.h"
#include "photon/lights/world_light.h"
#include "photon/render/accel.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace emission_pdf_test {
namespace {

constexpr int kGrid = 256;  // strata per axis of the 2D sample grids

// A light sample with its bidirectional densities, as VCM takes one.
bool illuminate(const Emitter& e, const PhotonFrame& frame, const Vec3& p, float u_rest, Vec2 u,
                LightSample* s) {
  LightSampleU lu;
  lu.pick = u_rest;
  lu.uv = u;
  return e.sample_li(p, lu, &frame, s);
}

// What a camera ray meets of `e` with its densities, as VCM asks it: a lamp by intersection, a
// light at infinity by direction.
bool bidirectional_hit(const Emitter& e, const PhotonFrame& frame, const Ray& ray, LightHit* h) {
  if (e.flags() & kEmitterInfinite) return hit_at_infinity(e, frame, ray.direction, h);
  return e.intersect(ray, INFINITY, true, h);
}

Light make_lamp(LightType type, const Vec3& position, float power) {
  Light l;
  l.name = "lamp";
  l.type = type;
  l.light_to_world = Transform::translation(position);  // emits down world -Z
  l.power = power;
  return l;
}

// Mean over a kGrid^2 grid of u_pos and a shifted grid of u_dir of radiance cos / pdf.
Vec3 emitted_power(const Emitter& e, const PhotonFrame& frame) {
  double sum[3] = {0, 0, 0};
  int failures = 0;
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i) {
      const Vec2 u_pos((i + 0.5f) / kGrid, (j + 0.5f) / kGrid);
      // A different stratum order for the direction, so the two are not correlated.
      const Vec2 u_dir(((j * 7 + i * 3) % kGrid + 0.5f) / kGrid,
                       ((i * 5 + j * 11) % kGrid + 0.5f) / kGrid);
      const float u_rest = ((i * 13 + j * 17) % kGrid + 0.5f) / kGrid;
      EmittedPhoton s;
      if (!e.sample_le(frame, u_rest, u_pos, u_dir, true, &s)) {
        ++failures;
        continue;
      }
      EXPECT_GT(s.pdf_pos, 0.0f);
      EXPECT_GT(s.pdf_dir, 0.0f);
      const Vec3 w = s.radiance * (s.cos_light / (s.pdf_pos * s.pdf_dir));
      for (int c = 0; c < 3; ++c) sum[c] += w[c];
    }
  const double n = static_cast<double>(kGrid) * kGrid;
  return Vec3(sum[0] / n, sum[1] / n, sum[2] / n);
}

// Mean of radiance cos_receiver / direct_pdf over light samples towards p with normal n.
Vec3 sampled_irradiance(const Emitter& e, const PhotonFrame& frame, const Vec3& p, const Vec3& n) {
  double sum[3] = {0, 0, 0};
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i) {
      LightSample s;
      const float u_rest = ((i * 13 + j * 17) % kGrid + 0.5f) / kGrid;
      if (!illuminate(e, frame, p, u_rest, Vec2((i + 0.5f) / kGrid, (j + 0.5f) / kGrid), &s))
        continue;
      const float c = std::max(0.0f, dot(s.wi, n));
      const Vec3 w = s.radiance * (c / s.direct_pdf);
      for (int k = 0; k < 3; ++k) sum[k] += w[k];
    }
  const double m = static_cast<double>(kGrid) * kGrid;
  return Vec3(sum[0] / m, sum[1] / m, sum[2] / m);
}

// Irradiance at p (normal n) by midpoint quadrature over the directions of the sphere, with
// `radiance(w)` the radiance arriving from w.
double quadrature_irradiance(const Vec3& n, const std::function<double(const Vec3&)>& radiance,
                             int steps = 1024) {
  double sum = 0.0;
  for (int j = 0; j < steps; ++j) {
    const double z = 1.0 - 2.0 * (j + 0.5) / steps;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    for (int i = 0; i < 2 * steps; ++i) {
      const double phi = 2.0 * kPi * (i + 0.5) / (2 * steps);
      const Vec3 w(static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)),
                   static_cast<float>(z));
      const double c = dot(w, n);
      if (c > 0.0) sum += radiance(w) * c;
    }
  }
  return sum * (4.0 * kPi) / (2.0 * steps * steps);
}

// The densities of a camera ray that meets what illuminate_vcm sampled equal the sample's.
// (At least `min_checked` of its 64 samples must reach the receiver.)
void expect_hit_matches_sample(const Emitter& e, const PhotonFrame& frame, const Vec3& p,
                               int min_checked = 17) {
  int checked = 0;
  for (int k = 0; k < 64; ++k) {
    LightSample s;
    const Vec2 u((k % 8 + 0.5f) / 8, (k / 8 + 0.5f) / 8);
    if (!illuminate(e, frame, p, 0.37f, u, &s)) continue;
    Ray ray;
    ray.origin = p;
    ray.direction = s.wi;
    ray.tmin = 0.0f;
    ray.tmax = INFINITY;
    LightHit h;
    ASSERT_TRUE(bidirectional_hit(e, frame, ray, &h)) << k;
    float direct = h.direct_pdf;
    if (std::isfinite(s.distance)) {  // area measure to solid angle at p
      EXPECT_NEAR(h.distance, s.distance, 1e-4f * s.distance);
      direct *= s.distance * s.distance / s.cos_light;
    }
    EXPECT_NEAR(direct, s.direct_pdf, 1e-3f * s.direct_pdf) << k;
    EXPECT_NEAR(h.emission_pdf, s.emission_pdf, 1e-3f * s.emission_pdf) << k;
    EXPECT_NEAR(h.radiance.x, s.radiance.x, 1e-4f * s.radiance.x) << k;
    ++checked;
  }
  EXPECT_GE(checked, min_checked);
}

const PhotonFrame kFrame{Vec3(0.5f, -0.25f, 0.0f), 3.0f};

TEST(EmissionPdf, AreaLampsCarryTheirPowerAndSampleTheirIrradiance) {
  for (AreaShape shape : {AreaShape::kRectangle, AreaShape::kEllipse}) {
    Light l = make_lamp(LightType::kArea, Vec3(0.2f, 0.1f, 2.0f), 50.0f);
    l.shape = shape;
    l.size_x = 1.5f;
    l.size_y = 0.5f;
    const LightSet set({l}, nullptr);
    const Emitter& e = set.lamp(0);
    EXPECT_EQ(e.flags(), kEmitterBidirectional);
    const Vec3 power = e.power(kFrame.radius);
    EXPECT_NEAR(emitted_power(e, kFrame).x, power.x, 2e-3f * power.x);
    // Quadrature of the irradiance at a tilted receiver below the light.
    const Vec3 p(0.6f, -0.4f, 0.0f), n = normalize(Vec3(0.2f, 0.1f, 1.0f));
    const float area = shape == AreaShape::kRectangle ? 1.5f * 0.5f : kPi * 0.75f * 0.25f;
    const double radiance = 50.0 / (4.0 * area);
    const double expected = quadrature_irradiance(n, [&](const Vec3& w) {
      Ray ray{p, w, 0.0f, INFINITY};
      LightHit h;
      return bidirectional_hit(e, kFrame, ray, &h) ? radiance : 0.0;
    });
    EXPECT_NEAR(sampled_irradiance(e, kFrame, p, n).x, expected, 5e-3 * expected);
    expect_hit_matches_sample(e, kFrame, p);
  }
}

// Irradiance at p (normal n) from a lamp facing down world -Z with its centre at `c`, by
// midpoint quadrature over its sx x sy rectangle (an ellipse: the points inside it), with
// `radiance(w)` the radiance arriving from w. Over the lamp rather than over directions, so a
// narrow spread's footprint is resolved.
double lamp_quadrature(const Vec3& p, const Vec3& n, const Vec3& c, float sx, float sy,
                       bool ellipse, const std::function<double(const Vec3&)>& radiance,
                       int steps = 1500) {
  double sum = 0.0;
  for (int j = 0; j < steps; ++j)
    for (int i = 0; i < steps; ++i) {
      const double u = (i + 0.5) / steps - 0.5, v = (j + 0.5) / steps - 0.5;
      if (ellipse && 4.0 * (u * u + v * v) > 1.0) continue;
      const Vec3 q = c + Vec3(static_cast<float>(u * sx), static_cast<float>(v * sy), 0.0f);
      const Vec3 d = q - p;
      const double d2 = length_squared(d), dist = std::sqrt(d2);
      const Vec3 w = d / static_cast<float>(dist);
      const double cos_r = dot(w, n), cos_l = w.z;
      if (cos_r > 0.0 && cos_l > 0.0) sum += radiance(w) * cos_r * cos_l / d2;
    }
  return sum * (static_cast<double>(sx) * sy) / (static_cast<double>(steps) * steps);
}

// A spread narrows where the lamp's light goes, not how much: emitted rays still carry its
// power, light samples give the irradiance of the radiance camera rays meet, and both agree.
TEST(EmissionPdf, AreaLampsWithASpreadKeepTheirPowerAndDensities) {
  for (AreaShape shape : {AreaShape::kRectangle, AreaShape::kEllipse})
    for (float degrees : {20.0f, 60.0f}) {
      Light l = make_lamp(LightType::kArea, Vec3(0.2f, 0.1f, 2.0f), 50.0f);
      l.shape = shape;
      l.size_x = 1.5f;
      l.size_y = 0.5f;
      l.spread = degrees * kPi / 180.0f;
      const LightSet set({l}, nullptr);
      const Emitter& e = set.lamp(0);
      const Vec3 power = e.power(kFrame.radius);
      EXPECT_NEAR(emitted_power(e, kFrame).x, power.x, 3e-3f * power.x) << degrees;
      for (const Vec3& p : {Vec3(0.6f, -0.4f, 0.0f), Vec3(0.3f, 0.2f, 1.0f)}) {
        const Vec3 n = normalize(Vec3(0.2f, 0.1f, 1.0f));
        const double expected = lamp_quadrature(p, n, Vec3(0.2f, 0.1f, 2.0f), 1.5f, 0.5f,
                                                shape == AreaShape::kEllipse, [&](const Vec3& w) {
                                                  Ray ray{p, w, 0.0f, INFINITY};
                                                  LightHit h;
                                                  return bidirectional_hit(e, kFrame, ray, &h)
                                                             ? static_cast<double>(h.radiance.x)
                                                             : 0.0;
                                                });
        ASSERT_GT(expected, 0.0);
        // Light samples cover the whole lamp here (bidirectional), of which a narrow spread
        // lets a small part reach p: 256^2 of them are within 2%.
        EXPECT_NEAR(sampled_irradiance(e, kFrame, p, n).x, expected, 2e-2 * expected)
            << degrees << " at " << p.z;
        expect_hit_matches_sample(e, kFrame, p, 1);
      }
    }
}

TEST(EmissionPdf, PointAndSpotLampsFollowTheirIntensity) {
  const Vec3 pos(0.0f, 0.0f, 2.0f);
  const LightSet points({make_lamp(LightType::kPoint, pos, 80.0f)}, nullptr);
  const Emitter& point = points.lamp(0);
  EXPECT_EQ(point.flags(), kEmitterBidirectional | kEmitterDeltaPosition);
  EXPECT_NEAR(emitted_power(point, kFrame).x, 80.0f, 1e-3f * 80.0f);
  LightSample s;
  const Vec3 p(1.0f, 0.5f, 0.0f);
  ASSERT_TRUE(illuminate(point, kFrame, p, 0.5f, Vec2(0.5f, 0.5f), &s));
  EXPECT_NEAR(s.radiance.x / s.direct_pdf, 80.0f / (4.0f * kPi) / length_squared(pos - p), 1e-5f);
  EXPECT_NEAR(s.emission_pdf, 1.0f / (4.0f * kPi), 1e-7f);

  Light spot = make_lamp(LightType::kSpot, pos, 80.0f);
  spot.spot_size = 1.2f;
  spot.spot_blend = 0.3f;
  const LightSet spots({spot}, nullptr);
  const Emitter& se = spots.lamp(0);
  const Vec3 power = se.power(kFrame.radius);
  EXPECT_NEAR(emitted_power(se, kFrame).x, power.x, 3e-3f * power.x);
  // Light sample and emitted ray: the emission density is the cone's, and a receiver outside
  // the cone gets nothing.
  ASSERT_TRUE(illuminate(se, kFrame, Vec3(0.1f, 0.0f, 0.0f), 0.5f, Vec2(0.5f, 0.5f), &s));
  EXPECT_NEAR(s.emission_pdf, uniform_cone_pdf(std::cos(0.6f)), 1e-4f);
  EXPECT_FALSE(illuminate(se, kFrame, Vec3(5.0f, 0.0f, 1.9f), 0.5f, Vec2(0.5f, 0.5f), &s));
}

// A point or spot with a radius is a Lambertian sphere of radiance I / (pi r^2): its emitted
// rays carry the lamp's power, its light samples give the irradiance of the sphere a camera ray
// meets (quadrature over hit_vcm), and the densities of a hit are those of the sample.
TEST(EmissionPdf, LampsWithARadiusAreSpheres) {
  const Vec3 pos(0.0f, 0.0f, 2.0f);
  for (LightType type : {LightType::kPoint, LightType::kSpot}) {
    Light l = make_lamp(type, pos, 80.0f);
    l.radius = 0.4f;
    l.spot_size = 1.2f;
    l.spot_blend = 0.3f;
    const LightSet set({l}, nullptr);
    const Emitter& e = set.lamp(0);
    EXPECT_EQ(e.flags(), kEmitterBidirectional);
    const Vec3 power = e.power(kFrame.radius);
    EXPECT_NEAR(emitted_power(e, kFrame).x, power.x, 5e-3f * power.x);
    // Receivers near the sphere, where it covers a wide solid angle, and one beside it.
    for (const Vec3& p : {Vec3(0.3f, -0.2f, 1.0f), Vec3(0.9f, 0.4f, 0.6f)}) {
      const Vec3 n = normalize(pos - p + Vec3(0.2f, 0.0f, 0.0f));
      const double expected = quadrature_irradiance(n, [&](const Vec3& w) {
        Ray ray{p, w, 0.0f, INFINITY};
        LightHit h;
        return bidirectional_hit(e, kFrame, ray, &h) ? static_cast<double>(h.radiance.x) : 0.0;
      });
      ASSERT_GT(expected, 0.0);
      EXPECT_NEAR(sampled_irradiance(e, kFrame, p, n).x, expected, 1e-2 * expected);
      // Half the sphere faces away from a receiver, and the spot's cone takes more.
      expect_hit_matches_sample(e, kFrame, p, 8);
    }
    // Far away the sphere is the lamp of radius 0 (a receiver inside the spot's cone, facing
    // it): the same irradiance.
    const Vec3 far(0.05f, 0.0f, -18.0f);
    const Vec3 up(0.0f, 0.0f, 1.0f);
    Light point_lamp = l;
    point_lamp.radius = 0.0f;
    const LightSet points({point_lamp}, nullptr);
    const Emitter& pe = points.lamp(0);
    LightSample s;
    ASSERT_TRUE(illuminate(pe, kFrame, far, 0.5f, Vec2(0.5f, 0.5f), &s));
    const double point_irradiance = s.radiance.x / s.direct_pdf * dot(s.wi, up);
    EXPECT_NEAR(sampled_irradiance(e, kFrame, far, up).x, point_irradiance,
                5e-3 * point_irradiance);
    // Inside the sphere nothing is lit.
    EXPECT_FALSE(illuminate(e, kFrame, pos, 0.5f, Vec2(0.3f, 0.6f), &s));
  }
}

// Mean power of photons (emitted without bidirectional densities) over a grid of samples.
Vec3 photon_power(const Emitter& e, const PhotonFrame& frame) {
  double sum = 0.0;
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i) {
      const Vec2 u_pos((i + 0.5f) / kGrid, (j + 0.5f) / kGrid);
      const Vec2 u_dir(((j * 7 + i * 3) % kGrid + 0.5f) / kGrid,
                       ((i * 5 + j * 11) % kGrid + 0.5f) / kGrid);
      EmittedPhoton s;
      if (e.sample_le(frame, 0.5f, u_pos, u_dir, false, &s)) sum += s.power.x;
    }
  return Vec3(static_cast<float>(sum / (static_cast<double>(kGrid) * kGrid)));
}

// A profile brighter towards the lamp's local +X than -X, dark above 120 degrees from its -Z.
std::string skewed_profile() {
  std::ifstream f(std::string(PHOTON_IES_PROFILES) + "/skewed.ies");
  std::stringstream text;
  text << f.rdbuf();
  return text.str();
}

// An IES profile changes how much a lamp sends each way: photons and emitted rays still carry
// its power (now the profile's integral times the strength), light samples follow the
// intensity along their direction, and a sphere lamp's hits match its samples.
TEST(EmissionPdf, LampsWithAnIesProfileFollowIt) {
  const Vec3 pos(0.0f, 0.0f, 2.0f);
  std::string error;
  const std::string text = skewed_profile();
  const std::optional<IesProfile> profile = IesProfile::parse(text, &error);
  ASSERT_TRUE(profile) << error;
  // The lamp turned 90 degrees about world Y: its local -Z points along world +X.
  const float rot[12] = {0, 0, -1, pos.x, 0, 1, 0, pos.y, 1, 0, 0, pos.z};
  for (LightType type : {LightType::kPoint, LightType::kSpot})
    for (float radius : {0.0f, 0.3f}) {
      Light l = make_lamp(type, pos, 80.0f);
      l.light_to_world = Transform::from_rows(rot);
      l.radius = radius;
      l.spot_size = 2.0f;
      l.spot_blend = 0.2f;
      l.has_ies = true;
      l.ies_profile = text;
      l.ies_strength = 0.5f;
      const LightSet set({l}, nullptr);
      const Emitter& e = set.lamp(0);
      const Vec3 power = e.power(kFrame.radius);
      if (type == LightType::kPoint)
        EXPECT_NEAR(power.x, 80.0f / (4.0f * kPi) * 0.5f * profile->integral(), 1e-3f * power.x);
      EXPECT_NEAR(emitted_power(e, kFrame).x, power.x, 1e-2f * power.x) << radius;
      EXPECT_NEAR(photon_power(e, kFrame).x, power.x, 1e-2f * power.x) << radius;
      // A receiver along the lamp's axis and one off it: the intensity of the profile's
      // direction (at a distance where the radius hardly matters).
      const IesEmission ies(std::make_shared<IesProfile>(*profile), 0.5f, l.light_to_world);
      for (const Vec3& p : {Vec3(30.0f, 0.0f, 2.0f), Vec3(25.0f, 9.0f, -8.0f)}) {
        const Vec3 d = normalize(p - pos);
        double expected = 80.0f / (4.0f * kPi) * ies.factor(d) / length_squared(p - pos);
        if (type == LightType::kSpot) {
          Light bare = l;  // the spot's own falloff
          bare.has_ies = false;
          bare.radius = 0.0f;
          const LightSet plain({bare}, nullptr);
          LightSample s;
          ASSERT_TRUE(illuminate(plain.lamp(0), kFrame, p, 0.5f, Vec2(0.5f, 0.5f), &s));
          expected *=
              s.radiance.x / s.direct_pdf / (80.0f / (4.0f * kPi) / length_squared(p - pos));
        }
        const double got = sampled_irradiance(e, kFrame, p, -d).x;
        EXPECT_NEAR(got, expected, 5e-3 * expected) << radius << " at " << p.y;
      }
      if (radius > 0.0f) expect_hit_matches_sample(e, kFrame, Vec3(2.5f, 0.4f, 1.0f), 8);
    }
}

// Area lamps reading a profile per direction (Cycles 4.0+): emitted rays and photons carry the
// lamp's power, and light samples give the irradiance of the radiance camera rays meet.
TEST(EmissionPdf, AreaLampsWithAnIesProfileFollowIt) {
  const std::string text = skewed_profile();
  for (float spread : {kPi, 1.2f}) {
    Light l = make_lamp(LightType::kArea, Vec3(0.2f, 0.1f, 2.0f), 50.0f);
    l.size_x = 1.5f;
    l.size_y = 0.5f;
    l.spread = spread;
    l.has_ies = true;
    l.ies_profile = text;
    l.ies_strength = 0.3f;
    const LightSet set({l}, nullptr);
    const Emitter& e = set.lamp(0);
    const Vec3 power = e.power(kFrame.radius);
    EXPECT_NEAR(emitted_power(e, kFrame).x, power.x, 5e-3f * power.x) << spread;
    EXPECT_NEAR(photon_power(e, kFrame).x, power.x, 5e-3f * power.x) << spread;
    const Vec3 p(0.9f, -0.6f, 0.0f), n = normalize(Vec3(0.2f, 0.1f, 1.0f));
    const double expected =
        lamp_quadrature(p, n, Vec3(0.2f, 0.1f, 2.0f), 1.5f, 0.5f, false, [&](const Vec3& w) {
          Ray ray{p, w, 0.0f, INFINITY};
          LightHit h;
          return bidirectional_hit(e, kFrame, ray, &h) ? static_cast<double>(h.radiance.x) : 0.0;
        });
    ASSERT_GT(expected, 0.0);
    EXPECT_NEAR(sampled_irradiance(e, kFrame, p, n).x, expected, 1e-2 * expected) << spread;
    expect_hit_matches_sample(e, kFrame, p, 8);
  }
}

TEST(EmissionPdf, SunBeamCarriesIrradianceOverTheSceneDisc) {
  for (float angle : {0.0f, 1.0f}) {
    Light l = make_lamp(LightType::kSun, Vec3(0.0f), 3.0f);
    l.sun_angle = angle;
    const LightSet set({l}, nullptr);
    const Emitter& e = set.lamp(0);
    EXPECT_EQ((e.flags() & kEmitterDeltaDirection) != 0, angle == 0.0f);
    const float power = 3.0f * kPi * kFrame.radius * kFrame.radius;
    EXPECT_NEAR(emitted_power(e, kFrame).x, power, 1e-3f * power);
    // A receiver facing the sun gets its irradiance (cos of the cone's directions aside).
    const Vec3 n(0.0f, 0.0f, 1.0f);
    const double expected = angle == 0.0f ? 3.0
                                          : 3.0 * uniform_cone_pdf(std::cos(0.5f)) *
                                                quadrature_irradiance(n, [&](const Vec3& w) {
                                                  return dot(w, n) >= std::cos(0.5f) ? 1.0 : 0.0;
                                                });
    EXPECT_NEAR(sampled_irradiance(e, kFrame, Vec3(0.0f), n).x, expected, 5e-3 * expected);
    if (angle > 0.0f) expect_hit_matches_sample(e, kFrame, Vec3(0.0f));
  }
}

TEST(EmissionPdf, UniformWorldAndEnvironmentMap) {
  const WorldEmitter world(Vec3(0.7f));
  EXPECT_NEAR(emitted_power(world, kFrame).x, world.power(kFrame.radius).x,
              1e-3f * world.power(kFrame.radius).x);
  const Vec3 n = normalize(Vec3(0.3f, -0.2f, 1.0f));
  EXPECT_NEAR(sampled_irradiance(world, kFrame, Vec3(0.0f), n).x, 0.7f * kPi, 5e-3f);
  expect_hit_matches_sample(world, kFrame, Vec3(0.0f));

  // A bright band and a dim rest: the table's density, its hit density and its emitted power.
  const auto sky = [](const Vec3& w) { return Vec3(w.z > 0.8f ? 5.0f : 0.2f); };
  const EnvironmentEmitter env(sky, 64);
  // pi R^2 times the integral of the radiance over the sphere (the table's own estimate,
  // power(), rounds the band's edges up).
  const float power =
      kPi * kFrame.radius * kFrame.radius * 2.0f * kPi * (5.0f * 0.2f + 0.2f * 1.8f);
  EXPECT_NEAR(emitted_power(env, kFrame).x, power, 1e-2f * power);
  const Vec3 up(0.0f, 0.0f, 1.0f);
  const double expected = quadrature_irradiance(up, [&](const Vec3& w) { return sky(w).x; });
  EXPECT_NEAR(sampled_irradiance(env, kFrame, Vec3(0.0f), up).x, expected, 1e-2 * expected);
  expect_hit_matches_sample(env, kFrame, Vec3(0.0f));
  // The direction density integrates to one over the sphere (both hemispheres, the cosine
  // that quadrature_irradiance weighs by divided out).
  double total = 0.0;
  for (const Vec3& axis : {up, -up})
    total += quadrature_irradiance(axis, [&](const Vec3& w) {
      Ray ray{Vec3(0.0f), w, 0.0f, INFINITY};
      LightHit h;
      return bidirectional_hit(env, kFrame, ray, &h) ? h.direct_pdf / std::fabs(w.z) : 0.0;
    });
  EXPECT_NEAR(total, 1.0, 0.01);
}

TEST(EmissionPdf, EmissiveTrianglesAloneAndAsAGroup) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.0f)).with_emission(Vec3(2.0f)));
  scene.materials.push_back(Material::diffuse(Vec3(0.0f)).with_emission(Vec3(6.0f)));
  add_mesh_instance(&scene, make_quad({-1, -1, 2}, {1, 0, 0}, {0, 1, 0}), 0);
  add_mesh_instance(&scene, make_quad({0.5f, 0, 1.5f}, {0.5f, 0, 0.3f}, {0, 0.7f, 0}), 1);
  std::vector<std::string> warnings;
  const Accel accel(scene, &warnings);
  const EmissiveMeshes meshes(scene, accel);
  ASSERT_EQ(meshes.size(), 4u);
  const EmissiveGroupEmitter group(meshes);
  const Vec3 power = group.power(1.0f);
  EXPECT_NEAR(emitted_power(group, kFrame).x, power.x, 2e-3f * power.x);
  const TriangleEmitter one(meshes, 2);
  EXPECT_NEAR(emitted_power(one, kFrame).x, one.power(1.0f).x, 2e-3f * one.power(1.0f).x);

  // Irradiance at a receiver: light samples against quadrature over directions, the group's
  // triangles found by tracing the scene.
  const Vec3 p(0.1f, 0.2f, 0.0f), n(0.0f, 0.0f, 1.0f);
  const double expected = quadrature_irradiance(n, [&](const Vec3& w) {
    Hit hit;
    if (!accel.intersect(Ray{p, w, 0.0f, INFINITY}, kVisibleDiffuse, &hit)) return 0.0;
    return meshes.triangle(meshes.find(hit.instance, hit.primitive)).radiance.x * 1.0;
  });
  EXPECT_NEAR(sampled_irradiance(group, kFrame, p, n).x, expected, 5e-3 * expected);
  // A camera ray meeting a triangle: its densities are the light sample's.
  for (int k = 0; k < 32; ++k) {
    LightSample s;
    ASSERT_TRUE(illuminate(group, kFrame, p, (k + 0.5f) / 32, Vec2(0.3f, 0.6f), &s));
    Hit hit;
    ASSERT_TRUE(accel.intersect(Ray{p, s.wi, 0.0f, INFINITY}, kVisibleDiffuse, &hit));
    LightHit h;
    const float cos_light = dot(s.wi, s.surface_normal);
    ASSERT_TRUE(group.surface_hit(hit.instance, hit.primitive, hit.t, cos_light, true, &h));
    EXPECT_NEAR(h.direct_pdf * s.distance * s.distance / s.cos_light, s.direct_pdf,
                1e-3f * s.direct_pdf);
    EXPECT_NEAR(h.emission_pdf, s.emission_pdf, 1e-3f * s.emission_pdf);
  }
}

}  // namespace
}  // namespace emission_pdf_test
}  // namespace photon
