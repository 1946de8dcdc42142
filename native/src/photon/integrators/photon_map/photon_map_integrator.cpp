#include "photon/integrators/photon_map/photon_map_integrator.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cstdio>

#include "photon/base/sampling.h"
#include "photon/integrators/photon_map/irradiance_cache_build.h"
#include "photon/integrators/photon_map/irradiance_cache_points.h"
#include "photon/integrators/photon_map/photon_memory.h"
#include "photon/integrators/photon_map/photon_tracer.h"
#include "photon/integrators/spectral_path.h"
#include "photon/lights/direct_lighting.h"
#include "photon/lights/emitter_set.h"

namespace photon {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Per-thread neighbour list, so radiance queries do not allocate.
std::vector<PhotonNeighbor>& scratch_neighbors() {
  thread_local std::vector<PhotonNeighbor> scratch;
  return scratch;
}

// Point j of the R2 sequence (Roberts 2018), rotated by `shift`: the final-gather directions of
// one camera sample are stratified, and the rotation differs per sample.
Vec2 rotated_r2(uint32_t j, Vec2 shift) {
  constexpr double kA1 = 0.7548776662466927, kA2 = 0.5698402909980532;
  double u = shift.x + kA1 * (j + 1), v = shift.y + kA2 * (j + 1);
  u -= std::floor(u);
  v -= std::floor(v);
  return {std::min(static_cast<float>(u), 0.99999994f),
          std::min(static_cast<float>(v), 0.99999994f)};
}

constexpr size_t kFallbackCount = 32;         // photons when no precomputed record is near
constexpr float kGatherMinCos = 0.5f;         // normals of gather point and surface must agree
constexpr float kDefaultGlobalRadius = 0.1f;  // of the scene's bounding radius
constexpr float kDefaultCausticRadius = 0.05f;
// Final-gather rays of an irradiance-cache record per final-gather ray of a camera sample:
// 16 -> 1024, enough that records differ by under 1% and their interpolation shows no blotches.
constexpr int kRecordRaysPerGatherRay = 64;
constexpr int kMinRecordRays = 256, kMaxRecordRays = 16384;

// Grid cell for the radiance records: about two record spacings, from the photon density
// measured at up to 256 gather points (median of k / (pi r_k^2), scaled by records / photons).
float record_cell_size(const PhotonMap& map, const std::vector<GatherPoint>& points, size_t k,
                       float max_radius, float length_scale) {
  if (points.empty()) return max_radius;
  std::vector<float> spacing;
  std::vector<PhotonNeighbor> scratch;
  const size_t step = std::max<size_t>(1, points.size() / 256);
  for (size_t i = 0; i < points.size(); i += step) {
    map.k_nearest(points[i].p, k, max_radius, kPhotonAny, &scratch);
    if (scratch.size() < 2) continue;
    const float photon_area = kPi * scratch.front().distance_squared / scratch.size();
    spacing.push_back(std::sqrt(photon_area * map.size() / points.size()));
  }
  if (spacing.empty()) return max_radius;
  std::nth_element(spacing.begin(), spacing.begin() + spacing.size() / 2, spacing.end());
  return std::clamp(2.0f * spacing[spacing.size() / 2], 1e-6f * length_scale, max_radius);
}

// A 48-bit stream id drawn from `sampler`, so the bake's inner samplers are a pure function of
// the caller's sampler.
uint64_t derived_stream(Sampler& sampler) {
  const auto a = static_cast<uint64_t>(sampler.get_1d() * 16777216.0f);
  const auto b = static_cast<uint64_t>(sampler.get_1d() * 16777216.0f);
  return (a << 24) | b;
}

// Photons per pass of the pilot trace that measures how many photons a path stores; requests
// under kPilotMinimum photons need no estimate (at worst a few hundred MB).
constexpr uint64_t kPilotPhotons = 8192;
constexpr uint64_t kPilotMinimum = 65536;
constexpr uint64_t kPilotSeedTag =
    0x9E3779B97F4A7C15ull;  // pilot streams differ from the real ones

std::string thousands(uint64_t n) {
  std::string digits = std::to_string(n), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

// Scales `trace`'s photon counts down when their estimated peak memory exceeds the
// configured fraction of the available memory. A pilot trace of a few thousand photons (its
// own random streams, discarded) measures the photons stored per photon emitted.
void fit_photon_counts_to_memory(const RenderContext& context, const PhotonSources& sources,
                                 const PrepareControl& control, PhotonTraceSettings* trace,
                                 std::optional<PhotonMemoryStats>* stats) {
  const RenderSettings& s = *context.settings;
  if (trace->time_budget > 0.0) return;  // counts unknown up front
  const uint64_t global = sources.has_global() ? trace->global_photons : 0;
  const uint64_t caustic = sources.has_caustic() ? trace->caustic_photons : 0;
  if (global + caustic < kPilotMinimum) return;
  control.report("Estimating photon memory", 0.0f);
  PhotonTraceSettings pilot = *trace;
  pilot.global_photons = global ? kPilotPhotons : 0;
  pilot.caustic_photons = caustic ? kPilotPhotons : 0;
  pilot.seed = trace->seed ^ kPilotSeedTag;
  PrepareControl pilot_control;  // no progress, no early stop: only cancellation
  pilot_control.cancel = control.cancel;
  const PhotonTraceResult traced = trace_photons(context, sources, pilot, pilot_control);
  if (control.cancelled()) return;

  PhotonMemoryRequest request;
  request.global_photons = global;
  request.caustic_photons = caustic;
  if (traced.global_emitted) {
    request.global_stored_per_emitted =
        static_cast<double>(traced.global.size()) / traced.global_emitted;
    request.gather_points_per_emitted =
        static_cast<double>(traced.gather_points.size()) / traced.global_emitted;
  }
  if (traced.caustic_emitted)
    request.caustic_stored_per_emitted =
        static_cast<double>(traced.caustic.size()) / traced.caustic_emitted;
  request.radiance_records = s.final_gather_rays > 0;
  request.irradiance_pixels = s.final_gather_rays > 0 && s.irradiance_cache
                                  ? static_cast<uint64_t>(s.full_width) * s.full_height
                                  : 0;
  const double available = static_cast<double>(available_memory_bytes());
  const double budget = s.memory_limit * available;
  const PhotonMemoryPlan plan = plan_photon_memory(request, budget);
  *stats = PhotonMemoryStats{plan.planned_bytes, available};
  if (plan.scale >= 1.0) return;
  trace->global_photons = plan.global_photons;
  trace->caustic_photons = plan.caustic_photons;
  char percent[32];
  std::snprintf(percent, sizeof percent, "%.0f%%", 100.0 * s.memory_limit);
  char scale[32];
  std::snprintf(scale, sizeof scale, "%.3g%%", 100.0 * plan.scale);
  if (control.warn)
    control.warn("Photon memory: " + thousands(global) + " global and " + thousands(caustic) +
                 " caustic photons would need about " + bytes_text(plan.requested_bytes) +
                 " at the peak, more than the memory limit (" + percent + " of the " +
                 bytes_text(available) + " available); tracing " + thousands(plan.global_photons) +
                 " and " + thousands(plan.caustic_photons) + " instead (" + scale +
                 " of the request, about " + bytes_text(plan.planned_bytes) +
                 "). Raise the memory limit or lower the photon counts to avoid this");
}

// A gather radius set by hand below the typical distance to the k-th nearest photon turns most
// k-nearest estimates (Jensen 2001, eq. 7.6: L = sum of photon powers / (pi r^2)) into
// fixed-disc estimates over a handful of photons. Radiance records sit on photons, so the photon
// at the centre alone gives power / (pi r^2): at r = 1e-6 m the image mean grew 5e4-fold.
// Such a radius is raised to the median k-th-nearest distance of the map (`k` its gather count),
// the smallest disc that holds a full estimate at a typical photon. Returns the note for the
// warning ("" when `radius` is kept).
std::string raise_to_photon_density(const PhotonMap& map, size_t k, uint8_t flags, const char* what,
                                    float* radius) {
  const float floor = map.median_kth_distance(k, flags);
  if (!(*radius < floor)) return "";
  *radius = floor;
  char text[200];
  std::snprintf(text, sizeof text, "%s: the median radius holding %zu of its %s photons is %.3g m",
                what, k, thousands(map.size()).c_str(), floor);
  return text;
}

}  // namespace

void PhotonMapIntegrator::prepare(const RenderContext& context, const PrepareControl& control) {
  const RenderSettings& s = *context.settings;
  stats_ = PrepareStats{};
  state_.irradiance = IrradianceCache();
  const PhotonSources sources(context);
  const float scene_radius = sources.scene_radius();
  state_.global_radius =
      s.gather_radius > 0.0f ? s.gather_radius : kDefaultGlobalRadius * scene_radius;
  state_.caustic_radius =
      s.gather_radius > 0.0f ? s.gather_radius : kDefaultCausticRadius * scene_radius;

  PhotonTraceSettings trace;
  trace.global_photons = s.photons;
  trace.caustic_photons = s.caustic_photons;
  trace.time_budget = s.photon_time;
  trace.seed = s.seed;
  trace.spectral = spectral_mode(context);
  fit_photon_counts_to_memory(context, sources, control, &trace, &stats_.photon_memory);
  if (control.cancelled()) return;
  PhotonTraceResult traced = trace_photons(context, sources, trace, control);
  if (control.cancelled()) return;
  if (traced.stopped_early && control.warn)
    control.warn("Photon tracing was stopped early: rendering with " +
                 std::to_string(traced.global_emitted + traced.caustic_emitted) +
                 " photons traced so far");

  control.report("Building photon maps", 1.0f);
  auto t0 = Clock::now();
  const uint64_t global_stored = traced.global.size(), caustic_stored = traced.caustic.size();
  state_.global = PhotonMap(std::move(traced.global), control.cancel, traced.spectral);
  if (control.cancelled()) return;
  state_.caustic = PhotonMap(std::move(traced.caustic), control.cancel, traced.spectral);
  if (control.cancelled()) return;
  if (s.gather_radius > 0.0f) {
    std::string notes;
    for (const std::string& note :
         {raise_to_photon_density(state_.global, static_cast<size_t>(s.gather_count), kPhotonAny,
                                  "global map", &state_.global_radius),
          raise_to_photon_density(state_.caustic, static_cast<size_t>(s.caustic_gather_count),
                                  kPhotonCaustic, "caustic map", &state_.caustic_radius)})
      if (!note.empty()) notes += (notes.empty() ? "" : "; ") + note;
    if (!notes.empty() && control.warn) {
      char text[160];
      std::snprintf(text, sizeof text,
                    "Gather radius %.3g m is smaller than the photon density supports (",
                    s.gather_radius);
      control.warn(text + notes +
                   "): raised to that distance. Raise Photons or lower Gather Count for a "
                   "smaller radius");
    }
  }
  const double build_seconds = seconds_since(t0);
  state_.secondary_distance = std::min(
      state_.global_radius, state_.global.median_kth_distance(
                                static_cast<size_t>(std::max(s.gather_count, 1)), kPhotonAny));

  // Christensen 1999: radiance (for albedo 1) precomputed at every gather point, so a final
  // gather ray needs one nearest-point lookup instead of a k-nearest estimate.
  t0 = Clock::now();
  if (s.final_gather_rays > 0 && !state_.global.empty()) {
    control.report("Precomputing radiance", 1.0f);
    const std::vector<GatherPoint>& points = traced.gather_points;
    std::vector<RadianceRecord> records(points.size());
    const size_t k = static_cast<size_t>(std::max(s.gather_count, 1));
    tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 1024), [&](const auto& r) {
      std::vector<PhotonNeighbor>& scratch = scratch_neighbors();
      // The partitioner hands out ranges of up to points / (4 threads): poll per point.
      for (size_t i = r.begin(); i != r.end(); ++i) {
        if (control.cancelled()) return;
        records[i].p = points[i].p;
        records[i].n = points[i].n;
        records[i].radiance = state_.global.radiance_estimate(
            points[i].p, points[i].n, k, state_.global_radius, kPhotonAny, &scratch, true);
        // The same neighbours show where the indirect light comes from.
        records[i].guide = build_guide(state_.global, scratch, Frame(points[i].n));
      }
    });
    if (control.cancelled()) return;
    state_.radiance = RadianceCache(std::move(records),
                                    record_cell_size(state_.global, points, k, state_.global_radius,
                                                     context.accel->length_scale()),
                                    control.cancel);
    if (control.cancelled()) return;
  }
  const double precompute_seconds = seconds_since(t0);
  if (s.final_gather_rays > 0 && s.irradiance_cache && !state_.global.empty()) {
    build_irradiance(context, control);
    if (control.cancelled()) return;
  }

  PhotonMapStats& pm = stats_.photon_map.emplace();
  pm.photons_emitted = traced.global_emitted;
  pm.caustic_photons_emitted = traced.caustic_emitted;
  pm.global_photons_stored = global_stored;
  pm.caustic_photons_stored = caustic_stored;
  pm.radiance_points = state_.radiance.size();
  pm.photon_rays = traced.rays;
  pm.photon_trace_seconds = traced.seconds;
  pm.photon_map_build_seconds = build_seconds;
  pm.radiance_precompute_seconds = precompute_seconds;
  pm.photon_map_bytes =
      state_.global.memory_bytes() + state_.caustic.memory_bytes() + state_.radiance.memory_bytes();
  pm.radiance_cell_size = state_.radiance.cell_size();
  pm.global_gather_radius = state_.global_radius;
  pm.caustic_gather_radius = state_.caustic_radius;
}

