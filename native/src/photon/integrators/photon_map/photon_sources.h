// Everything that emits photons (the scene's emitters: Blender lights, emissive triangles, a
// uniform world), with
// photons split between them in proportion to their power (Jensen 2001 sec. 5.1.4, multiple light
// sources).
#pragma once

#include <vector>

#include "photon/base/distribution.h"
#include "photon/integrators/integrator.h"
#include "photon/integrators/photon_map/caustic_targets.h"
#include "photon/lights/emissive_mesh.h"
#include "photon/lights/emitter_set.h"
#include "photon/lights/photon_aim.h"

namespace photon {

class PhotonSources {
 public:
  explicit PhotonSources(const RenderContext& context);

  bool has_global() const { return !global_.empty(); }
  bool has_caustic() const { return !caustic_.empty(); }
  // Total emitted flux (W per channel) that global photons carry.
  Vec3 total_power() const { return total_power_; }
  const std::vector<BoundingSphere>& targets() const { return targets_; }
  Vec3 scene_center() const { return center_; }
  float scene_radius() const { return radius_; }

  // One photon of the global map: its power is the flux it carries if it were the only photon
  // (divide by the number emitted). Consumes one 1D and two 2D sampler dimensions.
  bool emit_global(Sampler& sampler, EmittedPhoton* out) const;
  // One caustic photon, aimed at the specular targets.
  bool emit_caustic(Sampler& sampler, EmittedPhoton* out) const;

 private:
  const RenderContext& context_;
  std::vector<const Emitter*> sources_;  // EmitterSet::every_light() that emit
  Distribution1D global_, caustic_;
  std::vector<BoundingSphere> targets_;
  Vec3 total_power_{0.0f};
  Vec3 center_{0.0f};
  float radius_ = 1.0f;
};

}  // namespace photon
