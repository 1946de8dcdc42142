// A lamp's IES profile (IES Texture node feeding its Emission strength): the photometric table
// of an IESNA LM-63 file, read and interpolated as Cycles does, so a lamp renders the same in
// both engines.
//
//  - Units: the file's candela times its multiplier and ballast factors, times 4 pi / 177.83
//    (177.83 lm/W, the luminous efficacy of D65, turns candela into W/sr; 4 pi makes it the
//    "watts" of a lamp's strength). A 1000 cd direction multiplies the lamp's power by 70.7.
//  - Angles: photometric types A, B and C are brought to type C's, vertical angle v from the
//    lamp's -Z axis (its "down", where a spot points) and horizontal angle h around it; files
//    that give one quadrant or one half are mirrored to the whole circle.
//  - Direction d in the lamp's frame: v = acos(-d.z), h = atan2(d.x, d.y) + pi.
//  - Interpolation: Catmull-Rom across v, then across h, clamped at zero; outside the table's
//    angles the lamp sends nothing. Past the table's first and last rows the four-point stencil
//    takes what the Blender's Cycles takes (IesEdges): 3.x-4.0 repeat the edge row and always
//    wrap around the circle; 4.1-5.0 read zero unless the table wraps there (a full circle, a
//    pole); 5.1+ repeat the edge row unless it wraps. A downlight table ending at 90 degrees
//    differs by up to 20% between them in its last interval.
// (Cycles: util/ies.cpp, kernel/util/ies.h.)
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "photon/base/distribution.h"
#include "photon/base/math.h"
#include "photon/scene/scene.h"

namespace photon {

class IesProfile {
 public:
  // The profile of an LM-63 text, or nullopt with the reason in `error`.
  static std::optional<IesProfile> parse(std::string_view text, std::string* error,
                                         IesEdges edges = IesEdges::kHold);
  // A profile of one value in every direction: Cycles renders a profile it cannot read as 100.
  static IesProfile constant(float value);
  static constexpr float kUnreadableValue = 100.0f;

  // W/sr per watt of lamp strength along `local` (a unit direction in the lamp's frame), and
  // the same at angles (h, v) in radians.
  float eval(const Vec3& local) const;
  float eval_angles(float h, float v) const;
  // Integral of eval over the sphere of directions.
  float integral() const { return integral_; }
  // A local direction distributed nearly as eval (every direction with some chance), and its
  // solid-angle density; tabulated on a grid of 1 x 5 degree cells of (v, h).
  Vec3 sample(Vec2 u, float* pdf) const;
  float pdf(const Vec3& local) const;

  static constexpr int kVerticalCells = 180;
  static constexpr int kHorizontalCells = 72;

 private:
  IesProfile() = default;
  void tabulate();
  float vertical(int v, float v_frac, int h) const;
  float at(int h, int v) const { return values_[static_cast<size_t>(h) * v_.size() + v]; }
  int cell(const Vec3& local) const;

  std::vector<float> h_, v_;   // radians, increasing
  std::vector<float> values_;  // h-major, h_.size() x v_.size()
  bool wrap_h_ = false, wrap_v_low_ = false, wrap_v_high_ = false;
  IesEdges edges_ = IesEdges::kHold;
  float constant_ = -1.0f;  // >= 0: the constant profile
  Distribution1D cells_;
  std::vector<float> cell_pdf_;  // solid-angle density inside each cell
  float integral_ = 0.0f;
};

// Profiles already read while the lamps of one scene are made, by their text: lamps that share
// a file share its tables. A text that could not be read keeps the reason.
struct IesRead {
  std::shared_ptr<const IesProfile> profile;
  std::string error;
};
using IesCache = std::unordered_map<std::string, IesRead>;

// A profile on a lamp: its strength and the lamp's frame.
class IesEmission {
 public:
  IesEmission(std::shared_ptr<const IesProfile> profile, float strength,
              const Transform& light_to_world);

  // The factor along a unit world direction leaving the lamp.
  float factor(const Vec3& dir) const { return strength_ * profile_->eval(to_local(dir)); }
  // Integral of factor over the sphere of directions.
  float integral() const { return strength_ * profile_->integral(); }
  Vec3 sample(Vec2 u, float* pdf) const { return to_world(profile_->sample(u, pdf)); }
  float pdf(const Vec3& dir) const { return profile_->pdf(to_local(dir)); }

 private:
  Vec3 to_local(const Vec3& d) const { return {dot(d, x_), dot(d, y_), dot(d, z_)}; }
  Vec3 to_world(const Vec3& l) const { return x_ * l.x + y_ * l.y + z_ * l.z; }

  std::shared_ptr<const IesProfile> profile_;
  float strength_;
  Vec3 x_, y_, z_;  // the lamp's axes, orthonormal
};

}  // namespace photon