void PhotonMapIntegrator::build_irradiance(const RenderContext& context,
                                           const PrepareControl& control) {
  IrradianceCacheSettings settings;
  settings.rays = std::clamp(kRecordRaysPerGatherRay * context.settings->final_gather_rays,
                             kMinRecordRays, kMaxRecordRays);
  IrradianceCacheBuildStats build;
  // A record gathers up to 16384 rays: the gather polls for cancellation every 64 rays.
  auto gather = [&](const SurfaceInteraction& si, const Bsdf& bsdf, int rays, Sampler& sampler,
                    float* harmonic) {
    return final_gather(context, si, bsdf, rays, sampler, harmonic, control.cancel);
  };
  state_.irradiance = build_irradiance_cache(context, settings, gather, control, &build);
  stats_.irradiance_cache =
      IrradianceCacheStats{state_.irradiance.size(), build.candidates, build.gather_rays,
                           state_.irradiance.memory_bytes(), build.seconds};
}

PrepareStats PhotonMapIntegrator::prepare_stats() const {
  return stats_;
}

void PhotonMapIntegrator::save_prepared(PreparedStateWriter* out) const {
  write_photon_map_prepared(state_, stats_, out);
}

bool PhotonMapIntegrator::load_prepared(PreparedStateReader* in, std::string* error) {
  return read_photon_map_prepared(in, &state_, &stats_, error);
}

