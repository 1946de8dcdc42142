// Integrator RADIOSITY: a view-independent diffuse solution computed once in prepare()
// (meshing: radiosity_mesh.h; stochastic Jacobi solver: radiosity_solver.h), then displayed:
// camera rays follow mirrors and glass (camera_path.h) to a diffuse point and read its
// Gouraud-interpolated radiosity, L = B / pi (radiosity_field.h). Emission met on the way is
// added as in the other integrators. Light passes: Direct = emission plus light reflected
// straight from the lights; Caustics = light that reached the surface from a light through
// mirrors/glass; Indirect = light after at least one diffuse bounce.
#pragma once

#include "photon/integrators/pixel_integrator.h"
#include "photon/integrators/radiosity/radiosity_field.h"
#include "photon/integrators/radiosity/radiosity_mesh.h"
#include "photon/integrators/registry.h"

namespace photon {

class RadiosityIntegrator : public PixelIntegrator {
 public:
  void prepare(const RenderContext& context, const PrepareControl& control) override;
  PrepareStats prepare_stats() const override { return stats_; }
  uint64_t extra_rays(const RenderSettings& settings, uint64_t) const override {
    return settings.radiosity_rays;
  }
  RadianceSample radiance_from_hit(const RenderContext& context, const Ray& camera_ray,
                                   const CameraHit& first, Sampler& sampler) const override;
  // Emission plus the interpolated radiosity / pi on the side of the surface `si.ng` faces.
  bool baked_radiance(const RenderContext& context, const Hit& hit, const SurfaceInteraction& si,
                      Sampler& sampler, Vec3* radiance) const override;

  // Reflected radiance (B / pi) at a hit, seen from side `towards` of the surface; false when
  // the hit is not on a diffuse element.
  bool reflected_radiance(const SurfaceInteraction& si, const Vec3& towards,
                          RadiosityPower* radiance) const;

 private:
  RadiosityMesh mesh_;
  RadiosityField field_;
  PrepareStats stats_;
};

IntegratorInfo radiosity_integrator_info();

}  // namespace photon
