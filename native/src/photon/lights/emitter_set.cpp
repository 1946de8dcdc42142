#include "photon/lights/emitter_set.h"

#include "photon/lights/emissive_lights.h"
#include "photon/lights/environment.h"
#include "photon/lights/portal_world.h"
#include "photon/lights/world_light.h"

namespace photon {

EmitterSet::EmitterSet(const LightSet& lamps, const EmissiveMeshes& emissive,
                       const Vec3& world_color, size_t every_light_max)
    : EmitterSet(lamps, emissive, World::uniform(world_color), every_light_max) {}

EmitterSet::EmitterSet(const LightSet& lamps, const EmissiveMeshes& emissive, const World& world,
                       size_t every_light_max, const std::atomic<bool>* cancel,
                       const std::vector<Portal>& portals)
    : emissive_(&emissive), lamps_(&lamps) {
  auto own = [&](std::unique_ptr<Emitter> e) {
    owned_.push_back(std::move(e));
    return owned_.back().get();
  };
  std::vector<const Emitter*> lamp_emitters;
  for (size_t i = 0; i < lamps.size(); ++i) lamp_emitters.push_back(&lamps.lamp(i));
  every_light_ = lamp_emitters;
  if (!emissive.empty())
    every_light_.push_back(own(std::make_unique<EmissiveGroupEmitter>(emissive)));
  if (world.radiance) {
    world_ = own(
        std::make_unique<EnvironmentEmitter>(world.radiance, world.sample_map_width, 1, cancel));
  } else if (!is_black(world.color)) {
    world_ = own(std::make_unique<WorldEmitter>(world.color));
  }
  if (world_) {
    PortalSet portal_set(portals);
    if (!portal_set.empty())
      world_ = own(std::make_unique<PortalWorldEmitter>(*world_, std::move(portal_set)));
    every_light_.push_back(world_);
  }

  const size_t count = lamps.size() + (emissive.empty() ? 0 : 1);
  use_tree_ = count > every_light_max;
  if (!use_tree_) return;
  std::vector<LightBounds> bounds;
  std::vector<bool> hittable;
  for (size_t lamp = 0; lamp < lamp_emitters.size(); ++lamp) {
    const Emitter* e = lamp_emitters[lamp];
    const LightBounds b = e->bounds();
    if (b.infinite) {
      distant_.push_back(e);
      continue;
    }
    tree_emitters_.push_back(e);
    tree_lamp_.push_back(static_cast<uint32_t>(lamp));
    bounds.push_back(b);
    hittable.push_back(e->has_area());  // lamps are found by rays through the tree
  }
  first_triangle_ = tree_emitters_.size();
  for (size_t t = 0; t < emissive.size(); ++t) {
    const Emitter* e = own(std::make_unique<TriangleEmitter>(emissive, t));
    tree_emitters_.push_back(e);
    tree_lamp_.push_back(UINT32_MAX);
    bounds.push_back(e->bounds());
    hittable.push_back(false);  // triangles are found by the scene's BVH
  }
  tree_ = LightTree(bounds, hittable);
}

bool EmitterSet::intersect_lamps(const Ray& ray, float tmax, uint32_t mask, float* t_hit,
                                 Vec3* radiance, size_t* lamp_index) const {
  if (!use_tree_) return lamps_->intersect(ray, tmax, mask, t_hit, radiance, lamp_index);
  Ray bounded = ray;
  bounded.tmax = tmax;
  bool found = false;
  float best = tmax;
  tree_.for_each_hit(bounded, [&](uint32_t i) {
    const uint32_t lamp = tree_lamp_[i];
    if (lamp != UINT32_MAX && lamps_->intersect_one(lamp, ray, best, mask, &best, radiance)) {
      found = true;
      if (lamp_index) *lamp_index = lamp;
    }
  });
  if (found) *t_hit = best;
  return found;
}

}  // namespace photon