Vec3 PhotonMapIntegrator::gathered_radiance(const Vec3& p, const Vec3& n,
                                            std::vector<PhotonNeighbor>* scratch) const {
  if (const RadianceRecord* record = state_.radiance.nearest(p, n, kGatherMinCos))
    return record->radiance;
  return state_.global.radiance_estimate(p, n, kFallbackCount, state_.global_radius, kPhotonAny,
                                         scratch);
}

Vec3 PhotonMapIntegrator::secondary_radiance(const RenderContext& context,
                                             const SurfaceInteraction& y, const Bsdf& bsdf,
                                             const Vec3& wo, Sampler& sampler,
                                             std::vector<PhotonNeighbor>* scratch) const {
  // The point as seen from wo's side (direct_irradiance lights the side its normals face).
  SurfaceInteraction lit = y;
  if (dot(lit.ng, wo) < 0.0f) {
    lit.ng = -lit.ng;
    lit.ns = -lit.ns;
  }
  Vec3 radiance = direct_irradiance(context, lit, sampler) * kInvPi;
  const RenderSettings& s = *context.settings;
  if (!state_.caustic.empty())
    radiance += state_.caustic.radiance_estimate(
        y.p, bsdf.ng(), static_cast<size_t>(std::max(s.caustic_gather_count, 1)),
        state_.caustic_radius, kPhotonCaustic, scratch);
  // One cosine-distributed ray: pdf cos / pi, so its radiance is the (albedo 1) estimate.
  const Vec3 wi = bsdf.frame().to_world(sample_cosine_hemisphere(sampler.get_2d()));
  if (dot(wi, bsdf.ng()) > 0.0f) {
    Ray ray;
    spawn_ray(y, wi, context.accel->length_scale(), &ray);
    radiance += gather_ray(context, ray, sampler, scratch, nullptr, false);
  }
  return radiance;
}

