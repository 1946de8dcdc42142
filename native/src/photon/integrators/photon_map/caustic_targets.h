// The specular objects caustic photons are aimed at (lights/photon_aim.h aims them): the
// bounding spheres of the instances that carry mirror or glass triangles.
#pragma once

#include <vector>

#include "photon/lights/lights.h"
#include "photon/render/accel.h"

namespace photon {

// Bounding spheres of the instances that carry mirror or glass triangles. More than
// `max_targets` are merged into one sphere around all of them.
std::vector<BoundingSphere> specular_targets(const Scene& scene, const Accel& accel,
                                             size_t max_targets = 64);

}  // namespace photon
