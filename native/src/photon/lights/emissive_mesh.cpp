#include "photon/lights/emissive_mesh.h"

#include "photon/base/sampling.h"
#include "photon/render/material_eval.h"

namespace photon {

EmissiveMeshes::EmissiveMeshes(const Scene& scene, const Accel& accel, const TextureSet* textures)
    : length_scale_(accel.length_scale()) {
  std::vector<double> weights;
  double power[3] = {0, 0, 0};
  for (uint32_t id = 0; id < accel.instance_count(); ++id) {
    const Instance& inst = scene.instances[accel.scene_instance(id)];
    const Mesh& mesh = scene.meshes[inst.mesh];
    for (uint32_t tri = 0; tri < mesh.triangle_count(); ++tri) {
      const Material& mat = accel.triangle_material(id, tri);
      if (!mat.may_emit()) continue;
      // Textured emission is sampled by its value at the triangle's centroid.
      SurfaceInteraction centroid;
      if (!mesh.corner_uvs.empty()) {
        const Vec2* uv = &mesh.corner_uvs[3 * tri];
        centroid.uv = (uv[0] + uv[1] + uv[2]) * (1.0f / 3.0f);
      }
      const Vec3 le = max(emitted_radiance(mat, centroid, textures), Vec3(0.0f));
      if (is_black(le) || !is_finite(le)) continue;
      EmissiveTriangle t;
      t.p0 = inst.object_to_world.point(mesh.positions[mesh.indices[3 * tri]]);
      t.e1 = inst.object_to_world.point(mesh.positions[mesh.indices[3 * tri + 1]]) - t.p0;
      t.e2 = inst.object_to_world.point(mesh.positions[mesh.indices[3 * tri + 2]]) - t.p0;
      const Vec3 c = cross(t.e1, t.e2);
      t.area = 0.5f * length(c);
      if (!(t.area > 0.0f) || !std::isfinite(t.area)) continue;
      t.normal = c / (2.0f * t.area);
      t.radiance = le;
      const Vec3 flux = le * (2.0f * kPi * t.area);
      power[0] += flux.x;
      power[1] += flux.y;
      power[2] += flux.z;
      weights.push_back((static_cast<double>(flux.x) + flux.y + flux.z) / 3.0);
      index_[(static_cast<uint64_t>(id) << 32) | tri] = static_cast<uint32_t>(triangles_.size());
      triangles_.push_back(t);
    }
  }
  distribution_ = Distribution1D(weights);
  power_ = Vec3(static_cast<float>(power[0]), static_cast<float>(power[1]),
                static_cast<float>(power[2]));
}

}  // namespace photon