Vec3 PhotonMapIntegrator::gather_ray(const RenderContext& context, Ray ray, Sampler& sampler,
                                     std::vector<PhotonNeighbor>* scratch, float* hit_distance,
                                     bool primary) const {
  // A final-gather ray reads the precomputed radiance at every diffuse surface it meets and
  // goes on through glossy and specular lobes (importance_rules, path_walker.h).
  struct GatherVisitor {
    const RenderContext& context;
    const PhotonMapIntegrator& self;
    std::vector<PhotonNeighbor>* scratch;
    float* hit_distance;
    Sampler& sampler;
    bool primary;
    Vec3 sum{0.0f};
    ShadingPoint sp{};

    // Light met on the way is direct light (light sampling) or a caustic (the caustic map),
    // unless a rough glossy lobe was followed: neither of those holds such paths.
    bool segment(const PathState& state, bool found, const Hit& hit) {
      if (state.after_glossy) {
        float t_light;
        Vec3 lamp;
        if (context.emitters->intersect_lamps(state.ray, found ? hit.t : state.ray.tmax, state.mask,
                                              &t_light, &lamp)) {
          sum = sum + state.throughput * lamp;
          return false;
        }
        if (!found) {
          sum = sum + state.throughput *
                          (context.emitters->world_radiance(state.ray.direction) +
                           context.lights->distant_radiance(state.ray.direction, state.mask));
          return false;
        }
      }
      if (state.depth == 0 && hit_distance) *hit_distance = found ? hit.t : INFINITY;
      return found;
    }
    VertexStep vertex(PathState& state, const Hit& hit, const SurfaceInteraction& y) {
      sp = shade(context, y, -state.ray.direction);
      if (state.after_glossy) sum += state.throughput * sp.emission;
      const Vec3 rd = sp.bsdf.diffuse_reflectance(-state.ray.direction);
      if (!is_black(rd)) {
        // A record's estimate is blurred over about the secondary distance: at a nearer first hit
        // (a contact, a corner) that blur is larger than the gather's own spread, so the point
        // takes one more bounce (a secondary final gather) instead.
        const bool near = primary && state.depth == 0 && hit.t < self.state_.secondary_distance;
        sum += state.throughput * rd *
               (near ? self.secondary_radiance(context, y, sp.bsdf, -state.ray.direction, sampler,
                                               scratch)
                     : self.gathered_radiance(y.p, sp.bsdf.ng(), scratch));
      }
      return VertexStep::scatter(sp.bsdf);
    }
    void scattered(const PathState&, bool) {}
  };
  PathState state;
  state.ray = ray;
  state.mask = kVisibleDiffuse;
  GatherVisitor visitor{context, *this, scratch, hit_distance, sampler, primary};
  walk_path(context, importance_rules(context.settings->max_depth), &state, sampler, visitor);
  return visitor.sum;
}

