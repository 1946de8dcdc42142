// Stochastic progressive photon mapping (Hachisuka & Jensen 2009, "Stochastic Progressive
// Photon Mapping"): each iteration traces a photon pass (sppm_photons.h), hashes its photons in
// a kd-tree (photon_kdtree.h), then traces one camera path per pixel to its visible point
// (sppm_camera.h), which gathers the photons within the pixel's radius R. The pixel's statistics
// then follow eqs. 6-8 of the paper (Hachisuka et al. 2008, eqs. 7-9, with Phi and M of this
// iteration's visible point):
//   N' = N + alpha M,   R' = R sqrt(N' / (N + M)),   tau' = (tau + Phi) R'^2 / R^2,
// and the pixel's radiance after k iterations of P photons each is
//   L = (direct light summed over iterations) / k + tau / (k P pi R^2),
// which converges as R shrinks (alpha in (0, 1)).
//
// Memory: kBytesPerPixel of pixel state, plus the current iteration's photons (40 bytes per
// recorded bounce) and their kd-tree's split axes (1 byte per photon), freed before the next
// iteration's photons are traced.
//
// The integrator keeps the pixel state of its film between render() calls, so the viewport
// refines SPPM's own image pass after pass, and N iterations in several calls equal N in one.
//
// Determinism: camera samples draw from (seed, pixel, iteration) streams and photons from
// (seed, iteration, photon index); each pixel is updated by one thread from its own visible
// point, which sums photons in the kd-tree's fixed order. The image after k iterations is the
// same bits for any thread count, and tiles play no part. A render border does not change a
// pixel either: pixel streams are indexed in the full frame and the automatic radius of pixels
// that see nothing is a median over the whole frame.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "photon/integrators/integrator.h"
#include "photon/integrators/photon_map/photon_sources.h"
#include "photon/integrators/registry.h"
#include "photon/integrators/sppm/sppm_photons.h"

namespace photon {

// Peak bytes per photon recorded in an iteration: the chunks' records and their concatenation
// (2 x 40 bytes) exist together for a moment; the kd-tree then takes the array and adds 1 byte.
constexpr double kSppmPeakBytesPerRecord = 2.0 * sizeof(SppmPhoton) + 1.0;
// Share of the memory available at the start that one iteration's photons may use.
constexpr double kSppmMemoryFraction = 0.5;

// Photons per iteration that fit `budget_bytes` when each emitted photon records
// `records_per_photon` photons on average: `requested`, or fewer (at least 1). A budget of 0
// (unknown) keeps `requested`.
uint64_t sppm_photons_that_fit(uint64_t requested, double records_per_photon, double budget_bytes);

// The per-pixel state (Hachisuka & Jensen 2009, sec. 4).
struct SppmPixel {
  Vec3 direct{0.0f};  // direct light summed over iterations
  Vec3 tau{0.0f};     // accumulated flux, eq. 8 (camera throughput included)
  float n = 0.0f;     // accumulated photon count N, eq. 6
  float radius = 0.0f;
  float alpha = 0.0f;  // coverage summed over iterations
};

class SppmIntegrator final : public Integrator {
 public:
  static constexpr size_t kBytesPerPixel = sizeof(SppmPixel);

  // The photon sources, and a pilot trace of a few thousand photons measuring how many each
  // records: when sppm_photons_per_iteration would not fit kSppmMemoryFraction of the available
  // memory, fewer are traced per iteration and a warning says so.
  void prepare(const RenderContext& context, const PrepareControl& control) override;
  int passes(const RenderSettings& settings) const override { return settings.sppm_iterations; }
  // Iterations [first_pass, end_pass) over the film (a first pass of 0 starts afresh: initial
  // radii, and the data passes when the film keeps them), stopping after the iteration that
  // passes sppm_time. After each, the film holds the image (Direct: direct light, Indirect: the
  // photon estimate, caustics included; Caustics and Photon Map black) and control.update sees
  // the whole film.
  int render(const RenderContext& context, Film& film, const RenderControl& control) override;
  IterationStats render_stats() const override { return stats_; }
  uint64_t photons_per_iteration() const { return photons_per_iteration_; }
  const std::vector<SppmPixel>& pixels() const { return pixels_; }

 private:
  // R for every pixel before the first iteration: the setting (clamped to the meaningful
  // range of merge_radius.h, with a warning), or kAutoRadiusPixels pixel footprints at the
  // surface the pixel's centre sees.
  void initial_radii(const RenderContext& context, const Film& film, const RenderControl& control);
  // Iteration `iteration` of the film's pixels; false when cancelled during it (its pixels are
  // then partly updated and the film is not to be iterated or read again).
  bool iterate(const RenderContext& context, Film& film, uint32_t iteration,
               const std::atomic<bool>& cancel);
  // The image after `iterations` iterations into the film's sums.
  void write_film(Film& film, int iterations) const;

  std::unique_ptr<PhotonSources> sources_;
  std::vector<SppmPixel> pixels_;
  uint64_t photons_per_iteration_ = 0;
  IterationStats stats_;
};

IntegratorInfo sppm_integrator_info();

}  // namespace photon
