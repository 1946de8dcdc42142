#include "photon/caustic_targets.h"

#include "photon/sampling.h"

namespace photon {

std::vector<BoundingSphere> specular_targets(const Scene& scene, const Accel& accel,
                                             size_t max_targets) {
  std::vector<BoundingSphere> spheres;
  Vec3 all_lo(INFINITY), all_hi(-INFINITY);
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
        r2 = std::max(r2, length_squared(
                              inst.object_to_world.point(mesh.positions[mesh.indices[3 * tri + c]]) - center));
    all_lo = min(all_lo, lo);
    all_hi = max(all_hi, hi);
    // A small margin keeps rays grazing the object inside the cone.
    spheres.push_back({center, std::sqrt(r2) * 1.01f + 1e-4f});
  }
  if (spheres.size() > max_targets)
    spheres = {{(all_lo + all_hi) * 0.5f, 0.5f * length(all_hi - all_lo) * 1.01f + 1e-4f}};
  return spheres;
}

ConeMixture::ConeMixture(const Vec3& origin, const std::vector<BoundingSphere>& targets) {
  for (const BoundingSphere& s : targets) {
    const Vec3 to = s.center - origin;
    const float d2 = length_squared(to);
    Cone c;
    if (d2 <= s.radius * s.radius) {
      c.axis = Vec3(0.0f, 0.0f, 1.0f);
      c.cos_max = -1.0f;
    } else {
      const float d = std::sqrt(d2);
      c.axis = to / d;
      c.cos_max = std::sqrt(std::max(0.0f, 1.0f - s.radius * s.radius / d2));
    }
    c.solid_angle = 2.0f * kPi * (1.0f - c.cos_max);
    if (!(c.solid_angle > 1e-12f)) continue;
    total_solid_angle_ += c.solid_angle;
    cones_.push_back(c);
  }
}

float ConeMixture::coverage() const { return std::min(1.0f, total_solid_angle_ / (4.0f * kPi)); }

bool ConeMixture::sample(float u_pick, Vec2 u, Vec3* direction, float* pdf_out) const {
  if (cones_.empty()) return false;
  float target = u_pick * total_solid_angle_;
  size_t k = 0;
  while (k + 1 < cones_.size() && target >= cones_[k].solid_angle) target -= cones_[k++].solid_angle;
  const Cone& c = cones_[k];
  *direction = c.cos_max <= -1.0f ? sample_uniform_sphere(u)
                                  : Frame(c.axis).to_world(sample_uniform_cone(u, c.cos_max));
  *pdf_out = pdf(*direction);
  return *pdf_out > 0.0f;
}

// p(w) = sum_k P(k) p_k(w) with P(k) = Omega_k / sum Omega and p_k = 1 / Omega_k inside cone k,
// so p(w) = (number of cones containing w) / sum Omega.
float ConeMixture::pdf(const Vec3& direction) const {
  int inside = 0;
  for (const Cone& c : cones_)
    if (c.cos_max <= -1.0f || dot(direction, c.axis) >= c.cos_max) ++inside;
  return inside / total_solid_angle_;
}

DiscMixture::DiscMixture(const Vec3& beam_direction, const std::vector<BoundingSphere>& targets,
                         float extra_radius)
    : frame_(beam_direction) {
  for (const BoundingSphere& s : targets) {
    Disc d;
    d.center = s.center - frame_.n * dot(s.center, frame_.n);
    d.radius = s.radius + extra_radius;
    total_area_ += kPi * d.radius * d.radius;
    discs_.push_back(d);
  }
}

void DiscMixture::sample(float u_pick, Vec2 u, Vec3* point, float* pdf_out) const {
  float target = u_pick * total_area_;
  size_t k = 0;
  while (k + 1 < discs_.size() && target >= kPi * discs_[k].radius * discs_[k].radius)
    target -= kPi * discs_[k].radius * discs_[k].radius, ++k;
  const Disc& d = discs_[k];
  const Vec2 q = sample_concentric_disk(u);
  *point = d.center + (frame_.t * q.x + frame_.b * q.y) * d.radius;
  *pdf_out = pdf(*point);
}

// Same reasoning as ConeMixture::pdf, with areas: (number of discs containing x) / sum area.
float DiscMixture::pdf(const Vec3& point) const {
  int inside = 0;
  for (const Disc& d : discs_)
    if (length_squared(point - d.center) <= d.radius * d.radius * 1.000001f) ++inside;
  return inside / total_area_;
}

}  // namespace photon