Vec3 PhotonMapIntegrator::final_gather(const RenderContext& context, const SurfaceInteraction& x,
                                       const Bsdf& bsdf, int n, Sampler& sampler,
                                       float* harmonic_distance,
                                       const std::atomic<bool>* cancel) const {
  const Vec2 shift = sampler.get_2d();
  const Frame& frame = bsdf.frame();
  std::vector<PhotonNeighbor>& scratch = scratch_neighbors();
  // Directions from the nearest record's photon histogram mixed with cosine sampling; without
  // a record, plain cosine sampling.
  const RadianceRecord* record = state_.radiance.nearest(x.p, bsdf.ng(), kGatherMinCos);
  const GuidedSquare guide(record ? record->guide : GuideHistogram{});
  Vec3 sum(0.0f);
  double inverse_distances = 0.0;  // for the harmonic mean (Ward 1988)
  int traced = 0;
  for (int j = 0; j < n; ++j) {
    if (cancel && (j & 63) == 0 && cancel->load(std::memory_order_relaxed)) break;
    // pdf = density * cos / pi, so each ray adds (albedo / pi) L cos / pdf = albedo L / density.
    float density;
    const Vec2 u = guide.sample(rotated_r2(static_cast<uint32_t>(j), shift), &density);
    const Vec3 wi = frame.to_world(sample_cosine_hemisphere(u));
    if (dot(wi, bsdf.ng()) <= 0.0f) continue;
    Ray ray;
    spawn_ray(x, wi, context.accel->length_scale(), &ray);
    float t = INFINITY;
    sum += gather_ray(context, ray, sampler, &scratch, harmonic_distance ? &t : nullptr) / density;
    inverse_distances += 1.0 / std::max(t, 1e-6f * context.accel->length_scale());
    ++traced;
  }
  if (harmonic_distance)
    *harmonic_distance =
        inverse_distances > 0.0 ? static_cast<float>(traced / inverse_distances) : INFINITY;
  return sum / static_cast<float>(n);
}

