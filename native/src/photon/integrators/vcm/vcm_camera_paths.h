// VCM's camera subpaths (Georgiev et al. 2012 sec. 5; Davidovic et al. 2012, the camera half of
// the recursive MIS quantities and the weights of every strategy): one per pixel and iteration,
// through the pixel filter's importance sample. At each vertex it adds emission it meets
// (weighed against light sampling and light subpaths), and at each connectible vertex next-event
// estimation, connections to the vertices of one light subpath, and merging with every light
// vertex of the iteration within the radius.
#pragma once

#include "photon/integrators/vcm/vcm_camera_model.h"
#include "photon/integrators/vcm/vcm_grid.h"
#include "photon/integrators/vcm/vcm_light_paths.h"

namespace photon {

struct VcmCameraSample {
  Vec3 radiance{0.0f};
  float alpha = 0.0f;  // 1 when the camera ray met a surface
};

// The sample of pixel (px, py) of the full frame. `light_path` is the subpath it connects to;
// `colours` the iteration's wavelengths in spectral mode (those of the light subpaths).
VcmCameraSample trace_vcm_camera_path(const RenderContext& context, const VcmLights& lights,
                                      const VcmCamera& camera, const VcmMis& mis,
                                      const VcmLightPass& pass, uint64_t light_path,
                                      const VcmGrid& grid, int px, int py, Sampler& sampler,
                                      const VcmColours& colours = VcmColours{});

}  // namespace photon
