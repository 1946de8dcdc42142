#include "photon/integrators/sppm/sppm_photons.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "photon/integrators/camera_path.h"
#include "photon/integrators/path_walker.h"
#include "photon/integrators/sppm/sppm_camera.h"

namespace photon {
namespace {

constexpr uint64_t kChunk = 1024;                       // photons per parallel work item
constexpr uint64_t kPhotonStream = 0x5350504D50484F54;  // "SPPMPHOT"
// Roulette ends photon paths long before this; it only bounds a path between perfect mirrors.
constexpr int kMaxPhotonBounces = 64;

struct ChunkOutput {
  std::vector<SppmPhoton> photons;
  uint64_t rays = 0;
};

// Records the photon at every vertex after the first that could be a visible point
// (sppm_camera.h: a diffuse or rough glossy lobe); photons elsewhere could only leak into
// visible points of nearby surfaces.
struct SppmPhotonVisitor {
  const RenderContext& context;
  ChunkOutput* out;
  int wavelengths = 0;  // spectral photons: the iteration's wavelengths in use
  ShadingPoint sp{};
  SpectralBsdf sbsdf{};

  bool segment(const PathState&, bool found, const Hit&) {
    ++out->rays;
    return found;
  }
  VertexStep vertex(PathState& state, const Hit&, const SurfaceInteraction& si) {
    sp = shade(context, si, -state.ray.direction);
    const Bsdf& bsdf = sp.bsdf;
    // A non-finite position would break the kd-tree's ordering; such a photon is dropped.
    if (state.depth > state.transparent_depth && is_visible_point(bsdf) && is_finite(si.p)) {
      if (!state.spectral && is_finite(state.throughput))
        out->photons.push_back({si.p, -state.ray.direction, state.throughput});
      else if (state.spectral && is_finite(state.beta))
        out->photons.push_back(SppmPhoton::spectral(si.p, -state.ray.direction, state.beta,
                                                    state.wl.active_count() < wavelengths));
    }
    if (!state.spectral) return VertexStep::scatter(bsdf);
    sbsdf = SpectralBsdf(bsdf, state.wl);
    return VertexStep::scatter(bsdf, &sbsdf);
  }
  void scattered(const PathState&, bool) {}
};

}  // namespace

SppmPhotonPass trace_sppm_photons(const RenderContext& context, const PhotonSources& sources,
                                  uint32_t iteration, uint64_t count,
                                  const std::atomic<bool>& cancel, const SampledWavelengths* wl) {
  SppmPhotonPass pass;
  if (!sources.has_global() || count == 0) return pass;
  const uint64_t chunks = (count + kChunk - 1) / kChunk;
  std::vector<ChunkOutput> outputs(chunks);
  const uint64_t stream = hash_combine(kPhotonStream, iteration);
  const uint64_t seed = context.settings->seed;
  const auto stratify = static_cast<uint32_t>(std::min<uint64_t>(count, UINT32_MAX));
  const PathRules rules = power_rules(kMaxPhotonBounces - 1, kLobeAll);
  tbb::parallel_for(tbb::blocked_range<uint64_t>(0, chunks, 1), [&](const auto& r) {
    for (uint64_t c = r.begin(); c != r.end(); ++c) {
      if (cancel.load(std::memory_order_relaxed)) return;
      ChunkOutput& out = outputs[c];
      const uint64_t lo = c * kChunk, hi = std::min(count, lo + kChunk);
      for (uint64_t i = lo; i < hi; ++i) {
        Sampler sampler(seed, stream, static_cast<uint32_t>(i), stratify);
        EmittedPhoton e;
        if (!sources.emit_global(sampler, &e)) continue;
        PathState state;
        state.ray = e.ray;
        state.throughput = e.power;
        state.mask = kVisibleDiffuse | kVisibleGlossy | kVisibleTransmission | kVisibleShadow;
        SppmPhotonVisitor visitor{context, &out};
        if (wl) {
          state.start_spectral(*wl, e.emitter->spectrum(e.power, *wl));
          visitor.wavelengths = wl->active_count();
          if (state.black()) continue;
        }
        walk_path(context, rules, &state, sampler, visitor);
      }
    }
  });
  if (cancel.load(std::memory_order_relaxed)) {
    pass.cancelled = true;
    return pass;
  }
  size_t total = 0;
  for (const ChunkOutput& out : outputs) total += out.photons.size();
  pass.photons.reserve(total);
  for (const ChunkOutput& out : outputs) {
    pass.photons.insert(pass.photons.end(), out.photons.begin(), out.photons.end());
    pass.rays += out.rays;
  }
  return pass;
}

}  // namespace photon