// The classic photon-map view: a dot where a stored photon lies, coloured by its power's hue.
// The dot radius follows the local photon spacing, so dots stay dots in dense and sparse areas.
Vec3 PhotonMapIntegrator::photon_dots(const SurfaceInteraction& x) const {
  std::vector<PhotonNeighbor>& scratch = scratch_neighbors();
  for (const PhotonMap* map : {&state_.caustic, &state_.global}) {
    if (map->empty()) continue;
    map->k_nearest(x.p, 8, state_.global_radius, kPhotonAny, &scratch);
    if (scratch.size() < 2) continue;
    const float spacing2 =
        kPi * scratch.front().distance_squared / static_cast<float>(scratch.size());
    float best = INFINITY;
    uint32_t index = 0;
    for (const PhotonNeighbor& nb : scratch)
      if (nb.distance_squared < best) best = nb.distance_squared, index = nb.index;
    if (best < 0.09f * spacing2) {
      // A spectral photon shows its wavelength's colour (within the gamut).
      const Vec3 power = max(map->power((*map)[index]), Vec3(0.0f));
      const float m = max_component(power);
      return m > 0.0f ? power / m : Vec3(0.0f);
    }
  }
  return Vec3(0.0f);
}

void PhotonMapIntegrator::shade_diffuse(const RenderContext& context, const PathVertex& v,
                                        Sampler& sampler, RadianceSample* result) const {
  const RenderSettings& s = *context.settings;
  const SurfaceInteraction& x = *v.si;
  const Bsdf& bsdf = v.shading->bsdf;
  if (s.light_passes && v.depth == 0) result->photon_map = photon_dots(x);
  if (v.spectral) return shade_diffuse_spectral(context, v, sampler, result);
  const Vec3 weight = v.throughput * bsdf.diffuse_reflectance(v.wo);
  if (is_black(weight)) return;
  std::vector<PhotonNeighbor>& scratch = scratch_neighbors();
  if (!state_.caustic.empty())
    result->caustic +=
        weight * state_.caustic.radiance_estimate(
                     x.p, bsdf.ng(), static_cast<size_t>(std::max(s.caustic_gather_count, 1)),
                     state_.caustic_radius, kPhotonCaustic, &scratch);
  // Final gathering at the first diffuse surface of the camera path, whatever lobes led there,
  // and at any diffuse surface seen through perfect mirrors and glass only; the global map's
  // own estimate only after a diffuse reflection (Jensen 1996, "Global Illumination using
  // Photon Maps": the approximate evaluation once the path has been reflected diffusely). A
  // rough glossy reflection does not hide the map's blur: a metal sphere of roughness 0.2
  // mirrors the floor beside it, lit by the sphere's own glossy caustic, which the map's disc
  // of k photons spreads far wider than the reflection blurs it.
  const bool gather = s.final_gather_rays > 0 && (!v.after_glossy || !v.after_diffuse);
  Vec3 cached;
  if (gather && state_.irradiance.lookup(x.p, bsdf.frame().n, &cached)) {
    result->indirect += weight * cached;
  } else if (gather) {
    result->indirect += weight * final_gather(context, x, bsdf, s.final_gather_rays, sampler);
  } else if (!state_.global.empty()) {
    // Photons that bounced off a diffuse or glossy surface at least once; direct light and
    // caustics come from the other two estimates.
    result->indirect +=
        weight * state_.global.radiance_estimate(x.p, bsdf.ng(),
                                                 static_cast<size_t>(std::max(s.gather_count, 1)),
                                                 state_.global_radius, kPhotonIndirect, &scratch);
  }
}

