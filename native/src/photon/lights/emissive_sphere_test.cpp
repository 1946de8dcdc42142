// An emissive sphere mesh as the only light, against the irradiance of a spherical source.
//
// A sphere of radius r and radiance L whose centre is at distance d from a receiver, at angle
// theta from the receiver's normal, gives the irradiance (Snyder 1996, "Area light sources for
// real-time graphics", MSR-TR-96-11; in the form of Lagarde and de Rousiers 2014, "Moving
// Frostbite to Physically Based Rendering", sec. 4.7.2, illuminanceSphereOrDisk):
//   sin^2 sigma = (r / d)^2
//   fully above the horizon (cos^2 theta > sin^2 sigma):  E = pi L sin^2 sigma max(cos theta, 0)
//   cut by the horizon:  x = sqrt(1 / sin^2 sigma - 1), y = -x cos theta / sin theta,
//     E = L [(cos theta acos y - x sin theta sqrt(1 - y^2)) sin^2 sigma
//            + atan(sin theta sqrt(1 - y^2) / x)]
// (checked against a Monte Carlo integral of the sphere's projected solid angle to 0.3%.)
//
// The mesh is a UV sphere with vertices on the sphere. Its facets are planar (each quad of a
// UV sphere is an isosceles trapezoid), so it is a convex polyhedron between its insphere (the
// smallest distance from the centre to a facet plane, measured from the mesh) and the sphere.
// Irradiance is the integral of max(cos, 0) over the directions a convex emitter covers, which
// grows with the emitter, so the mesh's exact irradiance lies between the formula at the
// insphere radius and at r: that bracket, widened by the Monte Carlo error, is the tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "photon/lights/direct_lighting.h"
#include "photon/session/render_session.h"
#include "photon/session/scene_resources.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace emissive_sphere_test {
namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr float kRadius = 1.0f;    // sphere radius; distances below are in sphere radii
constexpr float kRadiance = 3.0f;  // emitted radiance, each channel
constexpr int kSegments = 256, kRings = 128;

// Irradiance from a sphere of radiance `radiance` (formula above).
double sphere_irradiance(double radiance, double radius, double distance, double cos_theta) {
  const double s2 = radius * radius / (distance * distance);
  cos_theta = std::clamp(cos_theta, -1.0, 1.0);
  if (cos_theta * cos_theta > s2) return radiance * kPiD * s2 * std::max(cos_theta, 0.0);
  const double sin_theta = std::sqrt(1.0 - cos_theta * cos_theta);
  const double x = std::sqrt(1.0 / s2 - 1.0);
  const double y = std::clamp(-x * cos_theta / sin_theta, -1.0, 1.0);
  const double st = sin_theta * std::sqrt(1.0 - y * y);
  return radiance * std::max(0.0, (cos_theta * std::acos(y) - x * st) * s2 + std::atan2(st, x));
}

// Smallest distance from the sphere's centre (the origin) to a facet plane of the mesh. The
// poles' slivers (vertices a float rounding apart, so not dropped as degenerate) have no
// meaningful plane and emit nothing that matters: facets under a thousandth of the mean
// area are left out.
float insphere_radius(const Mesh& mesh) {
  double total = 0.0;
  std::vector<Vec3> cross_products;
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Vec3 p0 = mesh.positions[mesh.indices[3 * t]];
    cross_products.push_back(cross(mesh.positions[mesh.indices[3 * t + 1]] - p0,
                                   mesh.positions[mesh.indices[3 * t + 2]] - p0));
    total += length(cross_products.back());
  }
  const double min_area = 1e-3 * total / std::max<size_t>(1, cross_products.size());
  float r = INFINITY;
  for (size_t t = 0; t < cross_products.size(); ++t)
    if (length(cross_products[t]) > min_area)
      r = std::min(
          r, std::fabs(dot(normalize(cross_products[t]), mesh.positions[mesh.indices[3 * t]])));
  return r;
}

// The emissive sphere at the origin, invisible to camera rays (so a camera above it sees the
// plane through it) but casting shadows, plus a diffuse receiver.
struct SphereScene {
  std::shared_ptr<Scene> scene = std::make_shared<Scene>();
  float inner_radius = 0.0f;

