// An area light's spread (Object Data > Light > Spread): the emission of a soft box whose
// grid of slats hides the lamp from directions far from its axis. Cycles models the share of
// the lamp not hidden by the slats at angle theta from the axis, for a spread of 2h, as
// (tan h - tan theta), normalised so the lamp's power stays that of the Lambertian lamp:
//
//   L(theta) = L * a(theta),  a(theta) = max(tan h - tan theta, 0) / (tan h - h),
//
// since the integral of cos * a over the hemisphere is pi, as that of cos alone (Cycles:
// scene/light.cpp, kernel/light/area.h; the normalisation integrates
// cos x (1 - tan x / tan h) sin x over [0, h] to (tan h - h) / (2 tan h)).
// Cycles 3.x clamps the spread to at least 1 degree; so does Photon in every Blender.
#pragma once

#include "photon/base/math.h"

namespace photon {

class AreaSpread {
 public:
  // `spread`: the full angle in radians; the whole hemisphere (pi) or more leaves a Lambertian
  // lamp, and NaN is read as that.
  explicit AreaSpread(float spread);

  static constexpr float kMinSpread = 1.0f * kPi / 180.0f;

  // Whether it narrows the emission at all.
  bool active() const { return active_; }
  float half_angle() const { return half_; }
  float tan_half_angle() const { return tan_half_; }
  // a(theta) above for the cosine of the angle to the lamp's axis; 1 when not active.
  float attenuation(float cos_theta) const;
  // A direction in the lamp's frame (z: its axis) distributed as cos * a / pi, by inverting
  // the distribution of tan theta; its solid-angle density is pdf(z).
  Vec3 sample_direction(Vec2 u) const;
  float pdf(float cos_theta) const { return cos_theta * attenuation(cos_theta) * kInvPi; }

 private:
  bool active_ = false;
  float half_ = 0.5f * kPi;
  float tan_half_ = 0.0f;
  float normalize_ = 1.0f;  // 1 / (tan h - h)
};

}  // namespace photon
