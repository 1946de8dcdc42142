// Blender's lamps, in the units Cycles gives them, so an artist's watts mean the same in both
// engines. What every lamp shares is here: its visibility flags, its spectrum, and the checks
// and clamps a lamp of the scene passes before it renders (make_lamp). Each kind is one class
// in its own file: point_lamp.h (point and spot, with or without a radius), area_lamp.h,
// sun_lamp.h.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "photon/lights/emitter.h"
#include "photon/lights/ies_profile.h"
#include "photon/scene/scene.h"
#include "photon/spectral/rgb_uplift.h"

namespace photon {

// A lamp's spectrum: a tabulated shape of luminance 1 (a blackbody, a CIE illuminant), or its
// colour uplifted once.
struct LampSpectrum {
  std::shared_ptr<const spectral::TabulatedSpectrum> owned;  // a blackbody's table
  const spectral::TabulatedSpectrum* shape = nullptr;
  std::optional<spectral::RgbIlluminantSpectrum> uplift;
  float inv_luminance = 0.0f;  // 1 / luminance of the colour the uplift was made from
};

class Lamp : public Emitter {
 public:
  EmitterKind kind() const override { return EmitterKind::kLamp; }
  // Ray kinds that see the lamp (Object > Visibility): kVisibleCamera, ...
  uint32_t visibility() const { return visibility_; }
  // Spectral mode: its spectrum scaled to the luminance of `rgb` (any value it returned: its
  // radiance, intensity, flux or a sample weight, all multiples of its colour), or its colour's
  // illuminant uplift scaled alike.
  SampledSpectrum spectrum(const Vec3& rgb, const SampledWavelengths& wl) const override;
  // For the light tree: the lamp's bounds with its power.
  LightBounds bounds() const override;

 protected:
  Lamp(uint32_t visibility, LampSpectrum spectrum)
      : visibility_(visibility), spectrum_(std::move(spectrum)) {}
  // Where it is and which way it shines; bounds() adds the power.
  virtual LightBounds extent() const = 0;

 private:
  uint32_t visibility_;
  LampSpectrum spectrum_;
};

// What every kind of lamp is made from: the scene's description, its flux colour (colour times
// power, clamped into the range Photon renders, in W per channel; a sun's W/m^2) and its
// spectrum.
struct LampDescription {
  const Light* light = nullptr;
  Vec3 flux_color{0.0f};
  LampSpectrum spectrum;
  // Lamps with an IES profile read per direction (ies_profile.h): flux_color is then the flux
  // the lamp would have with a profile of 1 in every direction. Suns, and area lamps as Cycles
  // 3.x reads them, take their profile's one value along their axis into flux_color instead.
  std::optional<IesEmission> ies;
};

// The lamp of `light`, or null when it is skipped (non-finite settings, zero power or size),
// with a warning in `warnings` when the user should know why. IES profiles are read once per
// `ies_cache` (optional).
std::unique_ptr<Lamp> make_lamp(const Light& light, std::vector<std::string>* warnings,
                                IesCache* ies_cache = nullptr);

}  // namespace photon
