#include "photon/lights/photon_aim.h"

#include <algorithm>
#include <cmath>

#include "photon/base/sampling.h"

namespace photon {

ConeMixture::ConeMixture(const Vec3& origin, const std::vector<BoundingSphere>& targets,
                         const Cap& region, float extra_radius)
    : region_(region) {
  for (const BoundingSphere& s : targets) {
    const Cap cone = Cap::towards_ball(origin, s.center, double(s.radius) + extra_radius);
    const double solid_angle = cap_overlap(cone, region);
    if (!(solid_angle > 0.0)) continue;  // behind the light, or outside its cone
    total_solid_angle_ += solid_angle;
    pieces_.push_back({cone, solid_angle});
  }
}

float ConeMixture::coverage() const {
  return static_cast<float>(std::min(1.0, total_solid_angle_ / region_.solid_angle()));
}

bool ConeMixture::sample(float u_pick, Vec2 u, Vec3* direction, float* pdf_out) const {
  if (pieces_.empty()) return false;
  double target = u_pick * total_solid_angle_;
  size_t k = 0;
  while (k + 1 < pieces_.size() && target >= pieces_[k].solid_angle)
    target -= pieces_[k++].solid_angle;
  if (!sample_cap_overlap(pieces_[k].cone, region_, u, direction)) return false;
  *pdf_out = pdf_counting(*direction, k);
  return *pdf_out > 0.0f;
}

// p(w) = sum_k P(k) p_k(w) with P(k) = Omega_k / sum Omega and p_k = 1 / Omega_k inside piece
// k, so p(w) = (number of pieces containing w) / sum Omega. The piece a direction was drawn
// from counts whatever rounding says at its border.
float ConeMixture::pdf_counting(const Vec3& direction, size_t known_inside) const {
  const bool in_region = region_.contains(direction);
  int inside = 0;
  for (size_t k = 0; k < pieces_.size(); ++k)
    if (k == known_inside || (in_region && pieces_[k].cone.contains(direction))) ++inside;
  return static_cast<float>(inside / total_solid_angle_);
}

float ConeMixture::pdf(const Vec3& direction) const {
  return pieces_.empty() ? 0.0f : pdf_counting(direction, pieces_.size());
}

SphereLightAim::SphereLightAim(const Vec3& center, float radius,
                               const std::vector<BoundingSphere>& targets)
    : center_(center), radius_(radius) {
  for (const BoundingSphere& t : targets) {
    const Vec3 to = t.center - center;
    const double d = length(to);
    Cap normals;
    if (!(d > 0.0)) {
      if (!(t.radius > radius)) continue;
      normals = Cap::whole_sphere();
    } else {
      // Target ball (c, rho) has a point in front of the tangent plane at q = p + r n when
      // (c - q) . n > -rho, i.e. n . (c - p) / |c - p| > (r - rho) / |c - p|.
      const double cos_max = (double(radius) - t.radius) / d;
      if (cos_max >= 1.0) continue;  // inside the light
      normals = Cap(to / static_cast<float>(d), std::acos(std::max(-1.0, cos_max)));
    }
    const double weight = Cap::towards_ball(center, t.center, t.radius).solid_angle();
    if (!(weight > 0.0)) continue;
    aims_.push_back({t, normals, weight});
    total_weight_ += weight;
  }
}

bool SphereLightAim::sample(float u_pick, Vec2 u_point, Vec2 u_dir, Vec3* normal, Vec3* direction,
                            float* pdf_out) const {
  if (aims_.empty()) return false;
  double target = u_pick * total_weight_;
  size_t k = 0;
  while (k + 1 < aims_.size() && target >= aims_[k].weight) target -= aims_[k++].weight;
  const Aim& a = aims_[k];
  if (!sample_cap_overlap(a.normals, Cap::whole_sphere(), u_point, normal)) return false;
  const Vec3 q = center_ + *normal * radius_;
  const Cap cone = Cap::towards_ball(q, a.target.center, a.target.radius);
  if (!sample_cap_overlap(cone, Cap(*normal, 0.5 * Cap::kPiD), u_dir, direction)) return false;
  double pdf = 0.0;
  for (size_t j = 0; j < aims_.size(); ++j) pdf += term(aims_[j], *normal, *direction, j == k);
  *pdf_out = static_cast<float>(pdf);
  return *pdf_out > 0.0f && std::isfinite(*pdf_out);
}

float SphereLightAim::pdf(const Vec3& normal, const Vec3& direction) const {
  double pdf = 0.0;
  for (const Aim& a : aims_) pdf += term(a, normal, direction, false);
  return static_cast<float>(pdf);
}

// P(k) / (r^2 Omega(normals_k)) / Omega(hemisphere ∩ cone_k(q)) where (n, w) can come from k.
double SphereLightAim::term(const Aim& a, const Vec3& normal, const Vec3& direction,
                            bool known_inside) const {
  if (!known_inside && !a.normals.contains(normal)) return 0.0;
  const Vec3 q = center_ + normal * radius_;
  const Cap cone = Cap::towards_ball(q, a.target.center, a.target.radius);
  if (!known_inside && !(dot(direction, normal) > 0.0f && cone.contains(direction))) return 0.0;
  const double piece = cap_overlap(cone, Cap(normal, 0.5 * Cap::kPiD));
  if (!(piece > 0.0)) return 0.0;
  const double r2 = double(radius_) * radius_;
  return a.weight / total_weight_ / (r2 * a.normals.solid_angle() * piece);
}

DiscMixture::DiscMixture(const Vec3& beam_direction, const std::vector<BoundingSphere>& targets)
    : frame_(beam_direction) {
  for (const BoundingSphere& s : targets) {
    Disc d;
    d.center = s.center - frame_.n * dot(s.center, frame_.n);
    d.radius = s.radius;
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
