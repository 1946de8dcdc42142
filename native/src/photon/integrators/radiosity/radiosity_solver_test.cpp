#include "photon/integrators/radiosity/radiosity_solver.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cstring>

#include "photon/integrators/radiosity/radiosity_field.h"
#include "photon/integrators/radiosity/radiosity_integrator.h"
#include "photon/session/render_session.h"
#include "photon/testing/radiosity_test_util.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace radiosity_solver_test {
namespace {

std::vector<RadiosityPower> solve(RadiosityFixture& f, const RadiosityMesh& mesh,
                                  const RadiositySolveSettings& s, RadiositySolveStats* stats) {
  PrepareControl control;
  return solve_radiosity(f.context, mesh, s, control, stats);
}

// A closed box whose walls emit Le (emissive mesh) and reflect rho per channel: in the
// radiosity equation B = Be + rho F B with sum_j F_ij = 1, so the reflected radiance inside is
// Le rho / (1 - rho) on every wall.
TEST(RadiositySolver, ClosedEmissiveBoxConvergesToTheAnalyticValue) {
  const Vec3 rho(0.3f, 0.6f, 0.8f);
  Scene scene;
  const Material wall = Material::diffuse(rho).with_emission(Vec3(1.0f));
  scene.materials.push_back(wall);
  add_mesh_instance(&scene, make_box({-1, -1, -1}, {1, 1, 1}), 0);
  RadiosityFixture f(std::move(scene));
  const RadiosityMesh mesh = f.mesh(0.5f);  // 6 faces x 2 triangles x 9 = 108 elements
  RadiositySolveSettings s;
  s.rays = 2000000;
  RadiositySolveStats stats;
  const std::vector<RadiosityPower> power = solve(f, mesh, s, &stats);
  ASSERT_EQ(power.size(), 2 * mesh.element_count());
  const RadiosityField field(mesh, power);
  const Vec3 expected = rho / (Vec3(1.0f) - rho);
  double sum[3] = {0, 0, 0}, worst = 0.0;
  for (uint32_t e = 0; e < mesh.element_count(); ++e) {
    // make_box winds its faces outwards: the inside is the back side.
    const Vec3 l = field.element_radiosity(e, 1).total() * kInvPi;
    for (int c = 0; c < 3; ++c) {
      sum[c] += l[c];
      worst = std::max(worst, std::fabs(l[c] / expected[c] - 1.0));
    }
    const Vec3 out = field.element_radiosity(e, 0).total();
    EXPECT_TRUE(is_black(out)) << "element " << e;  // outside: nothing arrives
  }
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(sum[c] / mesh.element_count(), expected[c], 0.01 * expected[c]) << "channel " << c;
  EXPECT_LT(worst, 0.1);  // every element within 10% (the noise is about 2% rms)
  EXPECT_GE(stats.incremental_iterations, 10);  // rho = 0.8 needs ~20 steps to reach 1%
  EXPECT_EQ(stats.regular_iterations, 4);
}

// Two parallel unit squares one unit apart: an emissive one (black, two-sided, flux
// 2 pi Le A) and a receiver of albedo rho. Half the flux leaves the emitter's back side; the
// front half reaches the receiver with the analytic form factor F = 0.19982 (Cohen & Wallace
// 1993, parallel squares); the receiver reflects rho of it, of which F lands back on the
// emitter. Power must balance, and match these fractions.
TEST(RadiositySolver, PowerIsConservedAndMatchesTheFormFactor) {
  Scene scene;
  const Material emitter = Material::diffuse(Vec3(0.0f)).with_emission(Vec3(2.0f));
  const Material receiver = Material::diffuse(Vec3(0.5f));
  scene.materials = {emitter, receiver};
  add_mesh_instance(&scene, make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}), 0);
  add_mesh_instance(&scene, make_quad({0, 0, 1}, {0, 1, 0}, {1, 0, 0}), 1);
  RadiosityFixture f(std::move(scene));
  const RadiosityMesh mesh = f.mesh(0.1f);
  RadiositySolveSettings s;
  s.rays = 4000000;
  s.iterations = 0;  // the balance is kept by the incremental phase
  s.threshold = 1e-4f;
  RadiositySolveStats stats;
  solve(f, mesh, s, &stats);
  const double phi = 2.0 * kPi * 2.0;  // 2 pi Le A
  const double F = 0.19982, rho = 0.5;
  EXPECT_NEAR(stats.emitted, phi, 1e-4 * phi);
  EXPECT_NEAR(stats.absorbed + stats.absorbed_specular + stats.escaped + stats.unshot,
              stats.emitted, 1e-4 * phi);
  const double half = phi / 2;
  const double absorbed = (1 - rho) * F * half + rho * F * F * half;  // receiver + emitter
  const double escaped = phi - absorbed;
  EXPECT_NEAR(stats.absorbed, absorbed, 0.01 * absorbed);
  EXPECT_NEAR(stats.escaped, escaped, 0.005 * escaped);
  EXPECT_LT(stats.unshot, 1e-3 * phi);
}

