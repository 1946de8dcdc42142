// Renders an iterative integrator (SPPM, VCM) once and keeps the image after chosen iteration
// counts, so a convergence test or benchmark reads 4, 16 and 64 iterations off one render
// instead of three. Also the image statistics the convergence tests compare with.
#pragma once

#include <string>
#include <vector>

#include "photon/integrators/integrator.h"
#include "photon/scene/scene.h"

namespace photon {

struct Checkpoint {
  int iterations = 0;
  double seconds = 0.0;     // wall time from the start of the render (scene build included)
  std::vector<float> rgba;  // the whole frame, top row first
};

// Renders the whole frame of `settings` (its integrator must be kSppm or kVcm; VCM needs a
// pinhole camera) for the largest of `iterations` and returns the image at each count.
std::vector<Checkpoint> render_checkpoints(const Scene& scene, const RenderSettings& settings,
                                           const std::vector<int>& iterations);

// An RGB image, 3 floats a pixel, top row first.
struct Rgb {
  int width = 0, height = 0;
  std::vector<float> rgb;
};

Rgb rgb_of(const std::vector<float>& rgba, int width, int height);
// Means of factor x factor blocks: a render at 1/factor the size of a box-filtered reference
// estimates exactly these means (Photon's box filter of width 1 covers its pixel).
Rgb downsample(const Rgb& image, int factor);
// sqrt(mean((a - b)^2)) / mean(b), over every channel of every pixel.
double relative_rmse(const Rgb& a, const Rgb& b);
// mean(|a - b|) / mean(b), over every channel of every pixel: unlike the RMSE, not made by the
// few pixels that see a small light through glass now and then.
double relative_mae(const Rgb& a, const Rgb& b);
// mean(a) / mean(b) - 1 over every channel.
double relative_mean_difference(const Rgb& a, const Rgb& b);
double mean_value(const Rgb& image);

}  // namespace photon
