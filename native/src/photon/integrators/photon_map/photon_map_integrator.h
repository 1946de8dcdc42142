// Jensen's two-pass photon mapping (Jensen 1996; Jensen 2001 ch. 9). The first pass
// (prepare) traces global and caustic photons into two maps and precomputes reflected radiance
// at a subset of the global photons (Christensen 1999). The second pass splits the light
// leaving each visible diffuse point into
//   I1 direct light: light sampling with MIS (direct_lighting.h),
//   I2 specular and glossy reflection and refraction: ray traced (camera_path.h),
//   I3 caustics: a radiance estimate from the caustic map,
//   I4 indirect diffuse light: final gathering, cosine-distributed rays whose hit points read
//      the precomputed radiance; or, with final_gather_rays = 0, a direct estimate from the
//      global map (a fast preview). Where the camera sees diffuse surfaces, the final gather is
//      read from an irradiance cache built in prepare() (irradiance_cache_build.h).
#pragma once

#include "photon/integrators/camera_path.h"
#include "photon/integrators/photon_map/prepared_state_io.h"
#include "photon/integrators/pixel_integrator.h"
#include "photon/integrators/registry.h"

namespace photon {

class PhotonMapIntegrator : public PixelIntegrator {
 public:
  void prepare(const RenderContext& context, const PrepareControl& control) override;
  RadianceSample radiance_from_hit(const RenderContext& context, const Ray& camera_ray,
                                   const CameraHit& first, Sampler& sampler) const override;
  PrepareStats prepare_stats() const override;
  // A sixteenth of the photons (kCoarsePhotonShare), when that is enough photons to be worth a
  // first look of its own.
  bool coarse_settings(const RenderSettings& settings, RenderSettings* coarse) const override;
  // Every camera sample's final-gather rays, and the photons.
  uint64_t extra_rays(const RenderSettings& settings, uint64_t camera_samples) const override {
    return camera_samples * static_cast<uint64_t>(std::max(0, settings.final_gather_rays)) +
           settings.photons + settings.caustic_photons;
  }
  // The photon maps, radiance records, irradiance cache and radii (prepared_state_io.h).
  void save_prepared(PreparedStateWriter* out) const override;
  bool load_prepared(PreparedStateReader* in, std::string* error) override;
  // The light leaving a diffuse point on the side its normal faces, for lighting bakes:
  //   L = Le + albedo / pi * (E_direct + E_caustic + E_indirect)
  // with E_direct by light sampling and E_indirect by final gathering (or, with
  // final_gather_rays = 0, the global map), each averaged over settings.samples samples so the
  // bake is smooth; E_caustic from the caustic map. False for mirrors and glass.
  // E_indirect comes from an irradiance cache placed among the bake's points by prepare_bake
  // (irradiance_cache_points.h) where it covers the point, else from a final gather per sample.
  bool baked_radiance(const RenderContext& context, const Hit& hit, const SurfaceInteraction& si,
                      Sampler& sampler, Vec3* radiance) const override;
  // Emission plus the photons' radiance near the point (no ray traced): enough to tell a lit
  // side from a dark one.
  bool baked_probe(const RenderContext& context, const Hit& hit, const SurfaceInteraction& si,
                   Sampler& sampler, Vec3* radiance) const override;
  void prepare_bake(const RenderContext& context, const BakePointSet& points,
                    const PrepareControl& control) override;

 private:
  // Radiance (for albedo 1) leaving a diffuse point p with normal n: the nearest precomputed
  // record, else a small global-map estimate.
  Vec3 gathered_radiance(const Vec3& p, const Vec3& n, std::vector<PhotonNeighbor>* scratch) const;
  // Radiance reaching the origin of a final-gather ray (the integrand of the indirect term, Jensen
  // 2001 sec. 9.1), and the distance to its first hit (infinity if none). A first hit nearer than
  // secondary_distance_ is shaded by secondary_radiance instead of its record unless `primary` is
  // false (the secondary gather's own ray).
  Vec3 gather_ray(const RenderContext& context, Ray ray, Sampler& sampler,
                  std::vector<PhotonNeighbor>* scratch, float* hit_distance = nullptr,
                  bool primary = true) const;
  // Radiance (for albedo 1) leaving the diffuse point `y` towards `wo` by one more bounce: its
  // direct light by light sampling, its caustics, and one cosine-distributed gather ray.
  Vec3 secondary_radiance(const RenderContext& context, const SurfaceInteraction& y,
                          const Bsdf& bsdf, const Vec3& wo, Sampler& sampler,
                          std::vector<PhotonNeighbor>* scratch) const;
  // Reflected radiance for albedo 1 from `rays` final-gather rays; optionally the harmonic
  // mean distance of their hits. Returns early (a meaningless value) once `cancel` is set.
  Vec3 final_gather(const RenderContext& context, const SurfaceInteraction& x, const Bsdf& bsdf,
                    int rays, Sampler& sampler, float* harmonic_distance = nullptr,
                    const std::atomic<bool>* cancel = nullptr) const;
  void build_irradiance(const RenderContext& context, const PrepareControl& control);
  // Caustics and indirect light of the diffuse lobes at a camera-path vertex.
  void shade_diffuse(const RenderContext& context, const PathVertex& vertex, Sampler& sampler,
                     RadianceSample* result) const;
  void shade_diffuse_spectral(const RenderContext& context, const PathVertex& vertex,
                              Sampler& sampler, RadianceSample* result) const;
  Vec3 photon_dots(const SurfaceInteraction& x) const;

  PhotonMapPrepared state_;          // what prepare() computes for the pixels
  IrradianceCache bake_irradiance_;  // final gathers among a bake's points
  PrepareStats stats_;
};

// The coarse photon map of a first look has this many times fewer photons (and a shorter photon
// time budget, when one is set); below kMinCoarsePhotons photons it would come about as fast as
// the full map.
constexpr int kCoarsePhotonShare = 16;
constexpr uint64_t kMinCoarsePhotons = 2000;

IntegratorInfo photon_map_integrator_info();

}  // namespace photon
