// Shadow rays through surfaces that let light straight through: a Transparent BSDF (a window
// made as Mix(Glass, Transparent), a leaf's alpha-mapped card, Principled Alpha). Such a
// surface passes the share of light its Transparent closures weigh, unchanged in direction, so
// a shadow ray crossing it carries that share on instead of stopping (Cycles' transparent
// shadows: the shadow path multiplies its throughput by the closures' transparency at every
// surface until an opaque one blocks it or the transparent bounce limit is reached).
//
// Opaque shadow casters are found with one any-hit query (kShadowOpaque); only instances with
// a material that may be transparent (kShadowTransparent) are walked hit by hit and shaded.
// In a scene without such materials a shadow ray is exactly the any-hit query it always was.
#pragma once

#include "photon/render/accel.h"
#include "photon/render/bsdf.h"

namespace photon {

class TextureSet;

// The summed weight of a BSDF's Transparent lobes (Cycles' surface_shader_transparency): the
// share of light that passes its surface straight through.
Vec3 transparent_weight(const Bsdf& bsdf);

// The share of light that passes straight through the surface `si` travelling along
// `direction`: the summed weights of its Transparent lobes, evaluated as a shadow ray sees the
// material (Light Path's Is Shadow Ray). Black for a material that cannot be transparent.
Vec3 straight_transmittance(const Accel& accel, const TextureSet* textures,
                            const SurfaceInteraction& si, const Vec3& direction);

// `ray` moved on past the surface `si` it hit, keeping its direction and its end point.
Ray ray_past(const Ray& ray, const SurfaceInteraction& si, float length_scale);

// How many transparent surfaces a shadow ray crosses before it counts as blocked: Cycles'
// default Light Paths > Max Bounces > Transparent.
constexpr int kShadowCrossings = 8;

// What reaches the end of the shadow ray `ray` (origin to tmax): (1, 1, 1) when nothing is in
// the way, black when an opaque surface is, or when more than `max_crossings` transparent
// surfaces are, else the product of the transmittances of the surfaces crossed.
Vec3 shadow_transmittance(const Accel& accel, const TextureSet* textures, const Ray& ray,
                          int max_crossings = kShadowCrossings);

}  // namespace photon
