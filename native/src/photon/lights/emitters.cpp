#include "photon/lights/emitters.h"

#include <cmath>

#include "photon/base/sampling.h"
#include "photon/lights/photon_aim.h"

namespace photon {
namespace {

void set_ray(const Vec3& origin, const Vec3& direction, Ray* ray) {
  ray->origin = origin;
  ray->direction = direction;
  ray->tmin = 0.0f;
  ray->tmax = INFINITY;
}

}  // namespace

LightBounds LightSet::bounds(size_t index) const {
  const Prepared& l = lights_[index];
  LightBounds b;
  switch (l.type) {
    case LightType::kSun:
      b.infinite = true;
      b.lo = b.hi = Vec3(0.0f);
      return b;
    case LightType::kPoint:
    case LightType::kSpot: {
      b.lo = l.position - Vec3(l.radius);
      b.hi = l.position + Vec3(l.radius);
      if (l.type == LightType::kPoint) {
        b.cos_theta_o = -1.0f;  // every direction
        b.cos_theta_e = 0.0f;
      } else {
        // A spot's light leaves within its cone; a radius widens it by the disc's edge, so
        // the bound keeps the cone and lets the box carry the rest (theta_u in importance()).
        b.axis = l.axis;
        b.cos_theta_o = 1.0f;
        b.cos_theta_e = l.cos_half_spot;
      }
      return b;
    }
    case LightType::kArea: {
      const Vec3 e(std::fabs(l.half_u.x) + std::fabs(l.half_v.x),
                   std::fabs(l.half_u.y) + std::fabs(l.half_v.y),
                   std::fabs(l.half_u.z) + std::fabs(l.half_v.z));
      b.lo = l.position - e;
      b.hi = l.position + e;
      b.axis = l.axis;  // one-sided cosine emitter
      b.cos_theta_o = 1.0f;
      b.cos_theta_e = 0.0f;
      return b;
    }
  }
  return b;
}

LightBounds LampEmitter::bounds() const {
  LightBounds b = lamps_.bounds(index_);
  // Scene radius only matters for suns, which stay out of the tree.
  b.power = mean_power(lamps_.power(index_, 1.0f));
  return b;
}

bool EmissiveGroupEmitter::emit_towards(const std::vector<BoundingSphere>& targets,
                                        const PhotonFrame&, float u_pick, Vec2 u_pos, Vec2 u_dir,
                                        Sampler& sampler, EmittedPhoton* out) const {
  // A point by power, then a direction to a target; two-sided emission sees |cos|.
  Vec3 q, n;
  const size_t tri = meshes_.pick_point(u_pick, u_pos, &q, &n);
  Vec3 d;
  float pdf;
  if (!ConeMixture(q, targets).sample(sampler.get_1d(), u_dir, &d, &pdf)) return false;
  const EmissiveTriangle& t = meshes_.triangle(tri);
  const float cos_n = std::fabs(dot(d, n));
  set_ray(offset_ray_origin(q, n, d, meshes_.length_scale()), d, &out->ray);
  out->power = t.radiance * (cos_n * t.area / (meshes_.pick_probability(tri) * pdf));
  return cos_n > 0.0f;
}

LightBounds EmissiveGroupEmitter::bounds() const {
  LightBounds b;
  for (size_t i = 0; i < meshes_.size(); ++i) b = merge(b, TriangleEmitter(meshes_, i).bounds());
  return b;
}

bool TriangleEmitter::sample(const Vec3& p, Sampler& sampler, LightSample* out) const {
  const EmissiveTriangle& t = meshes_.triangle(index_);
  const Vec2 b = sample_uniform_triangle(sampler.get_2d());
  const Vec3 q = t.p0 + t.e1 * b.x + t.e2 * b.y;
  const Vec3 to_light = q - p;
  const float dist2 = length_squared(to_light);
  if (!(dist2 > 0.0f)) return false;
  const float dist = std::sqrt(dist2);
  out->wi = to_light / dist;
  out->distance = dist;
  const float cos_light = std::fabs(dot(out->wi, t.normal));
  if (!(cos_light > 1e-6f)) return false;
  // Uniform over the area: pdf over solid angle d^2 / (cos A).
  out->pdf = dist2 / (cos_light * t.area);
  out->weight = t.radiance / out->pdf;
  out->surface_normal = t.normal;
  return std::isfinite(out->pdf);
}

float TriangleEmitter::surface_pdf(uint32_t instance, uint32_t primitive, float distance,
                                   float cos_light) const {
  if (meshes_.find(instance, primitive) != static_cast<long>(index_)) return 0.0f;
  const float c = std::fabs(cos_light);
  if (!(c > 1e-6f)) return 0.0f;
  return distance * distance / (c * meshes_.triangle(index_).area);
}

Vec3 TriangleEmitter::power(float) const {
  const EmissiveTriangle& t = meshes_.triangle(index_);
  return t.radiance * (2.0f * kPi * t.area);
}

void TriangleEmitter::emit(const PhotonFrame&, float u_rest, Vec2 u_pos, Vec2 u_dir,
                           EmittedPhoton* out) const {
  const EmissiveTriangle& t = meshes_.triangle(index_);
  const Vec2 b = sample_uniform_triangle(u_pos);
  const Vec3 q = t.p0 + t.e1 * b.x + t.e2 * b.y;
  const Vec3 n = u_rest < 0.5f ? t.normal : -t.normal;
  const Vec3 d = Frame(n).to_world(sample_cosine_hemisphere(u_dir));
  set_ray(offset_ray_origin(q, n, d, meshes_.length_scale()), d, &out->ray);
  // L cos / (1/A * 1/2 * cos / pi) = 2 pi L A.
  out->power = t.radiance * (2.0f * kPi * t.area);
}

LightBounds TriangleEmitter::bounds() const {
  const EmissiveTriangle& t = meshes_.triangle(index_);
  LightBounds b;
  const Vec3 p1 = t.p0 + t.e1, p2 = t.p0 + t.e2;
  b.lo = min(t.p0, min(p1, p2));
  b.hi = max(t.p0, max(p1, p2));
  b.axis = t.normal;
  b.cos_theta_o = -1.0f;  // two-sided: normals n and -n
  b.cos_theta_e = 0.0f;
  b.power = mean_power(power(0.0f));
  return b;
}

void WorldEmitter::emit(const PhotonFrame& frame, float, Vec2 u_pos, Vec2 u_dir,
                        EmittedPhoton* out) const {
  // Travelling along d, entering through a disc perpendicular to d that covers the scene.
  const Vec3 d = sample_uniform_sphere(u_dir);
  const Frame f(d);
  const Vec2 q = sample_concentric_disk(u_pos);
  set_ray(frame.center + (f.t * q.x + f.b * q.y) * frame.radius - d * (2.0f * frame.radius), d,
          &out->ray);
  out->power = power(frame.radius);
}

LightBounds WorldEmitter::bounds() const {
  LightBounds b;
  b.infinite = true;
  b.lo = b.hi = Vec3(0.0f);
  b.power = mean_power(color_);
  return b;
}

}  // namespace photon
