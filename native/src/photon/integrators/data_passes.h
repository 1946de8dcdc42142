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
//  - Denoising Normal / Albedo / Depth follow Cycles' denoising features
//    (integrators/denoising_features.h), averaged over all samples.
//  - Cryptomatte Object / Material / Asset rank the IDs of the surfaces each sample meets,
//    straight through Transparent closures, weighted by the share of the sample they take
//    (Cycles: the path throughput's average times one minus the transparency's), as
//    film/cryptomatte.h lays them out.
//  - Shader AOVs take the AOV Output nodes' values at every hit up to and including the first
//    opaque enough for the single-sample passes (Cycles' svm_node_aov_check), averaged over all
//    samples; a colour AOV's alpha is the share of samples that wrote it. The world writes its
//    own where the camera ray leaves the scene, unless the film is transparent (Cycles does not
//    evaluate the background for those rays then).
// Values depend on (seed, pixel, sample) only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "photon/film/cryptomatte.h"
#include "photon/film/pass_layout.h"
#include "photon/integrators/integrator.h"
#include "photon/render/shader_globals.h"

namespace photon {

// Accumulates the data passes of one row of pixels over its samples.
class DataPassRow {
 public:
  DataPassRow(const RenderContext& context, const DataPassSettings& settings, size_t width);
  ~DataPassRow();

  void clear();
  // Sample `sample` of pixel `i` (`pixel_index` in the full frame): the camera ray and its
  // first hit.
  void add(size_t i, int sample, uint64_t pixel_index, const Ray& ray, const CameraHit& first);
  // Writes width * data_pass_pixel_floats(settings) floats: the row's passes after `samples`
  // samples.
  void finish(int samples, float* out) const;

 private:
  // Adds the lamps that the segment of `ray` up to `t_end` meets to the Emit pass of `px`.
  void add_lamps(Ray ray, float t_end, const Vec3& throughput, float* px) const;
  // Adds the sample's denoising features to the pixel's sums.
  void add_denoising_features(float* px, int sample, uint64_t pixel_index, const Ray& ray,
                              const CameraHit& first) const;
  // Counts a surface met with `weight` into the enabled Cryptomatte rows.
  void add_cryptomatte(size_t i, const SurfaceInteraction& si, float weight);
  // Adds the shader AOVs the hit's material writes to pixel `i`.
  void add_aovs(size_t i, const SurfaceInteraction& si, const Vec3& wo, const ShadeRay& ray);
  // Adds the shader AOVs the world writes for a camera ray leaving the scene along `direction`.
  void add_world_aovs(size_t i, const Vec3& direction);
  // Adds `values` (of an owner's AOV outputs) by the (output, pass) pairs `writes`.
  void add_aov_values(size_t i, const std::vector<std::pair<int, int>>& writes, const Vec3* values);

  const RenderContext& context_;
  DataPassSettings settings_;
  size_t width_;
  int floats_;
  std::vector<float> sums_;         // width * floats_
  std::vector<float> mist_;         // per pixel: sum of (1 - m) * alpha
  std::vector<uint8_t> first_hit_;  // the first sample saw a surface
  int pixel_floats_;
  // The enabled Cryptomatte kinds in pass order (Object, Material, Asset) and their rows.
  std::vector<uint32_t> crypto_kinds_;
  std::vector<CryptomatteRow> crypto_rows_;
  // Shader AOVs: each pass's first float in a pixel's aov_floats_, and for each material that
  // writes any, (index into Material::aovs, pass) pairs.
  std::vector<int> aov_offsets_;
  int aov_floats_ = 0;
  std::unordered_map<const Material*, std::vector<std::pair<int, int>>> material_aovs_;
  std::vector<std::pair<int, int>> world_aovs_;  // the same for the world's outputs
  std::vector<float> aov_sums_;                  // width * aov_floats_
};

}  // namespace photon
