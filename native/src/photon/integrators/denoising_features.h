// The denoising feature passes of one camera sample (Blender's View Layer > Passes > Denoising
// Data: Denoising Normal, Albedo and Depth), with the definitions of Cycles 3.4
// (kernel/film/denoising_passes.h, film_write_denoising_features_surface):
//  - the feature path starts at the camera and follows the sample's bounces while the
//    surfaces it meets are mostly specular (75% or more of their closures' sample weight on
//    closures with GGX alpha <= 0.075, delta lobes and Transparent), its throughput multiplied
//    by the specular closures' albedo;
//  - at the first surface that is not, Normal is the closures' normals weighted by their sample
//    weight (not normalised) in Cycles' camera space, and Albedo the throughput times the
//    albedo of the diffuse-like closures, plus the light the path met up to there (lamps the
//    rays pass, the world where they leave, the surfaces' emission) times both the feature
//    and the path throughput (film_write_emission_or_background_pass);
//  - Depth sums, over the path's segments up to there, the segment length times the average
//    throughput before it (a segment through a lamp counts from the lamp on, as in Cycles).
// Values are averaged over a pixel's samples; the background adds nothing.
#pragma once

#include "photon/integrators/integrator.h"

namespace photon {

struct DenoisingFeatures {
  Vec3 normal{0.0f};  // Cycles' camera space: +X right, +Y up, +Z forward
  Vec3 albedo{0.0f};
  float depth = 0.0f;
};

// The features of one camera sample: `ray` and its first hit, `sampler` the sample's own
// stream for the bounces the feature path takes (independent of the image's).
DenoisingFeatures trace_denoising_features(const RenderContext& context, const Ray& ray,
                                           const CameraHit& first, Sampler& sampler);

}  // namespace photon
