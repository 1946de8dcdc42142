#include "photon/photon_tracer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cstdio>

#include "photon/optics.h"
#include "photon/sampling.h"

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

// Russian roulette survival: the largest channel, so a photon's power never grows (Jensen
// 2001 sec. 5.2); the survivor's power is multiplied by reflectance / probability per channel.
float survival_probability(const Vec3& reflectance) {
  return std::clamp(max_component(reflectance), 0.0f, 1.0f);
}

void trace_path(const PathSetup& setup, uint64_t index, const EmittedPhoton& emitted,
                Sampler& sampler, ChunkOutput* out) {
  const RenderContext& context = *setup.context;
  Ray ray = emitted.ray;
  Vec3 power = emitted.power * setup.power_scale;
  int specular_bounces = 0;
  bool diffuse_seen = false;
  uint32_t mask = kVisibleDiffuse | kVisibleGlossy | kVisibleTransmission | kVisibleShadow;
  for (int bounce = 0; bounce < setup.settings->max_bounces; ++bounce) {
    Hit hit;
    ++out->rays;
    if (!context.accel->intersect(ray, mask, &hit)) return;
    SurfaceInteraction si = context.accel->interaction(hit);
    const Material& mat = *si.mat;
    const Vec3 wo = -ray.direction;
    if (mat.type != MaterialType::kGlass && dot(si.ng, wo) < 0.0f) {
      si.ng = -si.ng;
      si.ns = -si.ns;
    }

    Vec3 wi;
    if (mat.type == MaterialType::kDiffuse) {
      const bool caustic_path = !diffuse_seen && specular_bounces > 0;
      if (setup.caustic_pass) {
        if (caustic_path)
          out->photons.push_back(Photon::make(si.p, ray.direction, power, kPhotonCaustic));
        return;  // caustic photons end at their first diffuse surface
      }
      const uint8_t flags = bounce == 0 ? kPhotonDirect
                            : caustic_path ? kPhotonCaustic
                                           : kPhotonIndirect;
      out->photons.push_back(Photon::make(si.p, ray.direction, power, flags));
      if (hash_combine(index, static_cast<uint64_t>(bounce)) % setup.settings->gather_point_stride == 0)
        out->gather_points.push_back({si.p, si.ng});
      const float p = survival_probability(mat.color);
      if (!(sampler.get_1d() < p)) return;  // absorbed
      power = power * mat.color / p;
      wi = Frame(si.ns).to_world(sample_cosine_hemisphere(sampler.get_2d()));
      if (dot(wi, si.ng) <= 0.0f) return;
      diffuse_seen = true;
      mask = kVisibleDiffuse;
    } else {
      if (setup.caustic_pass && diffuse_seen) return;
      const float p = survival_probability(mat.color);
      const float u = sampler.get_1d();
      if (!(u < p)) return;
      power = power * mat.color / p;
      if (mat.type == MaterialType::kMirror) {
        wi = reflect(wo, si.ns);
        if (dot(wi, si.ng) <= 0.0f) wi = reflect(wo, si.ng);
        mask = kVisibleGlossy;
      } else {
        // Dielectric: reflect with the Fresnel probability, else refract (eq. 2.2's s and t).
        const bool entering = dot(wo, si.ng) > 0.0f;
        const Vec3 n = entering ? si.ns : -si.ns;
        const float ior = std::max(mat.ior, 1e-3f);
        const float eta = entering ? ior : 1.0f / ior;
        Vec3 wt;
        if (sampler.get_1d() < fresnel_dielectric(dot(wo, n), eta) || !refract(wo, n, eta, &wt)) {
          wi = reflect(wo, n);
          mask = kVisibleGlossy;
        } else {
          wi = wt;
          mask = kVisibleTransmission;
        }
      }
      ++specular_bounces;
    }
    ray.origin = offset_ray_origin(si.p, si.ng, wi);
    ray.direction = wi;
    ray.tmin = 0.0f;
    ray.tmax = INFINITY;
  }
}

