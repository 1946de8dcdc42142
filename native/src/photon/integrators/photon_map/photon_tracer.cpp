#include "photon/integrators/photon_map/photon_tracer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cstdio>

#include "photon/integrators/camera_path.h"
#include "photon/integrators/spectral_path.h"

namespace photon {
namespace {

using Clock = std::chrono::steady_clock;
constexpr uint64_t kChunk = 2048;         // photons per parallel work item
constexpr uint64_t kRound = 32 * kChunk;  // photons between progress / time checks
constexpr uint64_t kGlobalStream = 0x6C6F62616C, kCausticStream = 0x636175737469;

struct ChunkOutput {
  std::vector<Photon> photons;
  std::vector<GatherPoint> gather_points;
  uint64_t rays = 0;
};

struct PathSetup {
  const RenderContext* context;
  const PhotonTraceSettings* settings;
  bool caustic_pass;
  float power_scale;  // 1 / photons emitted when known up front, else 1 (rescaled later)
};

// Where a path stands for the photon maps: at the light's first hit (direct), after perfectly
// specular bounces only (caustic: L S+ D), or after a diffuse or rough glossy bounce (indirect).
// Rough glossy paths are not caustics here: final gathering collects them (see
// photon_map_integrator.cpp), so the two never count the same light twice.
uint8_t photon_kind(const PathState& state) {
  // Straight through Transparent surfaces is still direct light: shadow rays see through them.
  if (state.depth == state.transparent_depth) return kPhotonDirect;
  return state.after_glossy ? kPhotonIndirect : kPhotonCaustic;
}

// Stores a photon at every diffuse surface the path meets (global pass: every photon; caustic
// pass: caustic photons only). Scattering and Russian roulette are the walker's power rules
// (path_walker.h: Jensen 2001 sec. 5.2, survival by the bounce's albedo).
struct PhotonVisitor {
  const PathSetup& setup;
  uint64_t index;
  ChunkOutput* out;
  float wavelength_pdf = 0.0f;  // spectral photons: the density their wavelength was drawn with
  ShadingPoint sp{};
  SpectralBsdf sbsdf{};

  Photon make(const PathState& state, const SurfaceInteraction& si, uint8_t kind) const {
    const Vec3& dir = state.ray.direction;
    if (!state.spectral) return Photon::make(si.p, dir, state.throughput, kind, sp.bsdf.ng());
    return Photon::make_spectral(si.p, dir, state.wl.lambda(0), state.beta[0] / wavelength_pdf,
                                 kind, sp.bsdf.ng());
  }

