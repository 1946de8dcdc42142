#include "photon/lights/lamp.h"

#include <cstdio>

#include "photon/lights/area_lamp.h"
#include "photon/lights/point_lamp.h"
#include "photon/lights/sun_lamp.h"
#include "photon/spectral/illuminants.h"

namespace photon {
namespace {

bool finite_light(const Light& l) {
  return l.light_to_world.is_finite() && is_finite(l.color) && std::isfinite(l.power) &&
         std::isfinite(l.radius) && std::isfinite(l.size_x) && std::isfinite(l.size_y) &&
         std::isfinite(l.spot_size) && std::isfinite(l.spot_blend) && std::isfinite(l.sun_angle) &&
         std::isfinite(l.ies_strength);
}

// The profile of a lamp's IES text, read once per cache. A text that cannot be read renders as
// Cycles renders it, a profile of 100 in every direction, with the reason in `warn`.
template <typename Warn>
std::shared_ptr<const IesProfile> read_ies(const Light& l, IesCache* cache, const Warn& warn) {
  IesCache local;
  IesCache& c = cache ? *cache : local;
  const std::string key = std::to_string(static_cast<int>(l.ies_edges)) + l.ies_profile;
  auto it = c.find(key);
  if (it == c.end()) {
    IesRead read;
    std::optional<IesProfile> p;
    if (l.ies_profile.empty()) {
      read.error = "empty";
    } else {
      p = IesProfile::parse(l.ies_profile, &read.error, l.ies_edges);
    }
    read.profile = std::make_shared<const IesProfile>(
        p ? std::move(*p) : IesProfile::constant(IesProfile::kUnreadableValue));
    it = c.emplace(key, std::move(read)).first;
  }
  if (!it->second.error.empty()) {
    const std::string source = l.ies_source.empty() ? "" : " (" + l.ies_source + ")";
    const std::string why = it->second.error == "empty" ? "" : ": " + it->second.error;
    warn("Light '" + l.name + "': its IES profile" + source + " could not be read" + why +
         "; rendered as Cycles renders such a lamp, 100 times the strength in every direction");
  }
  return it->second.profile;
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

SampledSpectrum Lamp::spectrum(const Vec3& rgb, const SampledWavelengths& wl) const {
  const LampSpectrum& s = spectrum_;
  if (s.shape) return s.shape->sample(wl) * std::max(luminance(rgb), 0.0f);
  // Every value a lamp returns is its colour times a non-negative number (the uplift is
  // homogeneous), found from the luminances.
  if (s.uplift) return s.uplift->sample(wl) * (std::max(luminance(rgb), 0.0f) * s.inv_luminance);
  return spectral::illuminant_at(rgb, wl);
}

LightBounds Lamp::bounds() const {
  LightBounds b = extent();
  // The scene's radius only matters for suns, which stay out of the tree.
  b.power = mean_power(power(1.0f));
  return b;
}

std::unique_ptr<Lamp> make_lamp(const Light& l, std::vector<std::string>* warnings,
                                IesCache* ies_cache) {
  auto warn = [&](const std::string& msg) {
    if (warnings) warnings->push_back(msg);
  };
  if (!finite_light(l)) {
    warn("Light '" + l.name + "' has non-finite settings or transform; skipped");
    return nullptr;
  }
  // A blackbody or standard illuminant: its own chromaticity (Rec.709, luminance 1) at the
  // colour's luminance, in both modes.
  LampDescription d;
  d.light = &l;
  Vec3 light_color = l.color;
  if (l.spectrum == LightSpectrum::kBlackbody) {
    const float kelvin =
        std::isfinite(l.temperature) ? std::clamp(l.temperature, 800.0f, 1e5f) : 6500.0f;
    d.spectrum.owned = blackbody_shape(kelvin);
    d.spectrum.shape = d.spectrum.owned.get();
  } else if (l.spectrum == LightSpectrum::kIlluminant) {
    d.spectrum.shape = &spectral::illuminant_spectrum(standard_illuminant(l.illuminant));
  }
  if (d.spectrum.shape)
    light_color = spectral::xyz_to_rec709(spectral::emission_to_xyz(*d.spectrum.shape)) *
                  std::max(luminance(max(l.color, Vec3(0.0f))), 0.0f);
  // In double: colour x power can overflow a float before it is clamped.
  const Vec3 color = max(light_color, Vec3(0.0f));
  double power = std::max(l.power, 0.0f);
  if (l.has_ies) {
    IesEmission ies(read_ies(l, ies_cache, warn), l.ies_strength, l.light_to_world);
    if (l.type == LightType::kPoint || l.type == LightType::kSpot ||
        (l.type == LightType::kArea && l.ies_area_by_direction)) {
      // Its mean over the sphere scales the flux for the range check below.
      power *= ies.integral() * kInv4Pi;
      d.ies.emplace(std::move(ies));
    } else {
      // Cycles 3.x reads an area light's profile along its axis only; a sun's direction is
      // its axis.
      power *= ies.factor(normalize(-l.light_to_world.column(2)));
    }
    if (!(power > 0.0)) {
      warn("Light '" + l.name + "': its IES profile sends no light; it adds no light");
      return nullptr;
    }
  }
  const double brightest = static_cast<double>(max_component(color)) * power;
  if (!(brightest > 0.0)) return nullptr;  // zero power: contributes nothing, costs nothing
  if (brightest > emitter_range().hi) {
    // Scaled, not clipped per channel, so the light keeps its colour.
    power *= emitter_range().hi / brightest;
    const char* unit = l.type == LightType::kSun ? "W/m^2" : "W";
    char text[160];
    std::snprintf(text, sizeof text, " %.3g %s is more than Photon can render; clamped to %.3g %s",
                  l.power, unit, power, unit);
    warn("Light '" + l.name + "': " + (l.type == LightType::kSun ? "strength" : "power") + text);
  }
  d.flux_color = color * static_cast<float>(power);
  if (d.ies) {
    // The profile's mean is in the lamp's directions, not in its flux.
    d.flux_color = d.flux_color * static_cast<float>(4.0 * kPi / d.ies->integral());
  }
  if (!d.spectrum.shape && luminance(color) > 0.0f) {
    d.spectrum.uplift.emplace(spectral::RgbToSpectrumTable::rec709(), color);
    d.spectrum.inv_luminance = 1.0f / luminance(color);
  }
  // Every kind of lamp, by its type in the scene.
  switch (l.type) {
    case LightType::kPoint:
    case LightType::kSpot:
      return make_point_lamp(std::move(d));
    case LightType::kSun:
      return make_sun_lamp(std::move(d));
    case LightType::kArea:
      return make_area_lamp(std::move(d), warnings);
  }
  return nullptr;
}

}  // namespace photon
