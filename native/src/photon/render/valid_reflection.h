#pragma once

#include "photon/base/math.h"

namespace photon {

// The shading normal Cycles gives every BSDF of a surface (svm_node_closure_bsdf turns N with
// its ensure_valid_reflection, bumped or not): a smooth, bump or normal-map normal is kept
// when the mirror reflection of the view direction about it stays above the geometric surface
// (dot(Ng, R) >= t, t = min(0.9 dot(Ng, I), 0.01)); otherwise it is turned towards Ng, in the
// plane of N and Ng, just far enough that dot(Ng, R') = t. Ng and I (towards the viewer) are
// unit vectors on the same side; N is a unit vector. Returns Ng when no such normal exists.
Vec3 ensure_valid_reflection(const Vec3& ng, const Vec3& i, const Vec3& n);

}  // namespace photon
