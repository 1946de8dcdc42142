// Camera ray generation: perspective and orthographic projections with a thin-lens aperture.
#pragma once

#include "photon/base/math.h"
#include "photon/scene/scene.h"

namespace photon {

// Generates the ray through image position (film_x, film_y) in [0, 1]^2 of the full frame
// (x to the right, y downwards). `lens_u` picks the point on the aperture. Clipping distances
// are measured along the view axis, as in Blender.
Ray generate_camera_ray(const Camera& camera, float film_x, float film_y, Vec2 lens_u);

}  // namespace photon