  bool segment(const PathState&, bool found, const Hit&) {
    ++out->rays;
    return found;
  }
  VertexStep vertex(PathState& state, const Hit&, const SurfaceInteraction& si) {
    sp = shade(*setup.context, si, -state.ray.direction);
    const Bsdf& bsdf = sp.bsdf;
    if (bsdf.flags() & kLobeDiffuse) {
      const uint8_t kind = photon_kind(state);
      if (!setup.caustic_pass) {
        out->photons.push_back(make(state, si, kind));
        if (hash_combine(index, static_cast<uint64_t>(state.depth)) %
                setup.settings->gather_point_stride ==
            0)
          out->gather_points.push_back({si.p, bsdf.ng()});
      } else if (kind == kPhotonCaustic) {
        out->photons.push_back(make(state, si, kPhotonCaustic));
      }
    }
    if (!state.spectral) return VertexStep::scatter(bsdf);
    sbsdf = SpectralBsdf(bsdf, state.wl);
    return VertexStep::scatter(bsdf, &sbsdf);
  }
  void scattered(const PathState&, bool) {}
};

void trace_path(const PathSetup& setup, uint64_t index, const EmittedPhoton& emitted,
                Sampler& sampler, ChunkOutput* out) {
  // Vertices 0 .. max_bounces - 1 are stored; none without any bounce.
  if (setup.settings->max_bounces <= 0) return;
  PathState state;
  state.ray = emitted.ray;
  state.throughput = emitted.power * setup.power_scale;
  state.mask = kVisibleDiffuse | kVisibleGlossy | kVisibleTransmission | kVisibleShadow;
  PhotonVisitor visitor{setup, index, out};
  if (setup.settings->spectral) {
    // One wavelength per photon, stratified over the pass's photons (no sampler dimension),
    // carrying the emitter's spectral flux at it.
    const float lambda = spectral::sample_visible_wavelength(sampler.stratified_1d(kWavelengthTag));
    visitor.wavelength_pdf = spectral::visible_wavelength_pdf(lambda);
    if (!(visitor.wavelength_pdf > 0.0f) || !emitted.emitter) return;
    const SampledWavelengths wl = SampledWavelengths::single(lambda, visitor.wavelength_pdf);
    state.start_spectral(wl, emitted.emitter->spectrum(emitted.power, wl) * setup.power_scale);
    if (state.black()) return;
  }
  // Caustic photons follow perfectly specular lobes only; global photons every lobe.
  const PathRules rules =
      power_rules(setup.settings->max_bounces - 1, setup.caustic_pass ? kLobeSpecular : kLobeAll);
  walk_path(*setup.context, rules, &state, sampler, visitor);
}

// Traces photons [begin, end) of one pass in parallel chunks; their results, in chunk order,
// become one block of `blocks` (concatenated once at the end, so the big arrays are never
// reallocated and copied while tracing). Chunks poll for cancellation.
void trace_range(const PathSetup& setup, const PhotonSources& sources, uint64_t begin, uint64_t end,
                 uint32_t stratify_count, const PrepareControl& control, PhotonTraceResult* result,
                 std::vector<std::vector<Photon>>* blocks,
                 std::vector<std::vector<GatherPoint>>* gather_blocks) {
  const uint64_t chunks = (end - begin + kChunk - 1) / kChunk;
  std::vector<ChunkOutput> outputs(chunks);
  const uint64_t stream = setup.caustic_pass ? kCausticStream : kGlobalStream;
  tbb::parallel_for(tbb::blocked_range<uint64_t>(0, chunks, 1), [&](const auto& r) {
    for (uint64_t c = r.begin(); c != r.end(); ++c) {
      if (control.cancelled()) return;
      ChunkOutput& out = outputs[c];
      const uint64_t lo = begin + c * kChunk, hi = std::min(end, lo + kChunk);
      for (uint64_t i = lo; i < hi; ++i) {
        Sampler sampler(setup.settings->seed, stream, static_cast<uint32_t>(i), stratify_count);
        EmittedPhoton e;
        const bool ok = setup.caustic_pass ? sources.emit_caustic(sampler, &e)
                                           : sources.emit_global(sampler, &e);
        if (ok) trace_path(setup, i, e, sampler, &out);
      }
    }
  });
  size_t photon_count = 0, gather_count = 0;
  for (const ChunkOutput& out : outputs) {
    photon_count += out.photons.size();
    gather_count += out.gather_points.size();
  }
  std::vector<Photon>& photons = blocks->emplace_back();
  photons.reserve(photon_count);
  std::vector<GatherPoint>& gather_points = gather_blocks->emplace_back();
  gather_points.reserve(gather_count);
  for (ChunkOutput& out : outputs) {
    photons.insert(photons.end(), out.photons.begin(), out.photons.end());
    gather_points.insert(gather_points.end(), out.gather_points.begin(), out.gather_points.end());
    result->rays += out.rays;
  }
}

// Moves the blocks into one exactly sized array, block by block, polling for cancellation.
template <typename T>
void concatenate(std::vector<std::vector<T>>* blocks, std::vector<T>* out,
                 const PrepareControl& control) {
  size_t total = 0;
  for (const auto& b : *blocks) total += b.size();
  out->clear();
  out->reserve(total);
  for (auto& b : *blocks) {
    if (control.cancelled()) break;
    out->insert(out->end(), b.begin(), b.end());
    std::vector<T>().swap(b);  // give the block's memory back now
  }
  blocks->clear();
}

void rescale(std::vector<Photon>* photons, float scale, bool spectral,
             const PrepareControl& control) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, photons->size(), 8192), [&](const auto& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      if ((i & 0xFFFF) == 0 && control.cancelled()) return;
      Photon& ph = (*photons)[i];
      if (spectral)
        ph.set_spectral_power(ph.spectral_power() * scale);
      else
        encode_rgbe(ph.power() * scale, ph.power_rgbe);
    }
  });
}

std::string count_text(uint64_t n) {
  char buf[32];
  if (n >= 1000000)
    std::snprintf(buf, sizeof buf, "%.2fM", n / 1e6);
  else if (n >= 1000)
    std::snprintf(buf, sizeof buf, "%.0fk", n / 1e3);
  else
    std::snprintf(buf, sizeof buf, "%llu", static_cast<unsigned long long>(n));
  return buf;
}

}  // namespace

