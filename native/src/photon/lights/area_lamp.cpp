#include "photon/lights/area_lamp.h"

#include "photon/base/sampling.h"
#include "photon/base/spherical_caps.h"
#include "photon/lights/photon_aim.h"

namespace photon {

std::unique_ptr<Lamp> make_area_lamp(LampDescription d, std::vector<std::string>* warnings) {
  auto lamp = std::make_unique<AreaLamp>(d);
  // Zero or so small its radiance overflows; a tiny lamp of a tiny scene is still a lamp.
  if (!(lamp->area() > 0.0f) || !is_finite(d.flux_color * (0.25f / lamp->area()))) {
    if (warnings) warnings->push_back("Area light '" + d.light->name + "' has zero size; skipped");
    return nullptr;
  }
  return lamp;
}

AreaLamp::AreaLamp(LampDescription d)
    : Lamp(d.light->visibility, std::move(d.spectrum)), spread_(d.light->spread) {
  const Light& l = *d.light;
  shape_ = l.shape;
  position_ = l.light_to_world.column(3);
  axis_ = normalize(-l.light_to_world.column(2));
  radius_ = std::max(l.radius, 0.0f);
  half_u_ = l.light_to_world.column(0) * (0.5f * std::max(l.size_x, 0.0f));
  half_v_ = l.light_to_world.column(1) * (0.5f * std::max(l.size_y, 0.0f));
  const float lu = length(half_u_), lv = length(half_v_);
  area_ = l.shape == AreaShape::kRectangle ? 4.0f * lu * lv : kPi * lu * lv;
  radiance_ = d.flux_color * (0.25f / area_);
  ies_ = std::move(d.ies);
  flux_ = radiance_ * (kPi * area_);
  if (ies_) {
    // Phi = L A * integral over the hemisphere of cos a(cos) profile, by the midpoint rule in
    // (cos^2, phi): cos d(omega) = d(cos^2) / 2 d(phi).
    constexpr int kSteps = 256, kTurns = 128;
    const Frame f(axis_);
    double sum = 0.0;
    for (int i = 0; i < kSteps; ++i) {
      const float c = std::sqrt((i + 0.5f) / kSteps);
      const float s = std::sqrt(std::max(0.0f, 1.0f - c * c));
      const float a = spread_.active() ? spread_.attenuation(c) : 1.0f;
      for (int j = 0; j < kTurns; ++j) {
        const float phi = (j + 0.5f) * (2.0f * kPi / kTurns);
        sum += a * profile(f.to_world(Vec3(s * std::cos(phi), s * std::sin(phi), c)));
      }
    }
    flux_ = radiance_ * static_cast<float>(area_ * kPi * sum / (double(kSteps) * kTurns));
  }
}

Vec3 AreaLamp::point(Vec2 u) const {
  if (shape_ == AreaShape::kRectangle)
    return position_ + half_u_ * (2.0f * u.x - 1.0f) + half_v_ * (2.0f * u.y - 1.0f);
  const Vec2 d = sample_concentric_disk(u);
  return position_ + half_u_ * d.x + half_v_ * d.y;
}

bool AreaLamp::inside(const Vec3& d) const {
  const float su = dot(d, half_u_) / length_squared(half_u_);
  const float sv = dot(d, half_v_) / length_squared(half_v_);
  return shape_ == AreaShape::kRectangle ? std::fabs(su) <= 1.0f && std::fabs(sv) <= 1.0f
                                         : su * su + sv * sv <= 1.0f;
}

bool AreaLamp::direct_window(const Vec3& p, Window* w) const {
  w->whole = true;
  w->area = area_;
  if (!spread_.active()) return true;
  // Points of the lamp farther than r = t tan(h) from the foot of p (t: p's height over the
  // lamp's plane) see p at more than h from the axis.
  const Vec3 d = p - position_;
  const float t = dot(d, axis_);
  if (!(t > 0.0f)) return false;
  const Vec3 foot = d - axis_ * t;
  const float r = t * spread_.tan_half_angle();
  const float lu = length(half_u_), lv = length(half_v_);
  const float cu = dot(foot, half_u_) / (lu * lu), cv = dot(foot, half_v_) / (lv * lv);
  w->u0 = std::max(cu - r / lu, -1.0f);
  w->u1 = std::min(cu + r / lu, 1.0f);
  w->v0 = std::max(cv - r / lv, -1.0f);
  w->v1 = std::min(cv + r / lv, 1.0f);
  if (!(w->u0 < w->u1) || !(w->v0 < w->v1)) return false;
  const float window_area = lu * lv * (w->u1 - w->u0) * (w->v1 - w->v0);
  // An ellipse's window also holds points off the lamp (samples there are lost): worth it
  // only when smaller than the ellipse.
  if (shape_ == AreaShape::kEllipse && !(window_area < area_)) return true;
  w->whole = false;
  w->area = window_area;
  return w->area > 0.0f;
}

Vec3 AreaLamp::power(float) const {
  return flux_;
}

LightBounds AreaLamp::extent() const {
  const Vec3 e(std::fabs(half_u_.x) + std::fabs(half_v_.x),
               std::fabs(half_u_.y) + std::fabs(half_v_.y),
               std::fabs(half_u_.z) + std::fabs(half_v_.z));
  LightBounds b;
  b.lo = position_ - e;
  b.hi = position_ + e;
  b.axis = axis_;  // one-sided cosine emitter
  b.cos_theta_o = 1.0f;
  b.cos_theta_e = spread_.active() ? std::cos(spread_.half_angle()) : 0.0f;
  return b;
}

bool AreaLamp::sample_li(const Vec3& p, const LightSampleU& u, const PhotonFrame* bidirectional,
                         LightSample* out) const {
  out->surface_normal = Vec3(0.0f);
  // Bidirectional estimators sample the whole lamp: the density a camera ray that meets it
  // reports (intersect) cannot depend on where its path came from.
  Window window;
  if (!bidirectional && spread_.active() && !direct_window(p, &window)) return false;
  const bool whole = bidirectional || window.whole;
  const Vec3 q = whole ? point(u.uv)
                       : position_ + half_u_ * (window.u0 + (window.u1 - window.u0) * u.uv.x) +
                             half_v_ * (window.v0 + (window.v1 - window.v0) * u.uv.y);
  if (!whole && !inside(q - position_)) return false;
  const Vec3 to_light = q - p;
  const float dist2 = length_squared(to_light);
  if (!(dist2 > 0.0f)) return false;
  const float dist = std::sqrt(dist2);
  out->wi = to_light / dist;
  out->distance = dist;
  const float cos_light = dot(-out->wi, axis_);  // one-sided: emits along its axis only
  if (spread_.active()) return sample_spread_li(cos_light, dist2, window.area, bidirectional, out);
  if (bidirectional) {
    if (!(cos_light > 1e-7f)) return false;
    out->radiance = radiance_ * profile(-out->wi);
    out->cos_light = cos_light;
    out->direct_pdf = dist2 / (cos_light * area_);
    out->emission_pdf = cos_light * kInvPi / area_;
    return std::isfinite(out->direct_pdf);
  }
  if (cos_light <= 0.0f) return false;
  out->weight = radiance_ * profile(-out->wi) * (cos_light * area_ / dist2);
  out->pdf = dist2 / (cos_light * area_);
  return true;
}

bool AreaLamp::sample_spread_li(float cos_light, float dist2, float window_area, bool bidirectional,
                                LightSample* out) const {
  if (!(cos_light > 1e-7f)) return false;
  const float a = spread_.attenuation(cos_light);
  if (!(a > 0.0f)) return false;
  const Vec3 radiance = radiance_ * profile(-out->wi);
  if (bidirectional) {
    out->radiance = radiance * a;
    out->cos_light = cos_light;
    out->direct_pdf = dist2 / (cos_light * area_);
    out->emission_pdf = spread_.pdf(cos_light) / area_;
    return std::isfinite(out->direct_pdf);
  }
  out->weight = radiance * (a * cos_light * window_area / dist2);
  out->pdf = dist2 / (cos_light * window_area);
  return std::isfinite(out->pdf);
}

bool AreaLamp::eval_li(const Vec3& p, const Vec3& wi, LightHit* out) const {
  const float denom = dot(wi, axis_);
  if (!(denom < 0.0f)) return false;
  const float t = dot(position_ - p, axis_) / denom;
  if (!(t > 0.0f)) return false;
  if (!inside(p + wi * t - position_)) return false;
  const float cos_light = -denom;
  if (spread_.active()) {
    const float a = spread_.attenuation(cos_light);
    Window window;
    if (!(a > 0.0f) || !direct_window(p, &window)) return false;
    out->radiance = radiance_ * profile(-wi) * a;
    out->distance = t;
    out->pdf = t * t / (cos_light * window.area);
    return true;
  }
  out->radiance = radiance_ * profile(-wi);
  out->distance = t;
  out->pdf = t * t / (cos_light * area_);
  return true;
}

bool AreaLamp::intersect(const Ray& ray, float tmax, bool bidirectional, LightHit* out) const {
  const float denom = dot(ray.direction, axis_);
  if (!(denom < 0.0f)) return false;  // seen from behind: the back of an area lamp is dark
  const float t = dot(position_ - ray.origin, axis_) / denom;
  if (bidirectional ? !(t > ray.tmin) || !(t < tmax) : t <= ray.tmin || t >= tmax) return false;
  if (!inside(ray.origin + ray.direction * t - position_)) return false;
  const Vec3 radiance = radiance_ * profile(-ray.direction);
  out->radiance = radiance;
  out->distance = t;
  if (spread_.active()) {
    const float a = spread_.attenuation(-denom);
    if (!(a > 0.0f)) return false;  // hidden by the soft box's slats: the ray passes
    out->radiance = radiance * a;
  }
  if (bidirectional) {
    out->direct_pdf = 1.0f / area_;
    out->emission_pdf = spread_.active() ? spread_.pdf(-denom) / area_ : -denom * kInvPi / area_;
    out->cos_light = -denom;
  }
  return true;
}

bool AreaLamp::sample_le(const PhotonFrame&, float, Vec2 u_pos, Vec2 u_dir, bool bidirectional,
                         EmittedPhoton* out) const {
  const Vec3 q = point(u_pos);
  // Directions as the radiance leaves (cos, or cos a with a spread): every photon carries the
  // lamp's power.
  const Vec3 local =
      spread_.active() ? spread_.sample_direction(u_dir) : sample_cosine_hemisphere(u_dir);
  set_emitted_ray(q, Frame(axis_).to_world(local), &out->ray);
  const Vec3 radiance = radiance_ * profile(out->ray.direction);
  if (!bidirectional) {
    out->power = radiance * (kPi * area_);
    return !ies_ || !is_black(out->power);
  }
  out->pdf_pos = out->direct_pdf = 1.0f / area_;
  out->cos_light = local.z;
  if (spread_.active()) {
    out->radiance = radiance * spread_.attenuation(local.z);
    out->pdf_dir = spread_.pdf(local.z);
    return local.z > 0.0f && out->pdf_dir > 0.0f;
  }
  out->radiance = radiance;
  out->pdf_dir = local.z * kInvPi;
  return local.z > 0.0f;
}

bool AreaLamp::sample_le_towards(const std::vector<BoundingSphere>& targets, const PhotonFrame&,
                                 float u_pick, Vec2 u_pos, Vec2 u_dir, Sampler&,
                                 EmittedPhoton* out) const {
  // One-sided: directions in the hemisphere below the lamp (or its spread's cone) that head
  // into a target, so targets behind its plane get nothing and those partly behind only their
  // facing part.
  const Vec3 q = point(u_pos);
  Vec3 d;
  float pdf;
  if (!ConeMixture(q, targets, emission_cap()).sample(u_pick, u_dir, &d, &pdf)) return false;
  const float cos_l = dot(d, axis_);
  if (cos_l <= 0.0f) return false;
  set_emitted_ray(q, d, &out->ray);
  const Vec3 radiance = radiance_ * profile(d);
  if (spread_.active()) {
    const float a = spread_.attenuation(cos_l);
    if (!(a > 0.0f)) return false;
    out->power = radiance * (a * cos_l * area_ / pdf);
    return true;
  }
  out->power = radiance * (cos_l * area_ / pdf);
  return true;
}

float AreaLamp::coverage(const std::vector<BoundingSphere>& targets, float) const {
  if (targets.empty()) return 0.0f;
  // The share of the lamp's hemisphere (seen from its centre) that heads into targets; zero
  // when its targets are all behind it.
  return ConeMixture(position_, targets, emission_cap(), radius_).coverage();
}

Cap AreaLamp::emission_cap() const {
  return Cap(axis_, spread_.active() ? static_cast<double>(spread_.half_angle()) : 0.5 * Cap::kPiD);
}

}  // namespace photon
