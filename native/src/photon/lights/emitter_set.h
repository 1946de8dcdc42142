// Every emitter of a scene, and how direct lighting picks among them:
//  - few emitters (at most `every_light_max` lamps, the emissive meshes counting as one): every
//    one is sampled at every shading point, as Photon always did (every_light());
//  - more: lamps at infinity (suns) and the world are still sampled one by one,
//    and one emitter among the other lamps and the emissive triangles is picked per shading
//    point by the light tree (Conty Estevez & Kulla 2018), so the cost no longer grows with
//    the number of lights.
// Photon emission always uses every_light() (power-proportional selection, photon_sources.h).
#pragma once

#include <atomic>
#include <memory>
#include <vector>

#include "photon/lights/emissive_mesh.h"
#include "photon/lights/emitter.h"
#include "photon/lights/light_tree.h"
#include "photon/lights/lights.h"

namespace photon {

class EmitterSet {
 public:
  // Up to 8 lamps + emissive meshes the every-light estimator is kept: the images it gives stay
  // exactly as they were, and with so few lights one sample of each costs little more than a
  // tree pick.
  static constexpr size_t kEveryLightMax = 8;

  EmitterSet() = default;
  // `lamps` and `emissive` must outlive the set.
  EmitterSet(const LightSet& lamps, const EmissiveMeshes& emissive, const Vec3& world_color,
             size_t every_light_max = kEveryLightMax);
  // The world as the scene gives it: an environment function (World::radiance, importance
  // sampled: environment.h) when set, else the constant colour; seen through `portals` when
  // there are any (portal_world.h; degenerate ones are left out).
  // `cancel` stops tabulating the environment early (the render is being abandoned).
  EmitterSet(const LightSet& lamps, const EmissiveMeshes& emissive, const World& world,
             size_t every_light_max = kEveryLightMax, const std::atomic<bool>* cancel = nullptr,
             const std::vector<Portal>& portals = {});
  EmitterSet(const EmitterSet&) = delete;
  EmitterSet& operator=(const EmitterSet&) = delete;

  // Lamps in scene order, then the emissive group, then the world (each only if it emits).
  const std::vector<const Emitter*>& every_light() const { return every_light_; }

  bool use_tree() const { return use_tree_; }
  // Tree mode: suns, sampled one by one.
  const std::vector<const Emitter*>& distant() const { return distant_; }
  // The world (null if black): in tree mode direct lighting samples it beside the tree.
  const Emitter* world() const { return world_; }
  // Radiance along a ray that left the scene (0 without a world): what the background,
  // reflections and refractions show.
  Vec3 world_radiance(const Vec3& direction) const {
    return world_ ? world_->radiance_at_infinity(direction) : Vec3(0.0f);
  }
  // The same at the wavelengths (the world's colour uplifted as an illuminant).
  SampledSpectrum world_radiance(const Vec3& direction, const SampledWavelengths& wl) const {
    return world_ ? world_->spectrum(world_->radiance_at_infinity(direction), wl)
                  : SampledSpectrum(0.0f);
  }
  const LightTree& tree() const { return tree_; }
  const Emitter& tree_emitter(uint32_t i) const { return *tree_emitters_[i]; }
  // Tree entry of emissive triangle `triangle` (EmissiveMeshes index).
  uint32_t triangle_entry(size_t triangle) const {
    return static_cast<uint32_t>(first_triangle_ + triangle);
  }
  const EmissiveMeshes* emissive() const { return emissive_; }

  // LightSet::intersect (the nearest lamp surface a ray meets before `tmax`); in tree mode only
  // the lamps whose boxes in the tree the ray crosses are tested, so camera and glossy rays do
  // not pay for every lamp of the scene. Lamps without power are not in the tree and so are
  // never met (they would only have hidden lamps behind them).
  // `lamp`, when given, receives the LightSet index of the lamp met.
  bool intersect_lamps(const Ray& ray, float tmax, uint32_t mask, float* t_hit, Vec3* radiance,
                       size_t* lamp = nullptr) const;

 private:
  std::vector<std::unique_ptr<Emitter>> owned_;
  std::vector<const Emitter*> every_light_, distant_, tree_emitters_;
  const Emitter* world_ = nullptr;
  const EmissiveMeshes* emissive_ = nullptr;
  const LightSet* lamps_ = nullptr;
  std::vector<uint32_t> tree_lamp_;  // per tree entry: its LightSet index (UINT32_MAX: triangle)
  LightTree tree_;
  size_t first_triangle_ = 0;
  bool use_tree_ = false;
};

}  // namespace photon
