// Holdouts and shadow catchers: objects that camera rays see as mattes for compositing, as
// Cycles does. Only camera rays (and rays that went on from them through Transparent BSDFs)
// see a matte; every other ray meets the object as usual, so it still casts shadows and
// reflects light onto the rest of the scene.
//
// - Holdout (a Holdout closure of weight h, or an object holdout, h = 1 minus the object's
//   transparency): the path loses h of its throughput into a hole, and the pixel's alpha drops
//   by that share (RadianceSample::holdout), whether or not the film is transparent.
// - Shadow catcher: the surface becomes a see-through filter of colour ratio = (direct light
//   with shadows) / (direct light without them), estimated with the same samples. With Film >
//   Transparent what lies behind is transparent, so alpha = 1 - ratio and colour 0 (the shadow
//   darkens a background plate when composited); otherwise the world (or whatever lies behind)
//   shows darkened by the ratio. Cycles also counts indirect light into the ratio; here only
//   direct light (lamps, emissive meshes, the world) does.
#pragma once

#include "photon/integrators/integrator.h"
#include "photon/render/material_eval.h"

namespace photon {

enum class Matte : uint8_t { kNone, kHoldout, kShadowCatcher };

// The matte flag of the instance a hit belongs to (a holdout that is also a catcher is a
// holdout).
Matte matte_at(const RenderContext& context, const Hit& hit);

// Turns the shading of an object holdout into what camera rays see of it: only its Transparent
// lobes stay (Cycles keeps an object holdout's transparency) and nothing is emitted. Returns
// the share held out, 1 - transparency, per channel.
Vec3 hold_out_object(ShadingPoint* sp);

// The shadow catcher's filter colour at `si` seen from `wo`: per channel, direct light with
// shadows over direct light without (1 where nothing lights the point), in [0, 1]. Uses the
// surface's non-delta lobes, or a white Lambertian lobe when it has none (a mirror catcher).
Vec3 shadow_catcher_ratio(const RenderContext& context, const SurfaceInteraction& si,
                          const Vec3& wo, Sampler& sampler);

}  // namespace photon
