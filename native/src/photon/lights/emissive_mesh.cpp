#include "photon/lights/emissive_mesh.h"

#include "photon/render/material_eval.h"
#include "photon/base/sampling.h"

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

size_t EmissiveMeshes::pick_point(float u_pick, Vec2 u_point, Vec3* point, Vec3* normal) const {
  const size_t i = distribution_.sample(u_pick);
  const EmissiveTriangle& t = triangles_[i];
  const Vec2 b = sample_uniform_triangle(u_point);
  *point = t.p0 + t.e1 * b.x + t.e2 * b.y;
  *normal = t.normal;
  return i;
}

bool EmissiveMeshes::sample(const Vec3& p, float u_pick, Vec2 u_point, LightSample* out) const {
  if (triangles_.empty() || distribution_.empty()) return false;
  Vec3 q, n;
  const size_t i = pick_point(u_pick, u_point, &q, &n);
  const EmissiveTriangle& t = triangles_[i];
  const Vec3 to_light = q - p;
  const float dist2 = length_squared(to_light);
  if (!(dist2 > 0.0f)) return false;
  const float dist = std::sqrt(dist2);
  out->wi = to_light / dist;
  out->distance = dist;
  const float cos_light = std::fabs(dot(out->wi, n));
  if (!(cos_light > 1e-6f)) return false;
  // pdf over solid angle: P(triangle) / area * d^2 / cos.
  out->pdf = distribution_.probability(i) / t.area * dist2 / cos_light;
  out->weight = t.radiance / out->pdf;
  out->surface_normal = n;
  return true;
}

float EmissiveMeshes::pdf(uint32_t instance, uint32_t primitive, float distance,
                          float cos_light) const {
  auto it = index_.find((static_cast<uint64_t>(instance) << 32) | primitive);
  if (it == index_.end()) return 0.0f;
  const float c = std::fabs(cos_light);
  if (!(c > 1e-6f)) return 0.0f;
  return distribution_.probability(it->second) / triangles_[it->second].area * distance * distance /
         c;
}

void EmissiveMeshes::emit(float u_pick, Vec2 u_point, Vec2 u_dir, Ray* ray, Vec3* power) const {
  float u_side;
  const size_t i = distribution_.sample(u_pick, &u_side);
  const EmissiveTriangle& t = triangles_[i];
  const Vec2 b = sample_uniform_triangle(u_point);
  const Vec3 q = t.p0 + t.e1 * b.x + t.e2 * b.y;
  const Vec3 n = u_side < 0.5f ? t.normal : -t.normal;
  const Vec3 d = Frame(n).to_world(sample_cosine_hemisphere(u_dir));
  ray->origin = offset_ray_origin(q, n, d, length_scale_);
  ray->direction = d;
  ray->tmin = 0.0f;
  ray->tmax = INFINITY;
  // Flux per photon = L cos / (P(tri) / A * 1/2 * cos / pi) = 2 pi L A / P(tri).
  *power = t.radiance * (2.0f * kPi * t.area / distribution_.probability(i));
}

}  // namespace photon