  explicit SphereScene(Mesh receiver) {
    scene->materials.push_back(Material::emission(Vec3(kRadiance)));
    scene->materials.push_back(Material::diffuse(Vec3(0.5f)));
    Mesh sphere = make_uv_sphere(Vec3(0.0f), kRadius, kSegments, kRings);
    add_mesh_instance(scene.get(), std::move(sphere), 0);
    scene->instances.back().visibility = kVisibleAll & ~kVisibleCamera;
    inner_radius = insphere_radius(scene->meshes.back());
    add_mesh_instance(scene.get(), std::move(receiver), 1);
  }
};

struct Estimate {
  double mean = 0.0, standard_error = 0.0;
};

// Mean and standard error of direct_irradiance (channel average) over n samples at si.
Estimate estimate_irradiance(const RenderContext& context, const SurfaceInteraction& si, int n) {
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    Sampler sampler(11, 3, static_cast<uint32_t>(i), static_cast<uint32_t>(n));
    const Vec3 e = direct_irradiance(context, si, sampler);
    const double v = (static_cast<double>(e.x) + e.y + e.z) / 3.0;
    sum += v;
    sum2 += v * v;
  }
  Estimate out;
  out.mean = sum / n;
  out.standard_error = std::sqrt(std::max(0.0, sum2 / n - out.mean * out.mean) / n);
  return out;
}

SurfaceInteraction receiver_point(const Scene& scene, const Vec3& p, const Vec3& n) {
  SurfaceInteraction si;
  si.p = p;
  si.ng = si.ns = n;
  si.mat = &scene.materials[1];
  si.material = 1;
  return si;
}

// Checks `e` against the bracket [formula at the insphere radius, formula at r] widened by
// four standard errors.
void expect_in_bracket(const Estimate& e, double lower, double upper, const char* what, float gap) {
  const double slack = 4.0 * e.standard_error;
  EXPECT_GE(e.mean, lower - slack) << what << " gap " << gap << ": " << e.mean << " +- "
                                   << e.standard_error << ", analytic " << upper;
  EXPECT_LE(e.mean, upper + slack) << what << " gap " << gap << ": " << e.mean << " +- "
                                   << e.standard_error << ", analytic " << upper;
}

constexpr float kGaps[] = {0.01f, 0.03f, 0.1f, 0.3f, 1.0f};  // surface to receiver

TEST(EmissiveSphere, IrradianceAtTheClosestPointOfAFacingPlane) {
  for (float gap : kGaps) {
    const float z = -(kRadius + gap);
    SphereScene s(make_quad({-50, -50, z}, {100, 0, 0}, {0, 100, 0}));
    RenderSettings settings;
    const SceneResources resources(*s.scene, settings, nullptr);
    const SurfaceInteraction si = receiver_point(*s.scene, Vec3(0, 0, z), Vec3(0, 0, 1));
    const Estimate e = estimate_irradiance(resources.context(), si, 50000);
    const double d = kRadius + gap;
    // The whole sphere is above the plane: E = pi L (r / d)^2.
    expect_in_bracket(e, sphere_irradiance(kRadiance, s.inner_radius, d, 1.0),
                      sphere_irradiance(kRadiance, kRadius, d, 1.0), "facing plane", gap);
  }
}

TEST(EmissiveSphere, IrradianceOnATiltedPatchWithTheSphereCutByItsHorizon) {
  // A small patch beside the sphere whose normal is 75 degrees from the sphere's direction:
  // its tangent plane cuts the sphere at every gap here (cos 75 < r / d).
  const float tilt = 75.0f * kPi / 180.0f;
  for (float gap : kGaps) {
    const float d = kRadius + gap;
    const Vec3 p(d, 0.0f, 0.0f);
    const Vec3 n(-std::cos(tilt), 0.0f, std::sin(tilt));  // towards the centre is -x
    const Frame f(n);
    const Vec3 corner = p - f.t * 0.005f - f.b * 0.005f;
    SphereScene s(make_quad(corner, f.t * 0.01f, f.b * 0.01f));
    RenderSettings settings;
    const SceneResources resources(*s.scene, settings, nullptr);
    const SurfaceInteraction si = receiver_point(*s.scene, p, n);
    const Estimate e = estimate_irradiance(resources.context(), si, 50000);
    const double cos_theta = std::cos(static_cast<double>(tilt));
    ASSERT_LT(cos_theta * cos_theta, (kRadius / d) * (kRadius / d));  // horizon-cut branch
    expect_in_bracket(e, sphere_irradiance(kRadiance, s.inner_radius, d, cos_theta),
                      sphere_irradiance(kRadiance, kRadius, d, cos_theta), "tilted patch", gap);
  }
}