// Spectral paths. The photon estimates reflect each spectral photon at its own wavelength and
// return the reflected light in Rec.709; the final gather and its caches are RGB (the gather
// rays and radiance records are not spectral: a tristimulus approximation of the indirect
// light, uplifted as an illuminant where a camera path meets it).
//  - Light reflected towards the camera's first hit is added as it is (the path's weight is 1
//    at every wavelength there); deeper in the path (seen in a mirror, through glass) it is
//    uplifted and weighted by the path at its wavelengths.
//  - Incident light (albedo 1) is uplifted and weighted by the path and the reflectance.
void PhotonMapIntegrator::shade_diffuse_spectral(const RenderContext& context, const PathVertex& v,
                                                 Sampler& sampler, RadianceSample* result) const {
  const RenderSettings& s = *context.settings;
  const SurfaceInteraction& x = *v.si;
  const Bsdf& bsdf = v.shading->bsdf;
  const SpectralVertex& sv = *v.spectral;
  const SampledWavelengths& wl = *sv.wl;
  const SampledSpectrum weight = sv.beta * sv.bsdf->diffuse_reflectance(v.wo);
  if (is_black(weight)) return;
  const Vec3 albedo = bsdf.diffuse_reflectance(v.wo);
  const auto add_reflected = [&](const Vec3& reflected, Vec3* pass, SpectralTally* tally) {
    if (v.depth == 0)
      *pass += reflected;
    else if (!is_black(reflected))
      tally->add(sv.beta * spectral::illuminant_at(reflected, wl), wl);
  };
  const auto add_incident = [&](const Vec3& incident, SpectralTally* tally) {
    if (!is_black(incident)) tally->add(weight * spectral::illuminant_at(incident, wl), wl);
  };
  std::vector<PhotonNeighbor>& scratch = scratch_neighbors();
  if (!state_.caustic.empty())
    add_reflected(state_.caustic.reflected_estimate(
                      x.p, bsdf.ng(), static_cast<size_t>(std::max(s.caustic_gather_count, 1)),
                      state_.caustic_radius, kPhotonCaustic, albedo, &scratch),
                  &result->caustic, &sv.light->caustic);
  const bool gather = s.final_gather_rays > 0 && (!v.after_glossy || !v.after_diffuse);
  Vec3 cached;
  if (gather && state_.irradiance.lookup(x.p, bsdf.frame().n, &cached)) {
    add_incident(cached, &sv.light->indirect);
  } else if (gather) {
    add_incident(final_gather(context, x, bsdf, s.final_gather_rays, sampler), &sv.light->indirect);
  } else if (!state_.global.empty()) {
    add_reflected(state_.global.reflected_estimate(
                      x.p, bsdf.ng(), static_cast<size_t>(std::max(s.gather_count, 1)),
                      state_.global_radius, kPhotonIndirect, albedo, &scratch),
                  &result->indirect, &sv.light->indirect);
  }
}

RadianceSample PhotonMapIntegrator::radiance_from_hit(const RenderContext& context,
                                                      const Ray& camera_ray, const CameraHit& first,
                                                      Sampler& sampler) const {
  RadianceSample result;
  trace_camera_path(
      context, camera_ray, first, sampler,
      [&](const PathVertex& v, RadianceSample* r) { shade_diffuse(context, v, sampler, r); },
      &result);
  return result;
}

bool PhotonMapIntegrator::baked_radiance(const RenderContext& context, const Hit& hit,
                                         const SurfaceInteraction& si, Sampler& sampler,
                                         Vec3* radiance) const {
  (void)hit;
  // The view-independent part of the surface: its emission and its diffuse lobes (seen along
  // the normal of the baked side). Surfaces with neither (mirrors, glass, metals) cannot bake.
  const ShadingPoint sp = shade(context, si, si.ng);
  const Vec3 albedo = sp.bsdf.diffuse_reflectance();
  if (is_black(albedo) && is_black(sp.emission)) return false;
  Vec3 reflected(0.0f);
  if (!is_black(albedo)) {
    const RenderSettings& s = *context.settings;
    const int n = std::max(s.samples, 1);
    std::vector<PhotonNeighbor>& scratch = scratch_neighbors();
    Vec3 cached(0.0f);
    const bool gather = s.final_gather_rays > 0;
    const bool from_cache = gather && bake_irradiance_.lookup(si.p, si.ns, &cached);
    // Direct light and final gathering are averaged over n stratified samples (the sampler's
    // 2D dimensions follow the R2 sequence over the n sample indices).
    const uint64_t stream = derived_stream(sampler);
    Vec3 direct(0.0f), indirect(0.0f);
    for (int k = 0; k < n; ++k) {
      Sampler inner(s.seed, stream, static_cast<uint32_t>(k), static_cast<uint32_t>(n));
      direct += direct_irradiance(context, si, inner);
      if (gather && !from_cache)
        indirect += final_gather(context, si, sp.bsdf, s.final_gather_rays, inner);
    }
    reflected = direct * (kInvPi / n) + (from_cache ? cached : indirect / static_cast<float>(n));
    if (!gather && !state_.global.empty())
      reflected += state_.global.radiance_estimate(si.p, si.ng,
                                                   static_cast<size_t>(std::max(s.gather_count, 1)),
                                                   state_.global_radius, kPhotonIndirect, &scratch);
    if (!state_.caustic.empty())
      reflected += state_.caustic.radiance_estimate(
          si.p, si.ng, static_cast<size_t>(std::max(s.caustic_gather_count, 1)),
          state_.caustic_radius, kPhotonCaustic, &scratch);
    reflected *= albedo;
  }
  *radiance = sp.emission + reflected;
  return true;
}