PhotonTraceResult trace_photons(const RenderContext& context, const PhotonSources& sources,
                                const PhotonTraceSettings& settings,
                                const PrepareControl& control) {
  PhotonTraceResult result;
  result.spectral = settings.spectral;
  const auto t0 = Clock::now();
  const bool timed = settings.time_budget > 0.0;
  uint64_t want_global = sources.has_global() ? settings.global_photons : 0;
  uint64_t want_caustic = sources.has_caustic() ? settings.caustic_photons : 0;
  if (timed) {
    // Keep the ratio of the two counts; each round traces kRound photons in that ratio.
    const double g = sources.has_global() ? std::max<double>(settings.global_photons, 1) : 0;
    const double c = sources.has_caustic() ? static_cast<double>(settings.caustic_photons) : 0;
    if (g + c <= 0) return result;
    want_global = static_cast<uint64_t>(kRound * g / (g + c));
    want_caustic = kRound - want_global;
  }
  if (want_global + want_caustic == 0) return result;

  PathSetup global_setup{&context, &settings, false,
                         timed ? 1.0f : 1.0f / std::max<uint64_t>(want_global, 1)};
  PathSetup caustic_setup{&context, &settings, true,
                          timed ? 1.0f : 1.0f / std::max<uint64_t>(want_caustic, 1)};
  const uint32_t strat_global =
      timed ? 0 : static_cast<uint32_t>(std::min<uint64_t>(want_global, UINT32_MAX));
  const uint32_t strat_caustic =
      timed ? 0 : static_cast<uint32_t>(std::min<uint64_t>(want_caustic, UINT32_MAX));
  uint64_t stored = 0;

  std::vector<std::vector<Photon>> global_blocks, caustic_blocks;
  std::vector<std::vector<GatherPoint>> gather_blocks;
  for (uint64_t round = 0;; ++round) {
    if (control.should_stop()) {
      result.stopped_early = true;
      break;
    }
    const double elapsed = std::chrono::duration<double>(Clock::now() - t0).count();
    if (timed && elapsed >= settings.time_budget) break;
    uint64_t g_end, c_end;
    if (timed) {
      g_end = result.global_emitted + want_global;
      c_end = result.caustic_emitted + want_caustic;
    } else {
      // Both passes advance together so an early stop leaves both maps usable.
      const double total = static_cast<double>(want_global + want_caustic);
      const double done = std::min(1.0, (round + 1) * static_cast<double>(kRound) / total);
      g_end = static_cast<uint64_t>(std::ceil(done * want_global));
      c_end = static_cast<uint64_t>(std::ceil(done * want_caustic));
    }
    if (g_end > result.global_emitted) {
      trace_range(global_setup, sources, result.global_emitted, g_end, strat_global, control,
                  &result, &global_blocks, &gather_blocks);
      stored += global_blocks.back().size();
    }
    if (c_end > result.caustic_emitted) {
      // The caustic pass makes no gather points: its (empty) blocks change nothing.
      trace_range(caustic_setup, sources, result.caustic_emitted, c_end, strat_caustic, control,
                  &result, &caustic_blocks, &gather_blocks);
      stored += caustic_blocks.back().size();
    }
    if (control.cancelled()) return result;
    result.global_emitted = g_end;
    result.caustic_emitted = c_end;
    const double t = std::chrono::duration<double>(Clock::now() - t0).count();
    const float fraction =
        timed ? static_cast<float>(std::min(1.0, t / settings.time_budget))
              : static_cast<float>(result.global_emitted + result.caustic_emitted) /
                    static_cast<float>(want_global + want_caustic);
    control.report("Tracing photons " + count_text(result.global_emitted + result.caustic_emitted) +
                       (timed ? "" : " / " + count_text(want_global + want_caustic)) + " (" +
                       count_text(stored) + " stored)",
                   fraction);
    if (!timed && g_end >= want_global && c_end >= want_caustic) break;
  }
  concatenate(&global_blocks, &result.global, control);
  concatenate(&caustic_blocks, &result.caustic, control);
  concatenate(&gather_blocks, &result.gather_points, control);
  // Each photon carries flux / (photons emitted); when that count was not known in advance
  // (time budget, early stop) the stored powers are rescaled now.
  if ((timed || result.stopped_early) && !control.cancelled()) {
    if (result.global_emitted)
      rescale(&result.global,
              (timed ? 1.0f : want_global) / static_cast<float>(result.global_emitted),
              settings.spectral, control);
    if (result.caustic_emitted)
      rescale(&result.caustic,
              (timed ? 1.0f : want_caustic) / static_cast<float>(result.caustic_emitted),
              settings.spectral, control);
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return result;
}

}  // namespace photon