// A whole render of the plane 0.3 radii below the sphere, seen from above through the sphere
// (hidden from the camera) by an orthographic camera: the plane is flat and the sphere reflects
// nothing, so every pixel is albedo / pi times the irradiance, averaged over the pixel.
void expect_plane_render_matches(IntegratorType integrator) {
  const float gap = 0.3f, z = -(kRadius + gap), half = 1.5f;
  const int size = 12;
  SphereScene s(make_quad({-50, -50, z}, {100, 0, 0}, {0, 100, 0}));
  Camera& cam = s.scene->camera;
  cam.projection = Projection::kOrthographic;
  cam.set_camera_to_world(Transform::translation(Vec3(0, 0, 5)));  // looking down -Z
  cam.window_min_x = cam.window_min_y = -half;
  cam.window_max_x = cam.window_max_y = half;
  cam.clip_start = 0.01f;
  RenderSettings settings;
  settings.full_width = settings.full_height = settings.x1 = settings.y1 = size;
  settings.samples = 256;
  settings.seed = 4;
  settings.integrator = integrator;
  settings.photons = 20000;
  settings.caustic_photons = 0;
  settings.final_gather_rays = 4;
  RenderSession session(s.scene, settings);
  session.start();
  session.wait();
  const std::vector<float> image = session.image();
  ASSERT_EQ(image.size(), static_cast<size_t>(size * size * 4));

  // The scene is symmetric about the z axis, so the image's orientation does not matter.
  const double albedo = 0.5, pixel = 2.0 * half / size;
  // Pixel noise is high (10% at 256 samples at the image's edge, where the sphere is small and
  // light samples on its far side are occluded), so pixels are compared in two groups: the
  // 4 x 4 pixels round the point closest to the sphere, and the whole image.
  double rendered_sum[2] = {0, 0}, analytic_sum[2] = {0, 0};
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      constexpr int kSub = 8;  // box filter: the mean over the pixel's square
      double e = 0.0;
      for (int b = 0; b < kSub; ++b)
        for (int a = 0; a < kSub; ++a) {
          const double x = -half + (i + (a + 0.5) / kSub) * pixel;
          const double y = -half + (j + (b + 0.5) / kSub) * pixel;
          const double d = std::sqrt(x * x + y * y + double(z) * z);
          e += sphere_irradiance(kRadiance, kRadius, d, -z / d);
        }
      const float* px = &image[4 * (static_cast<size_t>(j) * size + i)];
      const bool centre = std::abs(2 * i + 1 - size) <= 4 && std::abs(2 * j + 1 - size) <= 4;
      for (int g = 0; g < (centre ? 2 : 1); ++g) {
        rendered_sum[g] += (double(px[0]) + px[1] + px[2]) / 3.0;
        analytic_sum[g] += albedo / kPiD * e / (kSub * kSub);
      }
    }
  std::printf("rendered / analytic: image %.4f, centre %.4f\n", rendered_sum[0] / analytic_sum[0],
              rendered_sum[1] / analytic_sum[1]);
  // The analytic values are the true sphere's (the mesh is 0.03% darker); the rest is noise.
  EXPECT_NEAR(rendered_sum[0] / analytic_sum[0], 1.0, 0.015);
  EXPECT_NEAR(rendered_sum[1] / analytic_sum[1], 1.0, 0.02);
}

TEST(EmissiveSphere, RayTracedPlaneMatchesTheSphereIrradiance) {
  expect_plane_render_matches(IntegratorType::kRayTrace);
}

TEST(EmissiveSphere, PhotonMappedPlaneMatchesTheSphereIrradiance) {
  expect_plane_render_matches(IntegratorType::kPhotonMap);
}

}  // namespace
}  // namespace emissive_sphere_test
}  // namespace photon
