// Detects a camera whose clip start cannot be made small enough for a tiny scene.
#pragma once

#include <string>

#include "photon/render/accel.h"
#include "photon/scene/camera.h"

namespace photon {

// Blender's hard minimum of Camera.clip_start (m): a scene scaled below about 1e-5 m cannot be
// framed without clipping, whatever the user types.
constexpr float kBlenderMinClipStart = 1e-6f;

// A warning (empty when none) when the camera's clip start is at Blender's minimum and still
// hides geometry: probe rays over the film find surfaces nearer than the clip start. A larger
// clip start that hides geometry is taken as intended (cutaways).
std::string camera_clip_warning(const Camera& camera, const Accel& accel);

}  // namespace photon