bool PhotonMapIntegrator::baked_probe(const RenderContext& context, const Hit& hit,
                                      const SurfaceInteraction& si, Sampler& sampler,
                                      Vec3* radiance) const {
  (void)hit, (void)sampler;
  const ShadingPoint sp = shade(context, si, si.ng);
  const Vec3 albedo = sp.bsdf.diffuse_reflectance();
  if (is_black(albedo) && is_black(sp.emission)) return false;
  // The photons tell a lit side from a dark one without tracing a ray: the total radiance
  // (direct photons included) of the nearest precomputed record on this side, else a small
  // estimate. Both sides of a bake point are probed, so this keeps the probe cheap.
  Vec3 photons(0.0f);
  if (!state_.global.empty()) photons = gathered_radiance(si.p, si.ng, &scratch_neighbors());
  *radiance = sp.emission + albedo * photons;
  return true;
}

void PhotonMapIntegrator::prepare_bake(const RenderContext& context, const BakePointSet& points,
                                       const PrepareControl& control) {
  bake_irradiance_ = IrradianceCache();
  const RenderSettings& s = *context.settings;
  if (s.final_gather_rays <= 0 || state_.global.empty()) return;
  PointIrradianceCacheSettings settings;
  settings.rays =
      std::clamp(kRecordRaysPerGatherRay * s.final_gather_rays, kMinRecordRays, kMaxRecordRays);
  settings.seed = s.seed;
  auto gather = [&](const SurfaceInteraction& si, int rays, Sampler& sampler, float* harmonic) {
    const ShadingPoint sp = shade(context, si, si.ng);
    return final_gather(context, si, sp.bsdf, rays, sampler, harmonic, control.cancel);
  };
  PointIrradianceCacheStats build;
  bake_irradiance_ = build_point_irradiance_cache(points, gather, settings, control, &build);
  IrradianceCacheStats& cache = stats_.bake_irradiance_cache.emplace();
  cache.records = bake_irradiance_.size();
  cache.candidates = build.candidates;
  cache.seconds = build.seconds;
}

bool PhotonMapIntegrator::coarse_settings(const RenderSettings& settings,
                                          RenderSettings* coarse) const {
  const bool budget = settings.photon_time > 0.0f;
  if (!budget && settings.photons < kCoarsePhotonShare * kMinCoarsePhotons) return false;
  *coarse = settings;
  coarse->photons = std::max<uint64_t>(settings.photons / kCoarsePhotonShare, 1);
  coarse->caustic_photons = settings.caustic_photons / kCoarsePhotonShare;
  coarse->photon_time = settings.photon_time / kCoarsePhotonShare;
  return true;
}

IntegratorInfo photon_map_integrator_info() {
  IntegratorInfo info;
  info.type = IntegratorType::kPhotonMap;
  info.label = "Photon Mapping";
  info.description =
      "Global illumination and caustics from global and caustic photon maps, with final "
      "gathering";
  IntegratorCapabilities& c = info.capabilities;
  c.name = "PHOTON_MAP";
  c.prepares = true;
  c.bake = true;
  c.shares_preparation = true;
  // Only photon tracing (photon_tracer.cpp) polls stop_early; the maps are then built from the
  // photons stored so far.
  c.stop_early = true;
  c.stop_early_status = "Tracing photons";
  c.stop_early_effect = "photon tracing stopped, rendering with the photons traced so far";
  info.make = [] { return std::unique_ptr<Integrator>(new PhotonMapIntegrator); };
  return info;
}

}  // namespace photon
