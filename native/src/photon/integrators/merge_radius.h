// The gathering radius of SPPM and the merging radius of VCM measured against the picture and
// the scene. A radius is only meaningful between two scales:
//  - below a tenth of a pixel's footprint a disc gathers no sharper image (the pixel filter is
//    wider) but catches a hundredth of the photons a pixel-sized disc would, so at practical
//    photon counts the indirect light vanishes into rare fireflies;
//  - above a quarter of the scene's bounding radius the estimate blurs light across whole
//    objects and every lookup reads a large share of all photons (a render far slower and no
//    longer the scene's lighting).
// A requested radius outside that range is clamped to it, with a warning.
#pragma once

#include <string>

#include "photon/film/film.h"
#include "photon/render/render_context.h"

namespace photon {

// The median, over a grid of at most 64 x 64 pixels of the whole frame, of the distance
// between a pixel's centre ray and its right neighbour's at the depth the first sees; 0 when
// no sampled pixel sees a surface. The whole frame, not the rendered rectangle, so a band of a
// frame measures what the full frame does.
float median_pixel_footprint(const RenderContext& context, const FilmFrame& frame);

struct RadiusRange {
  float min = 0.0f, max = 0.0f;
  float scene_radius = 0.0f;  // for the warning
};

// The meaningful range for a frame whose median pixel footprint is `footprint` in a scene of
// bounding radius `scene_radius`; `automatic` (the radius the integrator picks by itself) is
// always inside it.
RadiusRange meaningful_radius_range(float footprint, float scene_radius, float automatic);

// `requested` clamped into `range`; when it had to be, `warning` says so, naming the setting.
float clamp_radius(const char* setting, float requested, const RadiusRange& range,
                   std::string* warning);

}  // namespace photon
