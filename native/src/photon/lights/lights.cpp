#include "photon/lights/lights.h"

#include <cstdio>

#include "photon/base/sampling.h"
#include "photon/spectral/illuminants.h"

namespace photon {
namespace {

float smoothstep01(float x) {
  x = std::clamp(x, 0.0f, 1.0f);
  return x * x * (3.0f - 2.0f * x);
}

bool finite_light(const Light& l) {
  return l.light_to_world.is_finite() && is_finite(l.color) && std::isfinite(l.power) &&
         std::isfinite(l.radius) && std::isfinite(l.size_x) && std::isfinite(l.size_y) &&
         std::isfinite(l.spot_size) && std::isfinite(l.spot_blend) && std::isfinite(l.sun_angle);
}

spectral::Illuminant standard_illuminant(StandardIlluminant i) {
  switch (i) {
    case StandardIlluminant::kA:
      return spectral::Illuminant::kA;
    case StandardIlluminant::kF2:
      return spectral::Illuminant::kF2;
    case StandardIlluminant::kF7:
      return spectral::Illuminant::kF7;
    case StandardIlluminant::kF11:
      return spectral::Illuminant::kF11;
    default:
      return spectral::Illuminant::kD65;
  }
}

// Planck's law at `kelvin` on the 1 nm table, scaled to luminance 1.
std::shared_ptr<const spectral::TabulatedSpectrum> blackbody_shape(float kelvin) {
  auto s = std::make_shared<spectral::TabulatedSpectrum>(spectral::TabulatedSpectrum::from_function(
      [kelvin](float lambda) { return spectral::blackbody_normalized(lambda, kelvin); }));
  const float y = spectral::emission_to_xyz(*s).y;
  if (y > 0.0f) s->scale(1.0f / y);
  return s;
}

}  // namespace

LightSet::LightSet(const std::vector<Light>& lights, std::vector<std::string>* warnings) {
  auto warn = [&](const std::string& msg) {
    if (warnings) warnings->push_back(msg);
  };
  for (const Light& l : lights) {
    if (!finite_light(l)) {
      warn("Light '" + l.name + "' has non-finite settings or transform; skipped");
      continue;
    }
    // A blackbody or standard illuminant: its own chromaticity (Rec.709, luminance 1) at the
    // colour's luminance, in both modes.
    Spectrum spectrum;
    Vec3 light_color = l.color;
    if (l.spectrum == LightSpectrum::kBlackbody) {
      const float kelvin =
          std::isfinite(l.temperature) ? std::clamp(l.temperature, 800.0f, 1e5f) : 6500.0f;
      shapes_.push_back(blackbody_shape(kelvin));
      spectrum.shape = shapes_.back().get();
    } else if (l.spectrum == LightSpectrum::kIlluminant) {
      spectrum.shape = &spectral::illuminant_spectrum(standard_illuminant(l.illuminant));
    }
    if (spectrum.shape)
      light_color = spectral::xyz_to_rec709(spectral::emission_to_xyz(*spectrum.shape)) *
                    std::max(luminance(max(l.color, Vec3(0.0f))), 0.0f);
    // In double: colour x power can overflow a float before it is clamped.
    const Vec3 color = max(light_color, Vec3(0.0f));
    double power = std::max(l.power, 0.0f);
    const double brightest = static_cast<double>(max_component(color)) * power;
    if (!(brightest > 0.0)) continue;  // zero power: contributes nothing, costs nothing
    if (brightest > emitter_range().hi) {
      // Scaled, not clipped per channel, so the light keeps its colour.
      power *= emitter_range().hi / brightest;
      const char* unit = l.type == LightType::kSun ? "W/m^2" : "W";
      char text[160];
      std::snprintf(text, sizeof text,
                    " %.3g %s is more than Photon can render; clamped to %.3g %s", l.power, unit,
                    power, unit);
      warn("Light '" + l.name + "': " + (l.type == LightType::kSun ? "strength" : "power") + text);
    }
    const Vec3 flux_color = color * static_cast<float>(power);

    Prepared p{};
    p.type = l.type;
    p.shape = l.shape;
    p.visibility = l.visibility;
    p.position = l.light_to_world.column(3);
    p.axis = normalize(-l.light_to_world.column(2));
    p.radius = std::max(l.radius, 0.0f);
    switch (l.type) {
      case LightType::kPoint:
      case LightType::kSpot: {
        p.intensity = flux_color * kInv4Pi;
        p.area = kPi * p.radius * p.radius;
        p.radiance = p.area > 0.0f ? p.intensity / p.area : Vec3(0.0f);
        if (!is_finite(p.radiance) || (p.radius > 0.0f && !(p.area > 0.0f))) {
          // A radius whose disc area under- or overflows a float: a point for every ray.
          p.radius = p.area = 0.0f;
          p.radiance = Vec3(0.0f);
        }
        // Cycles: cos_half_spot_angle = cos(spot_size / 2), smooth = (1 - cos) * blend.
        const float half = std::clamp(l.spot_size, 1e-4f, kPi) * 0.5f;
        p.cos_half_spot = std::cos(half);
        p.spot_smooth = (1.0f - p.cos_half_spot) * std::clamp(l.spot_blend, 0.0f, 1.0f);
        break;
      }
      case LightType::kSun: {
        p.irradiance = flux_color;
        const float half = std::clamp(l.sun_angle, 0.0f, kPi) * 0.5f;
        p.sun_cos_max = std::cos(half);
        const float tan_half = std::tan(std::min(half, 1.5f));
        p.radiance = tan_half > 1e-6f ? flux_color / (kPi * tan_half * tan_half) : Vec3(0.0f);
        break;
      }
      case LightType::kArea: {
        p.half_u = l.light_to_world.column(0) * (0.5f * std::max(l.size_x, 0.0f));
        p.half_v = l.light_to_world.column(1) * (0.5f * std::max(l.size_y, 0.0f));
        const float lu = length(p.half_u), lv = length(p.half_v);
        p.area = l.shape == AreaShape::kRectangle ? 4.0f * lu * lv : kPi * lu * lv;
        // Zero or so small its radiance overflows; a tiny light of a tiny scene is still a light.
        if (!(p.area > 0.0f) || !is_finite(flux_color * (0.25f / p.area))) {
          warn("Area light '" + l.name + "' has zero size; skipped");
          continue;
        }
        p.radiance = flux_color * (0.25f / p.area);
        break;
      }
    }
    if (!spectrum.shape && luminance(color) > 0.0f) {
      spectrum.uplift.emplace(spectral::RgbToSpectrumTable::rec709(), color);
      spectrum.inv_luminance = 1.0f / luminance(color);
    }
    lights_.push_back(p);
    spectra_.push_back(std::move(spectrum));
  }
}

SampledSpectrum LightSet::spectrum(size_t index, const Vec3& rgb,
                                   const SampledWavelengths& wl) const {
  const Spectrum& s = spectra_[index];
  if (s.shape) return s.shape->sample(wl) * std::max(luminance(rgb), 0.0f);
  // Every value a light returns is its colour times a non-negative number (the uplift is
  // homogeneous), found from the luminances.
  if (s.uplift) return s.uplift->sample(wl) * (std::max(luminance(rgb), 0.0f) * s.inv_luminance);
  return spectral::illuminant_at(rgb, wl);
}

SampledSpectrum LightSet::distant_radiance(const Vec3& direction, uint32_t mask,
                                           const SampledWavelengths& wl) const {
  SampledSpectrum sum(0.0f);
  for (size_t i = 0; i < lights_.size(); ++i) {
    const Prepared& l = lights_[i];
    if (l.type != LightType::kSun || !(l.visibility & mask) || l.sun_cos_max >= 1.0f) continue;
    if (dot(-direction, l.axis) >= l.sun_cos_max) sum += spectrum(i, l.radiance, wl);
  }
  return sum;
}

// Cycles 3.x spot_attenuation: the cosine to the axis, faded to zero over the blend region.
float LightSet::spot_attenuation(const Prepared& l, const Vec3& dir_from_light) {
  const float c = dot(l.axis, dir_from_light);
  if (c <= l.cos_half_spot) return 0.0f;
  const float t = c - l.cos_half_spot;
  if (l.spot_smooth > 0.0f && t < l.spot_smooth) return c * smoothstep01(t / l.spot_smooth);
  return c;
}

bool LightSet::sample(size_t index, const Vec3& p, Vec2 u, LightSample* out) const {
  const Prepared& l = lights_[index];
  switch (l.type) {
    case LightType::kPoint:
    case LightType::kSpot: {
      Vec3 q = l.position;
      float cos_light = 1.0f;
      if (l.radius > 0.0f) {
        // A disc of the light's radius facing the shaded point (Cycles 3.x "sphere" light).
        const Vec3 n = normalize(p - l.position);
        const Vec2 d = sample_concentric_disk(u);
        const Frame frame(n);
        q = l.position + (frame.t * d.x + frame.b * d.y) * l.radius;
        cos_light = -1.0f;  // computed below once the direction is known
      }
      const Vec3 to_light = q - p;
      const float dist2 = length_squared(to_light);
      if (!(dist2 > 0.0f)) return false;
      const float dist = std::sqrt(dist2);
      out->wi = to_light / dist;
      out->distance = dist;
      if (l.radius > 0.0f) cos_light = std::max(0.0f, dot(-out->wi, normalize(p - l.position)));
      float attenuation = cos_light;
      if (l.type == LightType::kSpot) attenuation *= spot_attenuation(l, -out->wi);
      if (attenuation <= 0.0f) return false;
      out->weight = l.intensity * (attenuation / dist2);
      out->pdf = l.radius > 0.0f ? dist2 / (cos_light * l.area) : 0.0f;
      return true;
    }
    case LightType::kSun: {
      const Frame frame(-l.axis);
      out->wi =
          l.sun_cos_max < 1.0f ? frame.to_world(sample_uniform_cone(u, l.sun_cos_max)) : -l.axis;
      out->distance = INFINITY;
      out->weight = l.irradiance;
      return true;
    }
    case LightType::kArea: {
      Vec3 q;
      if (l.shape == AreaShape::kRectangle) {
        q = l.position + l.half_u * (2.0f * u.x - 1.0f) + l.half_v * (2.0f * u.y - 1.0f);
      } else {
        const Vec2 d = sample_concentric_disk(u);
        q = l.position + l.half_u * d.x + l.half_v * d.y;
      }
      const Vec3 to_light = q - p;
      const float dist2 = length_squared(to_light);
      if (!(dist2 > 0.0f)) return false;
      const float dist = std::sqrt(dist2);
      out->wi = to_light / dist;
      out->distance = dist;
      const float cos_light = dot(-out->wi, l.axis);  // one-sided: emits along its axis only
      if (cos_light <= 0.0f) return false;
      out->weight = l.radiance * (cos_light * l.area / dist2);
      out->pdf = dist2 / (cos_light * l.area);
      return true;
    }
  }
  return false;
}

bool LightSet::intersect(const Ray& ray, float tmax, uint32_t mask, float* t_hit, Vec3* radiance,
                         size_t* index) const {
  bool found = false;
  float best = tmax;
  for (size_t i = 0; i < lights_.size(); ++i)
    if (intersect_one(i, ray, best, mask, &best, radiance)) {
      found = true;
      if (index) *index = i;
    }
  if (found) *t_hit = best;
  return found;
}

bool LightSet::intersect_one(size_t index, const Ray& ray, float tmax, uint32_t mask, float* t_hit,
                             Vec3* radiance) const {
  const Prepared& l = lights_[index];
  if (!(l.visibility & mask)) return false;
  bool found = false;
  float best = tmax;
  switch (l.type) {
    case LightType::kPoint:
    case LightType::kSpot: {
      if (l.radius <= 0.0f) break;
      const Vec3 oc = ray.origin - l.position;
      const float b = dot(oc, ray.direction);
      const float c = length_squared(oc) - l.radius * l.radius;
      const float disc = b * b - c;
      if (disc < 0.0f) break;
      const float s = std::sqrt(disc);
      float t = -b - s;
      if (t <= ray.tmin) t = -b + s;
      if (t <= ray.tmin || t >= best) break;
      Vec3 le = l.radiance;
      if (l.type == LightType::kSpot) le *= spot_attenuation(l, -ray.direction);
      best = t;
      *radiance = le;
      found = true;
      break;
    }
    case LightType::kArea: {
      const float denom = dot(ray.direction, l.axis);
      if (denom >= 0.0f) break;  // seen from behind: the back of an area light is dark
      const float t = dot(l.position - ray.origin, l.axis) / denom;
      if (t <= ray.tmin || t >= best) break;
      const Vec3 d = ray.origin + ray.direction * t - l.position;
      const float su = dot(d, l.half_u) / length_squared(l.half_u);
      const float sv = dot(d, l.half_v) / length_squared(l.half_v);
      const bool inside = l.shape == AreaShape::kRectangle
                              ? std::fabs(su) <= 1.0f && std::fabs(sv) <= 1.0f
                              : su * su + sv * sv <= 1.0f;
      if (!inside) break;
      best = t;
      *radiance = l.radiance;
      found = true;
      break;
    }
    case LightType::kSun:
      break;  // at infinity: see distant_radiance()
  }
  if (found) *t_hit = best;
  return found;
}

bool LightSet::has_area(size_t index) const {
  const Prepared& l = lights_[index];
  return l.type == LightType::kArea ||
         ((l.type == LightType::kPoint || l.type == LightType::kSpot) && l.radius > 0.0f);
}

bool LightSet::eval(size_t index, const Vec3& p, const Vec3& wi, Vec3* radiance, float* distance,
                    float* pdf) const {
  const Prepared& l = lights_[index];
  if (!has_area(index)) return false;
  // The surface sample() draws from: the area light itself, or the disc of the light's radius
  // facing p.
  const Vec3 n = l.type == LightType::kArea ? l.axis : normalize(p - l.position);
  const float denom = dot(wi, n);
  if (!(denom < 0.0f)) return false;
  const float t = dot(l.position - p, n) / denom;
  if (!(t > 0.0f)) return false;
  const Vec3 d = p + wi * t - l.position;
  bool inside;
  if (l.type == LightType::kArea) {
    const float su = dot(d, l.half_u) / length_squared(l.half_u);
    const float sv = dot(d, l.half_v) / length_squared(l.half_v);
    inside = l.shape == AreaShape::kRectangle ? std::fabs(su) <= 1.0f && std::fabs(sv) <= 1.0f
                                              : su * su + sv * sv <= 1.0f;
  } else {
    inside = length_squared(d) <= l.radius * l.radius;
  }
  if (!inside) return false;
  const float cos_light = -denom;
  Vec3 le = l.radiance;
  if (l.type == LightType::kSpot) le *= spot_attenuation(l, -wi);
  *radiance = le;
  *distance = t;
  *pdf = t * t / (cos_light * l.area);
  return true;
}

Vec3 LightSet::distant_radiance(const Vec3& direction, uint32_t mask) const {
  Vec3 sum(0.0f);
  for (const Prepared& l : lights_) {
    if (l.type != LightType::kSun || !(l.visibility & mask) || l.sun_cos_max >= 1.0f) continue;
    if (dot(-direction, l.axis) >= l.sun_cos_max) sum += l.radiance;
  }
  return sum;
}

}  // namespace photon
