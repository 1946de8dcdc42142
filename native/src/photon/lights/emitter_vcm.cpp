// Emissive triangles, the uniform world and the environment map for bidirectional estimators
// (emission_pdf.h). Lamps are in lamp_vcm.cpp.
//
// Emissive triangles are two-sided (as in Cycles): an emitted ray picks a triangle by power
// (the group) with probability P, a uniform point on it (1 / A), a side (1 / 2) and a
// cosine-distributed direction (cos / pi), so pdf_pos = P / A and pdf_dir = cos / (2 pi). Light
// samples pick the same point, P / A in area measure.
//
// Lights at infinity: an emitted ray travels along -w for a direction w towards the light,
// entering through a disc of radius R (the scene's bounding sphere) across it, pdf_pos =
// 1 / (pi R^2); light samples and emitted rays share the direction density.
#include "photon/base/sampling.h"
#include "photon/lights/emitters.h"
#include "photon/lights/environment.h"

namespace photon {
namespace {

void set_ray(const Vec3& origin, const Vec3& direction, Ray* ray) {
  ray->origin = origin;
  ray->direction = direction;
  ray->tmin = 0.0f;
  ray->tmax = INFINITY;
}

float disc_pdf(const PhotonFrame& frame) {
  return 1.0f / (kPi * frame.radius * frame.radius);
}

// A ray along `d` through a uniform point of the disc across d that covers the scene.
void infinite_ray(const PhotonFrame& frame, const Vec3& d, Vec2 u_pos, Ray* ray) {
  const Frame f(d);
  const Vec2 q = sample_concentric_disk(u_pos);
  set_ray(frame.center + (f.t * q.x + f.b * q.y) * frame.radius - d * (2.0f * frame.radius), d,
          ray);
}

bool emit_triangle(const EmissiveTriangle& t, float pick, float u_side, Vec2 u_pos, Vec2 u_dir,
                   float length_scale, EmissionSample* out) {
  const Vec2 b = sample_uniform_triangle(u_pos);
  const Vec3 q = t.p0 + t.e1 * b.x + t.e2 * b.y;
  const Vec3 n = u_side < 0.5f ? t.normal : -t.normal;
  const Vec3 local = sample_cosine_hemisphere(u_dir);
  const Vec3 d = Frame(n).to_world(local);
  set_ray(offset_ray_origin(q, n, d, length_scale), d, &out->ray);
  out->radiance = t.radiance;
  out->pdf_pos = out->direct_pdf = pick / t.area;
  out->pdf_dir = 0.5f * local.z * kInvPi;
  out->cos_light = local.z;
  return local.z > 0.0f && out->pdf_pos > 0.0f && std::isfinite(out->pdf_pos);
}

bool illuminate_triangle(const EmissiveTriangle& t, float pick, const Vec3& p, Vec2 u,
                         Illumination* out) {
  const Vec2 b = sample_uniform_triangle(u);
  const Vec3 q = t.p0 + t.e1 * b.x + t.e2 * b.y;
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

bool triangle_hit(const EmissiveTriangle& t, float pick, float cos_light, EmitterHit* out) {
  const float c = std::fabs(cos_light);
  if (!(c > 0.0f) || !(pick > 0.0f)) return false;
  out->direct_pdf = pick / t.area;
  out->emission_pdf = pick / t.area * 0.5f * c * kInvPi;
  out->cos_light = c;
  return std::isfinite(out->direct_pdf);
}

}  // namespace

bool EmissiveGroupEmitter::emit_vcm(const PhotonFrame&, float u_rest, Vec2 u_pos, Vec2 u_dir,
                                    EmissionSample* out) const {
  if (meshes_.empty() || meshes_.power().x + meshes_.power().y + meshes_.power().z <= 0.0f)
    return false;
  float u_side;
  const size_t i = meshes_.pick(u_rest, &u_side);
  const float pick = meshes_.pick_probability(i);
  return emit_triangle(meshes_.triangle(i), pick, u_side, u_pos, u_dir, meshes_.length_scale(),
                       out);
}

bool EmissiveGroupEmitter::illuminate_vcm(const PhotonFrame&, const Vec3& p, float u_rest, Vec2 u,
                                          Illumination* out) const {
  if (meshes_.empty()) return false;
  float unused;
  const size_t i = meshes_.pick(u_rest, &unused);
  return illuminate_triangle(meshes_.triangle(i), meshes_.pick_probability(i), p, u, out);
}

bool EmissiveGroupEmitter::surface_hit_vcm(uint32_t instance, uint32_t primitive, float cos_light,
                                           EmitterHit* out) const {
  const long i = meshes_.find(instance, primitive);
  if (i < 0) return false;
  return triangle_hit(meshes_.triangle(i), meshes_.pick_probability(i), cos_light, out);
}

bool TriangleEmitter::emit_vcm(const PhotonFrame&, float u_rest, Vec2 u_pos, Vec2 u_dir,
                               EmissionSample* out) const {
  return emit_triangle(meshes_.triangle(index_), 1.0f, u_rest, u_pos, u_dir, meshes_.length_scale(),
                       out);
}

bool TriangleEmitter::illuminate_vcm(const PhotonFrame&, const Vec3& p, float, Vec2 u,
                                     Illumination* out) const {
  return illuminate_triangle(meshes_.triangle(index_), 1.0f, p, u, out);
}

bool TriangleEmitter::surface_hit_vcm(uint32_t instance, uint32_t primitive, float cos_light,
                                      EmitterHit* out) const {
  if (meshes_.find(instance, primitive) != static_cast<long>(index_)) return false;
  return triangle_hit(meshes_.triangle(index_), 1.0f, cos_light, out);
}

bool WorldEmitter::emit_vcm(const PhotonFrame& frame, float, Vec2 u_pos, Vec2 u_dir,
                            EmissionSample* out) const {
  infinite_ray(frame, sample_uniform_sphere(u_dir), u_pos, &out->ray);
  out->radiance = color_;
  out->pdf_pos = disc_pdf(frame);
  out->pdf_dir = out->direct_pdf = kInv4Pi;
  out->cos_light = 1.0f;
  return !is_black(color_);
}

bool WorldEmitter::illuminate_vcm(const PhotonFrame& frame, const Vec3&, float, Vec2 u,
                                  Illumination* out) const {
  out->wi = sample_uniform_sphere(u);
  out->distance = INFINITY;
  out->radiance = color_;
  out->direct_pdf = kInv4Pi;
  out->emission_pdf = kInv4Pi * disc_pdf(frame);
  out->cos_light = 1.0f;
  out->surface_normal = Vec3(0.0f);
  return !is_black(color_);
}

bool WorldEmitter::hit_vcm(const PhotonFrame& frame, const Ray& ray, float tmax,
                           EmitterHit* out) const {
  if (tmax < INFINITY || is_black(color_)) return false;
  (void)ray;
  out->radiance = color_;
  out->distance = INFINITY;
  out->direct_pdf = kInv4Pi;
  out->emission_pdf = kInv4Pi * disc_pdf(frame);
  return true;
}

bool EnvironmentEmitter::emit_vcm(const PhotonFrame& frame, float, Vec2 u_pos, Vec2 u_dir,
                                  EmissionSample* out) const {
  Vec3 w;
  float pdf;
  if (!sample_direction(u_dir, &w, &pdf) || !(pdf > 0.0f)) return false;
  infinite_ray(frame, -w, u_pos, &out->ray);
  out->radiance = radiance_at_infinity(w);
  out->pdf_pos = disc_pdf(frame);
  out->pdf_dir = out->direct_pdf = pdf;
  out->cos_light = 1.0f;
  return !is_black(out->radiance) && is_finite(out->radiance);
}

bool EnvironmentEmitter::illuminate_vcm(const PhotonFrame& frame, const Vec3&, float, Vec2 u,
                                        Illumination* out) const {
  float pdf;
  if (!sample_direction(u, &out->wi, &pdf) || !(pdf > 0.0f)) return false;
  out->distance = INFINITY;
  out->radiance = radiance_at_infinity(out->wi);
  out->direct_pdf = pdf;
  out->emission_pdf = pdf * disc_pdf(frame);
  out->cos_light = 1.0f;
  out->surface_normal = Vec3(0.0f);
  return !is_black(out->radiance) && is_finite(out->radiance);
}

bool EnvironmentEmitter::hit_vcm(const PhotonFrame& frame, const Ray& ray, float tmax,
                                 EmitterHit* out) const {
  if (tmax < INFINITY) return false;
  out->radiance = radiance_at_infinity(ray.direction);
  out->distance = INFINITY;
  out->direct_pdf = pdf_at_infinity(ray.direction);
  out->emission_pdf = out->direct_pdf * disc_pdf(frame);
  return out->direct_pdf > 0.0f && is_finite(out->radiance);
}

}  // namespace photon