// Traces photons [begin, end) of one pass in parallel chunks and appends their results in
// chunk order.
void trace_range(const PathSetup& setup, const PhotonSources& sources, uint64_t begin,
                 uint64_t end, uint32_t stratify_count, PhotonTraceResult* result,
                 std::vector<Photon>* photons) {
  const uint64_t chunks = (end - begin + kChunk - 1) / kChunk;
  std::vector<ChunkOutput> outputs(chunks);
  const uint64_t stream = setup.caustic_pass ? kCausticStream : kGlobalStream;
  tbb::parallel_for(tbb::blocked_range<uint64_t>(0, chunks, 1), [&](const auto& r) {
    for (uint64_t c = r.begin(); c != r.end(); ++c) {
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
  for (ChunkOutput& out : outputs) {
    photons->insert(photons->end(), out.photons.begin(), out.photons.end());
    result->gather_points.insert(result->gather_points.end(), out.gather_points.begin(),
                                 out.gather_points.end());
    result->rays += out.rays;
  }
}

void rescale(std::vector<Photon>* photons, float scale) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, photons->size(), 8192), [&](const auto& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      Photon& ph = (*photons)[i];
      encode_rgbe(ph.power() * scale, ph.power_rgbe);
    }
  });
}

std::string count_text(uint64_t n) {
  char buf[32];
  if (n >= 1000000) std::snprintf(buf, sizeof buf, "%.2fM", n / 1e6);
  else if (n >= 1000) std::snprintf(buf, sizeof buf, "%.0fk", n / 1e3);
  else std::snprintf(buf, sizeof buf, "%llu", static_cast<unsigned long long>(n));
  return buf;
}

}  // namespace

PhotonTraceResult trace_photons(const RenderContext& context, const PhotonSources& sources,
                                const PhotonTraceSettings& settings,
                                const PrepareControl& control) {
  PhotonTraceResult result;
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

  PathSetup global_setup{&context, &settings, false, timed ? 1.0f : 1.0f / std::max<uint64_t>(want_global, 1)};
  PathSetup caustic_setup{&context, &settings, true, timed ? 1.0f : 1.0f / std::max<uint64_t>(want_caustic, 1)};
  const uint32_t strat_global = timed ? 0 : static_cast<uint32_t>(std::min<uint64_t>(want_global, UINT32_MAX));
  const uint32_t strat_caustic = timed ? 0 : static_cast<uint32_t>(std::min<uint64_t>(want_caustic, UINT32_MAX));

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
    if (g_end > result.global_emitted)
      trace_range(global_setup, sources, result.global_emitted, g_end, strat_global, &result,
                  &result.global);
    if (c_end > result.caustic_emitted)
      trace_range(caustic_setup, sources, result.caustic_emitted, c_end, strat_caustic, &result,
                  &result.caustic);
    result.global_emitted = g_end;
    result.caustic_emitted = c_end;
    const double t = std::chrono::duration<double>(Clock::now() - t0).count();
    const float fraction = timed ? static_cast<float>(std::min(1.0, t / settings.time_budget))
                                 : static_cast<float>(result.global_emitted + result.caustic_emitted) /
                                       static_cast<float>(want_global + want_caustic);
    control.report("Tracing photons " + count_text(result.global_emitted + result.caustic_emitted) +
                       (timed ? "" : " / " + count_text(want_global + want_caustic)) + " (" +
                       count_text(result.global.size() + result.caustic.size()) + " stored)",
                   fraction);
    if (!timed && g_end >= want_global && c_end >= want_caustic) break;
  }
  // Each photon carries flux / (photons emitted); when that count was not known in advance
  // (time budget, early stop) the stored powers are rescaled now.
  if (timed || result.stopped_early) {
    if (result.global_emitted)
      rescale(&result.global, (timed ? 1.0f : want_global) / static_cast<float>(result.global_emitted));
    if (result.caustic_emitted)
      rescale(&result.caustic, (timed ? 1.0f : want_caustic) / static_cast<float>(result.caustic_emitted));
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return result;
}

}  // namespace photon