// The solution is a function of the seed only: the same bits with 1 and 2 threads.
TEST(RadiositySolver, BitIdenticalWithOneAndTwoThreads) {
  RadiosityFixture f(make_cornell_box());
  const RadiosityMesh mesh = f.mesh(0.15f);
  RadiositySolveSettings s;
  s.rays = 300000;
  s.iterations = 2;
  std::vector<RadiosityPower> results[2];
  for (int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    RadiositySolveStats stats;
    results[threads - 1] = solve(f, mesh, s, &stats);
    EXPECT_EQ(stats.regular_iterations, 2);
  }
  ASSERT_EQ(results[0].size(), results[1].size());
  ASSERT_FALSE(results[0].empty());
  EXPECT_EQ(0, std::memcmp(results[0].data(), results[1].data(),
                           results[0].size() * sizeof(RadiosityPower)));
}

// Esc while solving keeps what was solved; cancelling returns nothing.
TEST(RadiositySolver, StopEarlyKeepsTheSolutionSoFar) {
  RadiosityFixture f(make_cornell_box());
  const RadiosityMesh mesh = f.mesh(0.2f);
  RadiositySolveSettings s;
  s.rays = 2000000;
  std::atomic<bool> stop{false}, cancel{false};
  PrepareControl control;
  control.stop_early = &stop;
  control.cancel = &cancel;
  int reports = 0;
  control.progress = [&](const std::string& status, float) {
    EXPECT_EQ(status.rfind("Radiosity: iteration ", 0), 0u) << status;
    if (++reports == 200 || status.find("iteration 3") != std::string::npos) stop = true;
  };
  RadiositySolveStats stats;
  const std::vector<RadiosityPower> power = solve_radiosity(f.context, mesh, s, control, &stats);
  EXPECT_TRUE(stats.stopped_early);
  EXPECT_GE(stats.incremental_iterations, 1);
  double total = 0.0;
  for (const RadiosityPower& p : power) total += p.total().x;
  EXPECT_GT(total, 0.0);

  stop = false;
  cancel = true;
  EXPECT_TRUE(solve_radiosity(f.context, mesh, s, control, &stats).empty());
}

// The integrator end to end: the camera inside the emissive box sees Le / (1 - rho).
TEST(RadiosityIntegrator, RendersTheClosedBoxValue) {
  Scene scene;
  const Material wall = Material::diffuse(Vec3(0.6f)).with_emission(Vec3(1.0f));
  scene.materials.push_back(wall);
  add_mesh_instance(&scene, make_box({-1, -1, -1}, {1, 1, 1}), 0);
  scene.camera = make_look_at_camera({0, -0.5f, 0}, {0, 1, 0.2f}, 1.2f, 1.0f);
  RenderSettings s;
  s.full_width = s.full_height = s.x1 = s.y1 = 16;
  s.samples = 2;
  s.integrator = IntegratorType::kRadiosity;
  s.radiosity_rays = 1000000;
  s.light_passes = true;
  RenderSession session(std::make_shared<Scene>(scene), s);
  session.start();
  session.wait();
  const std::vector<float> rgba = session.image();
  double mean = 0.0;
  for (size_t i = 0; i < rgba.size(); i += 4) mean += rgba[i];
  mean /= rgba.size() / 4;
  EXPECT_NEAR(mean, 1.0 / (1.0 - 0.6), 0.03 * 2.5);
  const std::optional<RadiosityStats>& radiosity = session.stats().integrator.radiosity;
  ASSERT_TRUE(radiosity.has_value());
  EXPECT_GT(radiosity->elements, 0u);
}

}  // namespace
}  // namespace radiosity_solver_test
}  // namespace photon

namespace photon {
namespace radiosity_solver_test {
namespace {

// Light reaches diffuse patches through the glass and mirror balls (caustics), and the power
// still balances with specular surfaces in the way.
TEST(RadiositySolver, RaysFollowMirrorsAndGlass) {
  RadiosityFixture f(make_caustic_box());
  const RadiosityMesh mesh = f.mesh(0.1f);
  RadiositySolveSettings s;
  s.rays = 1000000;
  s.iterations = 0;
  RadiositySolveStats stats;
  const std::vector<RadiosityPower> power = solve(f, mesh, s, &stats);
  double caustic = 0.0, direct = 0.0;
  for (const RadiosityPower& p : power) {
    caustic += p.caustic.x + p.caustic.y + p.caustic.z;
    direct += p.direct.x + p.direct.y + p.direct.z;
  }
  EXPECT_GT(caustic, 0.002 * direct);
  EXPECT_NEAR(stats.absorbed + stats.absorbed_specular + stats.escaped + stats.unshot,
              stats.emitted, 1e-3 * stats.emitted);
}

}  // namespace
}  // namespace radiosity_solver_test
}  // namespace photon
