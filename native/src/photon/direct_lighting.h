// Direct light at a Lambertian surface point: one sample of every light, plus multiple
// importance sampling (Veach 1997, power heuristic) with a cosine-distributed BSDF sample for
// lights that have an area (area lights, point and spot lights with a radius, emissive
// meshes), and a cosine-distributed sample of a uniform world.
#pragma once

#include "photon/integrator.h"

namespace photon {

// Irradiance E at `si` from every light and the world (seed 000 eq. 2.14 with f_r = albedo/pi:
// multiply by albedo / pi for the reflected radiance). `si.ng`/`si.ns` face the viewer.
Vec3 direct_irradiance(const RenderContext& context, const SurfaceInteraction& si,
                       Sampler& sampler);

}  // namespace photon
