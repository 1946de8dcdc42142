#include "photon/integrators/radiosity/radiosity_integrator.h"

#include <chrono>

#include "photon/integrators/camera_path.h"
#include "photon/integrators/radiosity/radiosity_material.h"
#include "photon/integrators/radiosity/radiosity_refine.h"
#include "photon/integrators/radiosity/radiosity_solver.h"
#include "photon/render/material_eval.h"

namespace photon {

void RadiosityIntegrator::prepare(const RenderContext& context, const PrepareControl& control) {
  const RenderSettings& s = *context.settings;
  stats_ = PrepareStats{};
  const auto t0 = std::chrono::steady_clock::now();
  control.report("Radiosity: meshing", 0.0f);
  // Brought into the schema's ranges here too: the integrator is also run without a session.
  RadiosityParams p = s;
  clamp_params(p, radiosity_schema(), nullptr);
  RadiosityMeshSettings mesh_settings;
  mesh_settings.patch_size = p.radiosity_patch_size;
  // The automatic patch size keeps enough rays per patch (see RadiosityMeshSettings).
  mesh_settings.rays = p.radiosity_rays;
  RadiositySolveSettings solve;
  solve.rays = p.radiosity_rays;
  solve.threshold = p.radiosity_threshold;
  solve.iterations = p.radiosity_iterations;
  solve.seed = s.seed;
  // Meshing, a first solve, refinement where the light changes, and the final solve.
  std::vector<std::string> warnings;
  RadiosityRefined refined = solve_radiosity_refined(context, mesh_settings, solve,
                                                     RadiosityRefineSettings{}, control, &warnings);
  if (control.warn)
    for (const std::string& w : warnings) control.warn(w);
  if (control.cancelled()) return;
  mesh_ = std::move(refined.mesh);
  const RadiositySolveStats& solved = refined.stats;
  std::vector<RadiosityPower>& power = refined.power;
  const double mesh_seconds =
      std::max(0.0, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() -
                        solved.seconds);
  if (solved.stopped_early && control.warn)
    control.warn("Radiosity was stopped early: rendering the solution of " +
                 std::to_string(solved.incremental_iterations) + " shooting and " +
                 std::to_string(solved.regular_iterations) + " averaged iterations");
  const auto t_field = std::chrono::steady_clock::now();
  field_ = RadiosityField(mesh_, power);
  const double field_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t_field).count();

  RadiosityStats& r = stats_.radiosity.emplace();
  r.elements = mesh_.element_count();
  r.patches = mesh_.patch_count();
  r.clusters = mesh_.cluster_count();
  r.split_patches = mesh_.split_count();
  r.first_patches = refined.first_patches;
  r.vertices = mesh_.vertex_count();
  r.patch_size = mesh_.patch_size();
  r.area = mesh_.total_area();
  r.mesh_seconds = mesh_seconds;
  r.field_seconds = field_seconds;
  r.rays = solved.rays;
  r.solve_seconds = solved.seconds;
  r.rays_per_second = solved.seconds > 0.0 ? solved.rays / solved.seconds : 0.0;
  r.shooting_iterations = solved.incremental_iterations;
  r.averaged_iterations = solved.regular_iterations;
  r.emitted_power = solved.emitted;
  r.absorbed_power = solved.absorbed;
  r.absorbed_specular_power = solved.absorbed_specular;
  r.escaped_power = solved.escaped;
  r.unshot_power = solved.unshot;
}

bool RadiosityIntegrator::reflected_radiance(const SurfaceInteraction& si, const Vec3& towards,
                                             RadiosityPower* radiance) const {
  RadiosityLocation where;
  if (field_.empty() ||
      !mesh_.locate(si.instance, si.primitive, si.barycentric.x, si.barycentric.y, &where))
    return false;
  const uint32_t side = dot(towards, mesh_.normal(where.element)) >= 0.0f ? 0u : 1u;
  const RadiosityPower b = field_.radiosity_at(where, side);
  *radiance = {b.direct * kInvPi, b.caustic * kInvPi, b.indirect * kInvPi};
  return true;
}

RadianceSample RadiosityIntegrator::radiance_from_hit(const RenderContext& context,
                                                      const Ray& camera_ray, const CameraHit& first,
                                                      Sampler& sampler) const {
  // The camera path is ray traced through glossy and specular lobes (glossy lobes also see
  // the lights directly); the diffuse lobes show the radiosity solution.
  RadianceSample result;
  trace_camera_path(
      context, camera_ray, first, sampler,
      [this](const PathVertex& v, RadianceSample* r) {
        RadiosityPower l;
        if (!reflected_radiance(*v.si, v.shading->bsdf.ng(), &l)) return;
        r->direct += v.throughput * l.direct;
        r->caustic += v.throughput * l.caustic;
        r->indirect += v.throughput * l.indirect;
      },
      &result, kLobeGlossy);
  return result;
}

bool RadiosityIntegrator::baked_radiance(const RenderContext& context, const Hit& hit,
                                         const SurfaceInteraction& si, Sampler& sampler,
                                         Vec3* radiance) const {
  (void)hit, (void)sampler;
  RadiosityPower l;
  if (!reflected_radiance(si, si.ng, &l)) return false;
  *radiance = (si.mat ? emitted_radiance(*si.mat, si, context.textures) : Vec3(0.0f)) + l.total();
  return true;
}

IntegratorInfo radiosity_integrator_info() {
  IntegratorInfo info;
  info.type = IntegratorType::kRadiosity;
  info.label = "Radiosity";
  info.description =
      "Diffuse global illumination solved once on a mesh of patches (stochastic Jacobi "
      "radiosity) and viewed from anywhere; mirrors and glass are ray traced";
  IntegratorCapabilities& c = info.capabilities;
  c.name = "RADIOSITY";
  c.prepares = true;
  c.bake = true;
  // The solver (radiosity_solver.cpp, radiosity_refine.cpp) keeps the solution so far.
  c.stop_early = true;
  c.stop_early_effect = "radiosity solve stopped, rendering the solution so far";
  c.spectral = false;
  info.make = [] { return std::unique_ptr<Integrator>(new RadiosityIntegrator); };
  return info;
}

}  // namespace photon
