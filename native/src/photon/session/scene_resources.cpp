#include "photon/session/scene_resources.h"

#include <algorithm>
#include <cstdio>
#include <set>
#include <string>

#include "photon/integrators/registry.h"
#include "photon/lights/environment.h"
#include "photon/lights/portals.h"
#include "photon/render/material_eval.h"
#include "photon/render/world_shader.h"

namespace photon {
namespace {

// One warning per material input whose texture holds values outside the input's range: they
// are clamped after each lookup, as constants are when the material is built.
void warn_out_of_range(const Scene& scene, const TextureSet& textures,
                       std::vector<std::string>* warnings) {
  if (!warnings) return;
  std::set<std::pair<size_t, std::string>> reported;
  for (size_t m = 0; m < scene.materials.size(); ++m)
    for (const Closure& c : scene.materials[m].closures)
      for (size_t k = 0; k < c.params.size(); ++k) {
        const Input& in = c.params[k];
        if (!textures.valid(in.texture)) continue;
        const Param p = static_cast<Param>(k);
        const ParamRange r = param_range(c.type, p);
        const float top = in.channel == TextureChannel::kAlpha ? textures.max_alpha(in.texture)
                                                               : textures.max_color(in.texture);
        if (!(top > r.hi)) continue;
        const std::string label = input_label(c.type, p);
        if (!reported.insert({m, label}).second) continue;
        char text[160];
        std::snprintf(text, sizeof text, "has values up to %g, outside [%g, %g]; clamped to %g",
                      top, r.lo, r.hi, r.hi);
        warnings->push_back("Material '" + scene.materials[m].name + "': " + label + " texture '" +
                            scene.textures[in.texture].path + "' " + text);
      }
}

// What the BVH, lights and emissive triangles are built from once the render was cancelled
// during texture conversion or the BVH build: nothing, so Esc is not held up.
const Scene& nothing() {
  static const Scene empty;
  return empty;
}

}  // namespace

BvhQuality bvh_quality_for(const Scene& scene, const RenderSettings& settings) {
  // A lower bound of the rays the render traces: every camera sample traces its camera ray,
  // a photon-map sample its final-gather rays too, and the light pre-passes their paths.
  const uint64_t width = static_cast<uint64_t>(std::max(0, settings.x1 - settings.x0));
  const uint64_t height = static_cast<uint64_t>(std::max(0, settings.y1 - settings.y0));
  const uint64_t camera_samples =
      width * height * static_cast<uint64_t>(std::max(0, settings.samples));
  const uint64_t rays =
      camera_samples + make_integrator(settings.integrator)->extra_rays(settings, camera_samples);
  uint64_t triangles = 0;
  for (const Mesh& mesh : scene.meshes) triangles += mesh.triangle_count();
  // Measured on a 1M-triangle mesh (Embree 3, robust mode): the LOW build saves ~0.2 us of CPU
  // per triangle and costs ~0.6 us more per incoherent ray, so it pays below ~0.3 rays per
  // triangle; a quarter keeps a margin for the rays the bound leaves out. Below 100k triangles
  // either build takes a few ms: not worth a slower BVH.
  constexpr uint64_t kSmallScene = 100000;
  return triangles >= kSmallScene && rays < triangles / 4 ? BvhQuality::kFastBuild
                                                          : BvhQuality::kFastTrace;
}

// The world as the lights see it: a node program becomes the radiance function the environment
// light tabulates and samples, evaluated for lighting rays (a Light Path "Is Camera Ray" trick
// shows its other branch only to camera rays, camera_path.cpp).
static World lit_world(const World& world, const TextureSet& textures) {
  World lit = world;
  if (!world.program.empty() && world.radiance_reg >= 0 && !world.radiance)
    lit.radiance = [&world, &textures](const Vec3& direction) {
      return world_radiance(world, direction, kWorldLightingRay, &textures);
    };
  return lit;
}

SceneResources::SceneResources(const Scene& scene, const RenderSettings& settings,
                               std::vector<std::string>* warnings, const std::atomic<bool>* cancel,
                               BlasCache* blas_cache)
    : textures_(scene.textures, warnings, cancel),
      accel_(textures_.cancelled() ? nothing() : scene, warnings, cancel,
             bvh_quality_for(scene, settings), blas_cache),
      lights_(textures_.cancelled() || accel_.cancelled() ? nothing().lights : scene.lights,
              warnings),
      emissive_(textures_.cancelled() || accel_.cancelled() ? nothing() : scene, accel_,
                &textures_),
      // A cancelled render skips tabulating an environment (and keeps the constant colour).
      emitters_(std::make_unique<EmitterSet>(lights_, emissive_,
                                             textures_.cancelled() || accel_.cancelled()
                                                 ? World::uniform(scene.world.color)
                                                 : lit_world(scene.world, textures_),
                                             EmitterSet::kEveryLightMax, cancel, scene.portals)),
      scene_(scene) {
  warn_out_of_range(scene, textures_, warnings);
  size_t skipped_portals = 0;
  PortalSet(scene.portals, &skipped_portals);
  if (warnings && skipped_portals > 0)
    warnings->push_back(std::to_string(skipped_portals) +
                        " portal(s) without area or with non-finite placement left out");
  const int map_width = EnvironmentEmitter::clamped_width(scene.world.sample_map_width);
  if (warnings && scene.world.radiance && map_width != scene.world.sample_map_width)
    warnings->push_back("World: sample map width " + std::to_string(scene.world.sample_map_width) +
                        " out of range; using " + std::to_string(map_width));
  context_.scene = &scene;
  context_.accel = &accel_;
  context_.lights = &lights_;
  context_.settings = &settings;
  context_.emissive = &emissive_;
  context_.textures = &textures_;
  context_.emitters = emitters_.get();
}

namespace {

bool same(const Vec3& a, const Vec3& b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

bool same_triangles(const EmissiveMeshes& a, const EmissiveMeshes& b) {
  if (a.size() != b.size() || a.length_scale() != b.length_scale()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    const EmissiveTriangle &s = a.triangle(i), &t = b.triangle(i);
    if (!(same(s.p0, t.p0) && same(s.e1, t.e1) && same(s.e2, t.e2) && same(s.normal, t.normal) &&
          s.area == t.area && same(s.radiance, t.radiance)))
      return false;
  }
  return true;
}

}  // namespace

bool SceneResources::update_instance_transforms(const std::vector<uint32_t>& scene_indices) {
  if (textures_.cancelled() || !accel_.update_instance_transforms(scene_indices)) return false;
  refresh_emissive();
  return true;
}

bool SceneResources::update_materials() {
  if (textures_.cancelled() || accel_.cancelled()) return false;
  accel_.update_shadow_masks();  // which objects shadow rays must look through
  refresh_emissive();
  return true;
}

void SceneResources::refresh_emissive() {
  EmissiveMeshes now(scene_, accel_, &textures_);
  if (same_triangles(now, emissive_)) return;
  // The emitters point at the emissive triangles and the lamps: rebuilt on the new triangles
  // (the world, unchanged, is tabulated again: EmitterSet owns its environment emitter).
  emitters_.reset();
  emissive_ = std::move(now);
  emitters_ = std::make_unique<EmitterSet>(lights_, emissive_, lit_world(scene_.world, textures_),
                                           EmitterSet::kEveryLightMax, nullptr, scene_.portals);
  context_.emitters = emitters_.get();
}

}  // namespace photon
