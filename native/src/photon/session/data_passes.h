// Blender's standard data passes (View Layer > Passes > Data), with the definitions of Cycles'
// film_write_data_passes (kernel/film/data_passes.h) and its film conversion:
//  - Depth, Position, Object Index and Material Index come from the first sample of a pixel
//    only; a pixel whose first sample saw no surface keeps Depth 1e10 and zeros elsewhere.
//  - Normal and UV are averaged over all samples (the background adds zero).
//  - Mist is 1 - mean((1 - m) * alpha) with m = clamp((d - start) / depth)^falloff, d the
//    distance to the camera (along the view axis for an orthographic camera).
//  - Diffuse / Glossy / Transmission Color are the summed weights of the hit's closures of that
//    kind (surface_shader_diffuse etc.), Emit its emitted radiance and that of the lamps the
//    camera sees, averaged over all samples.
// Values are taken at the camera ray's first hit, so they depend on (seed, pixel, sample) only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "photon/integrators/integrator.h"

namespace photon {

// A pass as Blender registers it: name, channel count and channel letters.
struct DataPassInfo {
  uint32_t bit;
  const char* name;
  int channels;
  const char* channel_ids;
};

// Every data pass, in the order their floats follow each other in a pixel.
const std::vector<DataPassInfo>& data_pass_table();
// Floats per pixel for the passes in `mask`.
int data_pass_floats(uint32_t mask);
// Offset of `bit`'s first float within a pixel of `mask` (-1 when `bit` is not in `mask`).
int data_pass_offset(uint32_t mask, uint32_t bit);

// Accumulates the data passes of one row of pixels over its samples.
class DataPassRow {
 public:
  DataPassRow(const RenderContext& context, const DataPassSettings& settings, size_t width);

  void clear();
  // Sample `sample` of pixel `i`: the camera ray and its first hit.
  void add(size_t i, int sample, const Ray& ray, const CameraHit& first);
  // Writes width * data_pass_floats(mask) floats: the row's passes after `samples` samples.
  void finish(int samples, float* out) const;

 private:
  // Adds the lamps that the segment of `ray` up to `t_end` meets to the Emit pass of `px`.
  void add_lamps(Ray ray, float t_end, const Vec3& throughput, float* px) const;

  const RenderContext& context_;
  DataPassSettings settings_;
  size_t width_;
  int floats_;
  std::vector<float> sums_;         // width * floats_
  std::vector<float> mist_;         // per pixel: sum of (1 - m) * alpha
  std::vector<uint8_t> first_hit_;  // the first sample saw a surface
};

}  // namespace photon
