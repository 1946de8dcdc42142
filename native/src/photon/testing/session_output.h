// Runs a final-render session to its end the way Blender's add-on polls it, keeping what the
// tiles handed over: the image, every data pass as the last tile of each pixel left it, the
// warnings and the camera samples. For tests of how a render's rounds end (Time Limit, adaptive
// sampling).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "photon/integrators/render_settings.h"
#include "photon/scene/scene.h"

namespace photon {

struct SessionOutput {
  std::vector<float> image;  // RGBA, top row first
  // data_pass_pixel_floats(settings.data_passes) floats per pixel of the frame, in the data
  // passes' slot order; -9 where no tile wrote one.
  std::vector<float> data;
  std::vector<std::string> warnings;
  uint64_t camera_samples = 0;
};

// `settings` must render the whole frame (no border).
SessionOutput render_whole_session(std::shared_ptr<const Scene> scene,
                                   const RenderSettings& settings);

// Renders to the end and returns the mean over the rendered image's pixels of (R + G + B) / 3.
double render_mean(std::shared_ptr<const Scene> scene, const RenderSettings& settings);

}  // namespace photon
