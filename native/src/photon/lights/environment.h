// An environment (an HDRI world, a sky): radiance as any function of direction, importance
// sampled through a piecewise-constant table over an equirectangular grid (Pharr, Jakob and
// Humphreys, "Physically Based Rendering" 4th ed., sec. 12.5.2 ImageInfiniteLight; the layout
// Cycles' background map uses: width x width/2 texels).
//
// The table: the mean of the three channels of the function (as Cycles' background map and
// Photon's light selection weigh colours), evaluated at the centre of each texel's solid angle
// (mid phi, mid cos(theta)), or at k x k such points per texel and averaged, times the texel's
// solid angle (proportional to sin(theta) at its centre). Rows are picked by their sums (the
// marginal), a texel within the row by its value (the conditional), then a direction uniform in
// solid angle inside the texel (phi and cos(theta) uniform), so the density of a direction in
// texel (i, j) is exactly value(i, j) / sum of value x solid angle.
//
// The table sees the function only at its sample points: a feature between them (a sun smaller
// than a texel) would get no density and photons would never leave it. So the density is a
// defensive mixture (Hesterberg 1995, "Weighted average importance sampling and defensive
// mixture distributions") with 1/16 of uniform sphere sampling: positive for every direction,
// which keeps light-sampling-only estimates (photon emission, shadow catchers) unbiased.
#pragma once

#include <algorithm>
#include <atomic>
#include <functional>
#include <vector>

#include "photon/base/distribution.h"
#include "photon/lights/emitter.h"

namespace photon {

// Radiance arriving from `direction` (world space, unit, pointing away from the scene).
using EnvironmentFunction = std::function<Vec3(const Vec3& direction)>;

class EnvironmentEmitter final : public Emitter {
 public:
  static constexpr int kDefaultWidth = 1024;  // Cycles' default map resolution
  static constexpr float kUniformShare = 1.0f / 16.0f;

  // `radiance` must be thread-safe: the table is built in parallel (TBB; each texel's value
  // depends on its own evaluations only, so the table does not depend on the thread count).
  // `width` is clamped to [4, 16384] and made even; the height is width / 2. `subsamples`
  // (clamped to [1, 8]) evaluations per texel axis. When `cancel` becomes true the remaining
  // rows are left black (the render is being abandoned; a row takes well under 100 ms).
  explicit EnvironmentEmitter(EnvironmentFunction radiance, int width = kDefaultWidth,
                              int subsamples = 1, const std::atomic<bool>* cancel = nullptr);

  EmitterKind kind() const override { return EmitterKind::kWorld; }
  // A world whose nodes give one colour in every direction (an RGB node into the Background)
  // is lit as the uniform world is: by BSDF samples alone, which for a constant radiance are
  // the better strategy (cosine sampling is exact for an unshadowed diffuse surface) and save
  // a shadow ray per shading point. Its radiance is still the function's.
  uint8_t flags() const override {
    return kEmitterBidirectional | kEmitterInfinite | (flat_ ? kEmitterBsdfSampledOnly : 0);
  }
  LightSampleU draw_li(Sampler& sampler) const override {
    return flat_ ? LightSampleU{} : Emitter::draw_li(sampler);
  }
  // One 2D sample: a direction from the table; pdf in solid angle, weight L / pdf with L the
  // function's value (not the table's). Bidirectional estimators sample it alike; direct
  // lighting does not sample a flat world.
  bool sample_li(const Vec3& p, const LightSampleU& u, const PhotonFrame* bidirectional,
                 LightSample* out) const override;
  float pdf_li_at_infinity(const Vec3& p, const Vec3& direction) const override {
    return flat_ ? 0.0f : Emitter::pdf_li_at_infinity(p, direction);
  }
  // Every evaluation that built the table gave the same colour.
  bool flat() const { return flat_; }
  bool has_area() const override { return true; }
  Vec3 radiance_at_infinity(const Vec3& direction, bool bidirectional = false) const override;
  float pdf_at_infinity(const Vec3& direction, bool bidirectional = false) const override;
  // The flux through a disc of radius R covering the scene: pi R^2 times the integral of the
  // radiance over the sphere (as the table estimates it).
  Vec3 power(float scene_radius) const override;
  // Jensen 2001 sec. 5.1 for lights at infinity: a direction w from the table, a point on the
  // disc of the scene's bounding sphere perpendicular to it, flux L(w) / pdf(w) x pi R^2.
  bool sample_le(const PhotonFrame& frame, float u_rest, Vec2 u_pos, Vec2 u_dir, bool bidirectional,
                 EmittedPhoton* out) const override;
  // Caustic photons: a direction from the table, then a point of the targets' discs across it
  // (as the sun's beam, sun_lamp.h): flux L(w) / (pdf(w) x area density).
  bool sample_le_towards(const std::vector<BoundingSphere>& targets, const PhotonFrame& frame,
                         float u_pick, Vec2 u_pos, Vec2 u_dir, Sampler& sampler,
                         EmittedPhoton* out) const override;
  // The targets' cross-sections over the scene's disc (a sphere's is the same from any side).
  float coverage(const std::vector<BoundingSphere>& targets, float scene_radius) const override;
  LightBounds bounds() const override;

  // The map width a requested one is rendered with: in [4, 16384] and even.
  static int clamped_width(int width) { return std::clamp(width, 4, 16384) & ~1; }

  // A direction for `u` in [0, 1)^2 and its solid-angle density (0 only if `u` is invalid).
  bool sample_direction(Vec2 u, Vec3* direction, float* pdf) const;
  // The table's estimate of the integral of the radiance over the sphere, per channel.
  Vec3 integral() const { return integral_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  // Density of the table part alone for texel (row, col).
  float map_pdf(int row, int col) const {
    return static_cast<float>(static_cast<double>(value_[static_cast<size_t>(row) * width_ + col]) *
                              inv_total_);
  }
  float mixed_pdf(int row, int col) const;

  EnvironmentFunction radiance_;
  int width_ = 0, height_ = 0;
  std::vector<double> z_edge_;  // cos(theta) at each row's edges: height_ + 1 values, 1 .. -1
  std::vector<float> value_;  // per texel: sampling weight, the largest mean channel value over it
                              // and its neighbours (before the solid angle)
  Distribution1D rows_;
  std::vector<Distribution1D> columns_;
  double inv_total_ = 0.0;      // 1 / sum of value x solid angle (0: the table is black)
  float uniform_share_ = 1.0f;  // kUniformShare, or 1 when the table is black
  Vec3 integral_{0.0f};
  bool flat_ = false;
};

}  // namespace photon
