#include "photon/render/scene_resources.h"

#include <cstdio>
#include <set>

#include "photon/render/material_eval.h"

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

SceneResources::SceneResources(const Scene& scene, const RenderSettings& settings,
                               std::vector<std::string>* warnings, const std::atomic<bool>* cancel)
    : textures_(scene.textures, warnings, cancel),
      accel_(textures_.cancelled() ? nothing() : scene, warnings, cancel),
      lights_(textures_.cancelled() || accel_.cancelled() ? nothing().lights : scene.lights,
              warnings),
      emissive_(textures_.cancelled() || accel_.cancelled() ? nothing() : scene, accel_,
                &textures_),
      emitters_(lights_, emissive_, scene.world.color) {
  warn_out_of_range(scene, textures_, warnings);
  context_.scene = &scene;
  context_.accel = &accel_;
  context_.lights = &lights_;
  context_.settings = &settings;
  context_.emissive = &emissive_;
  context_.textures = &textures_;
  context_.emitters = &emitters_;
}

}  // namespace photon
