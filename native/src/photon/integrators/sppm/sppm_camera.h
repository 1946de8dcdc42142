// The camera pass of one SPPM iteration at one pixel (Hachisuka & Jensen 2009, sec. 4): the
// camera path follows delta lobes and sharp glossy lobes (the shared camera walk, with emission
// and direct light by light sampling with MIS at every vertex: camera_path.h,
// direct_lighting.h) to its visible point, the first vertex with a diffuse lobe or a glossy lobe
// at least kSppmGlossyAlpha rough. There the iteration's photons within the pixel's radius are
// summed: Phi = sum beta_vp beta_j f(wo, wi_j) and M = their count (eqs. 6-8 then update the
// pixel, sppm_integrator.h).
#pragma once

#include <cstdint>

#include "photon/integrators/integrator.h"
#include "photon/integrators/sppm/photon_kdtree.h"
#include "photon/render/bsdf.h"

namespace photon {

// GGX alpha (Blender roughness 0.3, squared) from which a glossy lobe ends the camera path at a
// visible point; sharper glossy lobes are ray traced on, as mirrors are, since a density
// estimate blurs them and their few photons are noisy.
constexpr float kSppmGlossyAlpha = 0.09f;

// Whether a vertex of this BSDF is a visible point.
bool is_visible_point(const Bsdf& bsdf);

struct SppmCameraSample {
  Vec3 direct;           // emission and direct light met along the path (RadianceSample::direct)
  Vec3 phi;              // photon flux times f at the visible point, camera throughput included
  uint32_t photons = 0;  // M: photons within the radius
  bool visible_point = false;
  float alpha = 0.0f;    // as RadianceSample::alpha
  float holdout = 0.0f;  // as RadianceSample::holdout
};

// Traces the camera ray through a pixel and gathers the iteration's `photons` within `radius` of
// its visible point; a spectral path at the iteration's wavelengths `wl` when given (those of
// its photons), whose light arrives converted to Rec.709.
SppmCameraSample trace_sppm_camera(const RenderContext& context, const Ray& camera_ray,
                                   Sampler& sampler, const PhotonKdTree& photons, float radius,
                                   const SampledWavelengths* wl = nullptr);

}  // namespace photon
