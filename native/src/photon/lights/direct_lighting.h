// Direct light at a surface point: one sample of every light, plus multiple importance
// sampling (Veach 1997, power heuristic) with a BSDF sample for lights that have an area (area
// lights, point and spot lights with a radius, emissive meshes, an environment map), and a BSDF
// sample of a uniform world. Only the BSDF's non-delta lobes see direct light this way; delta lobes
// reach lights by ray tracing. Shadow rays and these BSDF rays cross surfaces that let light
// straight through (Transparent closures, alpha), taking the share they pass
// (render/shadow_ray.h); paths do not count light met after such a pass-through from a
// non-delta bounce (path_walker.h), so each light path is counted once.
#pragma once

#include "photon/base/rng.h"
#include "photon/render/accel.h"
#include "photon/render/bsdf.h"
#include "photon/render/render_context.h"
#include "photon/render/spectral_bsdf.h"

namespace photon {

// Reflected (and transmitted) radiance towards `wo` from every light and the world: the
// direct term of Jensen 2001 sec. 9.1. `bsdf`'s normals face wo.
// Only the lobes in `lobes` (diffuse and / or glossy) are lit this way.
Vec3 direct_radiance(const RenderContext& context, const SurfaceInteraction& si, const Bsdf& bsdf,
                     const Vec3& wo, Sampler& sampler, uint8_t lobes = kLobeDiffuse | kLobeGlossy);
// The same at the BSDF's wavelengths (spectral mode): the same random numbers and rays, each
// emitter's light converted to its spectrum where it is used.
SampledSpectrum direct_radiance(const RenderContext& context, const SurfaceInteraction& si,
                                const SpectralBsdf& bsdf, const Vec3& wo, Sampler& sampler,
                                uint8_t lobes = kLobeDiffuse | kLobeGlossy);

// Two estimates of direct_radiance from the same samples, one with shadow rays and one without
// (`*unshadowed`); returns the shadowed one. Light sampling only (plus a BSDF sample of a
// uniform world), no MIS, so the estimates differ exactly by the occluders' share: their ratio is
// what a shadow catcher shows (integrators/matte.h).
Vec3 direct_radiance_with_and_without_shadows(const RenderContext& context,
                                              const SurfaceInteraction& si, const Bsdf& bsdf,
                                              const Vec3& wo, Sampler& sampler, Vec3* unshadowed);

// Irradiance E at `si` (as a Lambertian surface would receive it; `si.ng`/`si.ns` face the
// side that is lit). Multiply by albedo / pi for the reflected radiance.
Vec3 direct_irradiance(const RenderContext& context, const SurfaceInteraction& si,
                       Sampler& sampler);

}  // namespace photon
