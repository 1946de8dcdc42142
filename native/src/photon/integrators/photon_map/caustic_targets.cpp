#include "photon/integrators/photon_map/caustic_targets.h"

#include <algorithm>

#include "photon/base/sampling.h"

namespace photon {

std::vector<BoundingSphere> specular_targets(const Scene& scene, const Accel& accel,
                                             size_t max_targets) {
  std::vector<BoundingSphere> spheres;
  Vec3 all_lo(INFINITY), all_hi(-INFINITY);
  const float margin = 1e-4f * accel.length_scale();  // 0.1 mm in a scene of a metre or more
  for (uint32_t id = 0; id < accel.instance_count(); ++id) {
    const Instance& inst = scene.instances[accel.scene_instance(id)];
    if (!(inst.visibility & (kVisibleGlossy | kVisibleTransmission | kVisibleDiffuse))) continue;
    const Mesh& mesh = scene.meshes[inst.mesh];
    // Centre of the box around the specular triangles, radius to the farthest vertex: tight
    // for balls and lenses, where the box's half diagonal would waste 2/3 of the photons.
    Vec3 lo(INFINITY), hi(-INFINITY);
    std::vector<uint32_t> specular;
    for (uint32_t tri = 0; tri < mesh.triangle_count(); ++tri) {
      if (!accel.triangle_material(id, tri).may_be_specular()) continue;
      specular.push_back(tri);
      for (int c = 0; c < 3; ++c) {
        const Vec3 p = inst.object_to_world.point(mesh.positions[mesh.indices[3 * tri + c]]);
        lo = min(lo, p);
        hi = max(hi, p);
      }
    }
    if (specular.empty()) continue;
    const Vec3 center = (lo + hi) * 0.5f;
    float r2 = 0.0f;
    for (uint32_t tri : specular)
      for (int c = 0; c < 3; ++c)
        r2 = std::max(
            r2,
            length_squared(inst.object_to_world.point(mesh.positions[mesh.indices[3 * tri + c]]) -
                           center));
    all_lo = min(all_lo, lo);
    all_hi = max(all_hi, hi);
    // A small margin keeps rays grazing the object inside the cone.
    spheres.push_back({center, std::sqrt(r2) * 1.01f + margin});
  }
  if (spheres.size() > max_targets)
    spheres = {{(all_lo + all_hi) * 0.5f, 0.5f * length(all_hi - all_lo) * 1.01f + margin}};
  return spheres;
}

}  // namespace photon
