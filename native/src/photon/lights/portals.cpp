#include "photon/lights/portals.h"

#include <algorithm>
#include <cmath>

#include "photon/base/sampling.h"
#include "photon/base/spherical_rectangle.h"

namespace photon {
namespace {

// Cycles' test of which side of a portal a point is on (kernel/light/background.h).
constexpr float kFacingEpsilon = 1e-4f;

}  // namespace

PortalSet::PortalSet(const std::vector<Portal>& portals, size_t* skipped) {
  size_t dropped = 0;
  for (const Portal& p : portals) {
    Entry e;
    e.center = p.center;
    e.half_x = length(p.half_x);
    const Vec3 ax = e.half_x > 0.0f ? p.half_x / e.half_x : Vec3(0.0f);
    // A sheared transform tilts the second axis: keep its part at right angles to the first.
    const Vec3 y_perp = p.half_y - ax * dot(p.half_y, ax);
    e.half_y = length(y_perp);
    e.axis_x = ax;
    e.axis_y = e.half_y > 0.0f ? y_perp / e.half_y : Vec3(0.0f);
    Vec3 n = cross(e.axis_x, e.axis_y);
    if (dot(n, p.direction) < 0.0f) n = -n;
    e.normal = n;
    e.ellipse = p.shape == AreaShape::kEllipse;
    e.area = 4.0f * e.half_x * e.half_y * (e.ellipse ? 0.25f * kPi : 1.0f);
    const bool ok = is_finite(e.center) && is_finite(e.normal) && e.area > 0.0f &&
                    std::isfinite(e.area) && length_squared(p.direction) > 0.0f &&
                    std::fabs(length(e.normal) - 1.0f) < 1e-3f;
    if (!ok) {
      ++dropped;
      continue;
    }
    portals_.push_back(e);
    total_area_ += e.area;
    area_cdf_.push_back(total_area_);
  }
  if (skipped) *skipped = dropped;
}

bool PortalSet::faces(const Entry& e, const Vec3& p) const {
  return dot(e.normal, p - e.center) > kFacingEpsilon;
}

size_t PortalSet::facing(const Vec3& p) const {
  size_t n = 0;
  for (const Entry& e : portals_) n += faces(e, p) ? 1 : 0;
  return n;
}

bool PortalSet::inside(const Entry& e, const Vec3& x) const {
  const Vec3 local = x - e.center;
  const float a = dot(local, e.axis_x) / e.half_x, b = dot(local, e.axis_y) / e.half_y;
  return e.ellipse ? a * a + b * b <= 1.0f : std::fabs(a) <= 1.0f && std::fabs(b) <= 1.0f;
}

bool PortalSet::hit(const Entry& e, const Vec3& p, const Vec3& wi, float* t) const {
  // wi looks back along the light, which travels through the portal along its normal.
  const float cos_d = dot(wi, e.normal);
  if (!(cos_d < 0.0f)) return false;
  const float dist = dot(e.center - p, e.normal) / cos_d;
  if (!(dist > 0.0f) || !std::isfinite(dist) || !inside(e, p + wi * dist)) return false;
  *t = dist;
  return true;
}

float PortalSet::entry_pdf(const Entry& e, const Vec3& p, const Vec3& wi) const {
  float t;
  if (!hit(e, p, wi, &t)) return 0.0f;
  if (!e.ellipse) {
    const SphericalRectangle rect(p, e.center - e.axis_x * e.half_x - e.axis_y * e.half_y,
                                  e.axis_x * (2.0f * e.half_x), e.axis_y * (2.0f * e.half_y));
    return rect.empty() ? 0.0f : 1.0f / rect.solid_angle();
  }
  // Uniform in area: 1 / A per area is t^2 / (A |cos|) per solid angle.
  return t * t / (e.area * std::fabs(dot(wi, e.normal)));
}

float PortalSet::pdf(const Vec3& p, const Vec3& wi) const {
  size_t n = 0;
  float sum = 0.0f;
  for (const Entry& e : portals_) {
    if (!faces(e, p)) continue;
    ++n;
    sum += entry_pdf(e, p, wi);
  }
  return n > 0 ? sum / static_cast<float>(n) : 0.0f;
}

bool PortalSet::sample(const Vec3& p, float u_pick, Vec2 u, Vec3* wi, float* pdf_out) const {
  const size_t n = facing(p);
  if (n == 0) return false;
  size_t pick = std::min(static_cast<size_t>(u_pick * static_cast<float>(n)), n - 1);
  const Entry* chosen = nullptr;
  for (const Entry& e : portals_) {
    if (!faces(e, p)) continue;
    if (pick-- == 0) {
      chosen = &e;
      break;
    }
  }
  const Entry& e = *chosen;
  Vec3 point;
  if (e.ellipse) {
    const Vec2 d = sample_concentric_disk(u);
    point = e.center + e.axis_x * (d.x * e.half_x) + e.axis_y * (d.y * e.half_y);
  } else {
    const SphericalRectangle rect(p, e.center - e.axis_x * e.half_x - e.axis_y * e.half_y,
                                  e.axis_x * (2.0f * e.half_x), e.axis_y * (2.0f * e.half_y));
    if (rect.empty()) return false;
    point = rect.sample(u);
  }
  const Vec3 to = point - p;
  const float len = length(to);
  if (!(len > 0.0f)) return false;
  *wi = to / len;
  *pdf_out = pdf(p, *wi);
  return *pdf_out > 0.0f && std::isfinite(*pdf_out);
}

void PortalSet::sample_line(float u_pick, Vec2 u_point, Vec2 u_dir, Vec3* point,
                            Vec3* direction) const {
  const float target = u_pick * total_area_;
  size_t i = static_cast<size_t>(std::upper_bound(area_cdf_.begin(), area_cdf_.end(), target) -
                                 area_cdf_.begin());
  i = std::min(i, portals_.size() - 1);
  const Entry& e = portals_[i];
  Vec2 q;
  if (e.ellipse) {
    q = sample_concentric_disk(u_point);
  } else {
    q = Vec2(2.0f * u_point.x - 1.0f, 2.0f * u_point.y - 1.0f);
  }
  *point = e.center + e.axis_x * (q.x * e.half_x) + e.axis_y * (q.y * e.half_y);
  *direction = normalize(Frame(e.normal).to_world(sample_cosine_hemisphere(u_dir)));
}

int PortalSet::crossings(const Vec3& point, const Vec3& direction) const {
  int n = 0;
  for (const Entry& e : portals_) {
    const float cos_d = dot(direction, e.normal);
    if (!(cos_d > 0.0f)) continue;
    const float s = dot(e.center - point, e.normal) / cos_d;
    if (std::isfinite(s) && inside(e, point + direction * s)) ++n;
  }
  return n;
}

}  // namespace photon
