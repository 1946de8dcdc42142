// The photon pass of one SPPM iteration (Hachisuka & Jensen 2009, sec. 4): photons leave the
// lights (lamps, emissive meshes, the world: photon_sources.h) and are traced with the shared
// walker's power rules (path_walker.h: Russian roulette by the bounce's albedo). A photon is
// recorded at every vertex after its first bounce that could be a visible point (a diffuse or
// rough glossy lobe): the first hit is direct light, which the camera pass estimates by light
// sampling instead.
//
// Photons are traced in fixed chunks whose records are concatenated in chunk order, and photon
// j of iteration i draws from the stream (seed, i, j), so the records (and their order) do not
// depend on the number of threads.
#pragma once

#include <atomic>
#include <cmath>
#include <cstdint>
#include <vector>

#include "photon/integrators/integrator.h"
#include "photon/integrators/photon_map/photon_sources.h"
#include "photon/spectral/sampled_spectrum.h"

namespace photon {

// A photon at a surface: 40 bytes, full precision (the estimate evaluates the visible point's
// BSDF with wi, so it is not quantised as the photon map's 20-byte record is).
struct SppmPhoton {
  Vec3 p;
  Vec3 wi;    // towards where the photon came from, unit length
  Vec3 beta;  // flux carried if it were the only photon emitted (divide by the count emitted)
  // Spectral mode: beta holds the flux at the iteration's wavelengths 0-2 and beta_w at
  // wavelength 3; its sign bit is set when a dispersive refraction terminated the photon's
  // wavelengths but the hero (0), whose flux then stands alone.
  float beta_w = 0.0f;

  SampledSpectrum spectral_beta() const {
    SampledSpectrum s;
    s[0] = beta.x, s[1] = beta.y, s[2] = beta.z, s[3] = std::fabs(beta_w);
    return s;
  }
  bool terminated() const { return std::signbit(beta_w); }
  static SppmPhoton spectral(const Vec3& p, const Vec3& wi, const SampledSpectrum& beta,
                             bool terminated) {
    return {p, wi, Vec3(beta[0], beta[1], beta[2]), terminated ? -0.0f : beta[3]};
  }
};
static_assert(spectral::kSpectrumSamples == 4, "SppmPhoton stores four wavelengths");

struct SppmPhotonPass {
  std::vector<SppmPhoton> photons;  // in (photon index, bounce) order
  uint64_t rays = 0;
  bool cancelled = false;
};

// Traces photons [0, count) of `iteration`; spectral photons at the iteration's wavelengths
// `wl` when given.
SppmPhotonPass trace_sppm_photons(const RenderContext& context, const PhotonSources& sources,
                                  uint32_t iteration, uint64_t count,
                                  const std::atomic<bool>& cancel,
                                  const SampledWavelengths* wl = nullptr);

}  // namespace photon
