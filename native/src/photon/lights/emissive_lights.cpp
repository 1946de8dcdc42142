#include "photon/lights/emissive_lights.h"

#include <cmath>

#include "photon/base/ray_offset.h"
#include "photon/base/sampling.h"
#include "photon/lights/photon_aim.h"

namespace photon {
namespace {

// A uniform point of triangle t for `u`.
Vec3 triangle_point(const EmissiveTriangle& t, Vec2 u) {
  const Vec2 b = sample_uniform_triangle(u);
  return t.p0 + t.e1 * b.x + t.e2 * b.y;
}

// Bidirectional densities of triangle t, picked with probability `pick`:
// An emitted ray: a uniform point, a side by `u_side`, a cosine-distributed direction.
bool emit_from_triangle(const EmissiveTriangle& t, float pick, float u_side, Vec2 u_pos, Vec2 u_dir,
                        float length_scale, EmittedPhoton* out) {
  const Vec3 q = triangle_point(t, u_pos);
  const Vec3 n = u_side < 0.5f ? t.normal : -t.normal;
  const Vec3 local = sample_cosine_hemisphere(u_dir);
  const Vec3 d = Frame(n).to_world(local);
  set_emitted_ray(offset_ray_origin(q, n, d, length_scale), d, &out->ray);
  out->radiance = t.radiance;
  out->pdf_pos = out->direct_pdf = pick / t.area;
  out->pdf_dir = 0.5f * local.z * kInvPi;
  out->cos_light = local.z;
  return local.z > 0.0f && out->pdf_pos > 0.0f && std::isfinite(out->pdf_pos);
}

// A light sample towards p: a uniform point.
bool illuminate_from_triangle(const EmissiveTriangle& t, float pick, const Vec3& p, Vec2 u,
                              LightSample* out) {
  const Vec3 q = triangle_point(t, u);
  const Vec3 to_light = q - p;
  const float dist2 = length_squared(to_light);
  if (!(dist2 > 0.0f)) return false;
  out->distance = std::sqrt(dist2);
  out->wi = to_light / out->distance;
  const float cos_light = std::fabs(dot(out->wi, t.normal));
  if (!(cos_light > 1e-6f)) return false;
  out->radiance = t.radiance;
  out->cos_light = cos_light;
  out->direct_pdf = pick / t.area * dist2 / cos_light;
  out->emission_pdf = pick / t.area * 0.5f * cos_light * kInvPi;
  out->surface_normal = t.normal;
  return out->direct_pdf > 0.0f && std::isfinite(out->direct_pdf);
}

// A point a ray met, with cosine `cos_light` to the triangle.
bool triangle_densities(const EmissiveTriangle& t, float pick, float cos_light, LightHit* out) {
  const float c = std::fabs(cos_light);
  if (!(c > 0.0f) || !(pick > 0.0f)) return false;
  out->direct_pdf = pick / t.area;
  out->emission_pdf = pick / t.area * 0.5f * c * kInvPi;
  out->cos_light = c;
  return std::isfinite(out->direct_pdf);
}

}  // namespace

// --- EmissiveGroupEmitter ---

LightBounds EmissiveGroupEmitter::bounds() const {
  LightBounds b;
  for (size_t i = 0; i < meshes_.size(); ++i) b = merge(b, TriangleEmitter(meshes_, i).bounds());
  return b;
}

LightSampleU EmissiveGroupEmitter::draw_li(Sampler& sampler) const {
  LightSampleU u;
  u.pick = sampler.get_1d();
  u.uv = sampler.get_2d();
  return u;
}

bool EmissiveGroupEmitter::sample_li(const Vec3& p, const LightSampleU& u,
                                     const PhotonFrame* bidirectional, LightSample* out) const {
  if (bidirectional) {
    if (meshes_.empty()) return false;
    float unused;
    const size_t i = meshes_.pick(u.pick, &unused);
    return illuminate_from_triangle(meshes_.triangle(i), meshes_.pick_probability(i), p, u.uv, out);
  }
  if (meshes_.empty() || meshes_.distribution_empty()) return false;
  const size_t i = meshes_.pick(u.pick);
  const EmissiveTriangle& t = meshes_.triangle(i);
  const Vec3 q = triangle_point(t, u.uv);
  const Vec3 n = t.normal;
  const Vec3 to_light = q - p;
  const float dist2 = length_squared(to_light);
  if (!(dist2 > 0.0f)) return false;
  const float dist = std::sqrt(dist2);
  out->wi = to_light / dist;
  out->distance = dist;
  const float cos_light = std::fabs(dot(out->wi, n));
  if (!(cos_light > 1e-6f)) return false;
  // pdf over solid angle: P(triangle) / area * d^2 / cos.
  out->pdf = meshes_.pick_probability(i) / t.area * dist2 / cos_light;
  out->weight = t.radiance / out->pdf;
  out->surface_normal = n;
  return true;
}

bool EmissiveGroupEmitter::surface_hit(uint32_t instance, uint32_t primitive, float distance,
                                       float cos_light, bool bidirectional, LightHit* out) const {
  const long i = meshes_.find(instance, primitive);
  if (i < 0) return false;
  if (bidirectional)
    return triangle_densities(meshes_.triangle(i), meshes_.pick_probability(i), cos_light, out);
  const float c = std::fabs(cos_light);
  out->pdf = c > 1e-6f
                 ? meshes_.pick_probability(i) / meshes_.triangle(i).area * distance * distance / c
                 : 0.0f;
  return true;
}

bool EmissiveGroupEmitter::sample_le(const PhotonFrame&, float u_rest, Vec2 u_pos, Vec2 u_dir,
                                     bool bidirectional, EmittedPhoton* out) const {
  if (bidirectional) {
    if (meshes_.empty() || meshes_.power().x + meshes_.power().y + meshes_.power().z <= 0.0f)
      return false;
    float u_side;
    const size_t i = meshes_.pick(u_rest, &u_side);
    return emit_from_triangle(meshes_.triangle(i), meshes_.pick_probability(i), u_side, u_pos,
                              u_dir, meshes_.length_scale(), out);
  }
  float u_side;
  const size_t i = meshes_.pick(u_rest, &u_side);
  const EmissiveTriangle& t = meshes_.triangle(i);
  const Vec3 q = triangle_point(t, u_pos);
  const Vec3 n = u_side < 0.5f ? t.normal : -t.normal;
  const Vec3 d = Frame(n).to_world(sample_cosine_hemisphere(u_dir));
  set_emitted_ray(offset_ray_origin(q, n, d, meshes_.length_scale()), d, &out->ray);
  // Flux per photon = L cos / (P(tri) / A * 1/2 * cos / pi) = 2 pi L A / P(tri).
  out->power = t.radiance * (2.0f * kPi * t.area / meshes_.pick_probability(i));
  return true;
}

bool EmissiveGroupEmitter::sample_le_towards(const std::vector<BoundingSphere>& targets,
                                             const PhotonFrame&, float u_pick, Vec2 u_pos,
                                             Vec2 u_dir, Sampler& sampler,
                                             EmittedPhoton* out) const {
  // A point by power, then a direction to a target; two-sided emission sees |cos|.
  const size_t tri = meshes_.pick(u_pick);
  const EmissiveTriangle& t = meshes_.triangle(tri);
  const Vec3 q = triangle_point(t, u_pos);
  const Vec3 n = t.normal;
  Vec3 d;
  float pdf;
  if (!ConeMixture(q, targets).sample(sampler.get_1d(), u_dir, &d, &pdf)) return false;
  const float cos_n = std::fabs(dot(d, n));
  set_emitted_ray(offset_ray_origin(q, n, d, meshes_.length_scale()), d, &out->ray);
  out->power = t.radiance * (cos_n * t.area / (meshes_.pick_probability(tri) * pdf));
  return cos_n > 0.0f;
}

// --- TriangleEmitter ---

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

Vec3 TriangleEmitter::power(float) const {
  const EmissiveTriangle& t = meshes_.triangle(index_);
  return t.radiance * (2.0f * kPi * t.area);
}

bool TriangleEmitter::sample_li(const Vec3& p, const LightSampleU& u,
                                const PhotonFrame* bidirectional, LightSample* out) const {
  const EmissiveTriangle& t = meshes_.triangle(index_);
  if (bidirectional) return illuminate_from_triangle(t, 1.0f, p, u.uv, out);
  const Vec3 q = triangle_point(t, u.uv);
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

bool TriangleEmitter::surface_hit(uint32_t instance, uint32_t primitive, float distance,
                                  float cos_light, bool bidirectional, LightHit* out) const {
  if (meshes_.find(instance, primitive) != static_cast<long>(index_)) return false;
  const EmissiveTriangle& t = meshes_.triangle(index_);
  if (bidirectional) return triangle_densities(t, 1.0f, cos_light, out);
  const float c = std::fabs(cos_light);
  out->pdf = c > 1e-6f ? distance * distance / (c * t.area) : 0.0f;
  return true;
}

bool TriangleEmitter::sample_le(const PhotonFrame&, float u_rest, Vec2 u_pos, Vec2 u_dir,
                                bool bidirectional, EmittedPhoton* out) const {
  const EmissiveTriangle& t = meshes_.triangle(index_);
  if (bidirectional)
    return emit_from_triangle(t, 1.0f, u_rest, u_pos, u_dir, meshes_.length_scale(), out);
  const Vec3 q = triangle_point(t, u_pos);
  const Vec3 n = u_rest < 0.5f ? t.normal : -t.normal;
  const Vec3 d = Frame(n).to_world(sample_cosine_hemisphere(u_dir));
  set_emitted_ray(offset_ray_origin(q, n, d, meshes_.length_scale()), d, &out->ray);
  // L cos / (1/A * 1/2 * cos / pi) = 2 pi L A.
  out->power = t.radiance * (2.0f * kPi * t.area);
  return true;
}

}  // namespace photon
