#include "photon/integrators/radiosity/radiosity_solver.h"

#include <tbb/parallel_for.h>

#include <chrono>
#include <cstdio>

#include "photon/base/sampling.h"
#include "photon/integrators/camera_path.h"
#include "photon/integrators/photon_map/photon_sources.h"
#include "photon/integrators/radiosity/radiosity_material.h"
#include "photon/integrators/radiosity/radiosity_params.h"

namespace photon {
namespace {

using Clock = std::chrono::steady_clock;

constexpr size_t kChunkRays = 4096;      // rays per task; fixed, so results ignore thread count
constexpr size_t kBatchChunks = 64;      // chunks traced between two cancel checks / progress
constexpr uint64_t kMinStepRays = 4096;  // an incremental step never shoots fewer rays
constexpr int kMaxIncrementalSteps = 500;
constexpr uint32_t kLightMask =
    kVisibleDiffuse | kVisibleGlossy | kVisibleTransmission | kVisibleShadow;

double scalar(const Vec3& v) {
  return (static_cast<double>(v.x) + v.y + v.z) / 3.0;
}

struct DVec3 {
  double x = 0, y = 0, z = 0;
  void add(const Vec3& v) { x += v.x, y += v.y, z += v.z; }
  void add(const DVec3& v) { x += v.x, y += v.y, z += v.z; }
  double mean() const { return (x + y + z) / 3.0; }
  Vec3 to_float(double scale = 1.0) const {
    return {static_cast<float>(x * scale), static_cast<float>(y * scale),
            static_cast<float>(z * scale)};
  }
};

enum Kind : uint8_t { kDirect, kCaustic, kIndirect };

struct Deposit {
  uint32_t slot;
  uint8_t kind;
  Vec3 power;
};

struct ChunkOutput {
  std::vector<Deposit> deposits;
  DVec3 absorbed, absorbed_specular, escaped, shot;
};

// The reflected power received by every element side in one step, plus where the rest went.
struct StepResult {
  std::vector<DVec3> received[3];  // by Kind, per slot
  std::vector<uint32_t> hits;      // deposits per slot
  DVec3 absorbed, absorbed_specular, escaped, shot;
  uint64_t rays = 0;
  bool complete = false;
};

// One Jacobi step's sources: `light_rays` rays from the lights, `element_rays` from the
// element sides in proportion to `source` (systematic sampling of the power CDF).
struct StepPlan {
  uint64_t light_rays = 0;
  uint64_t element_rays = 0;
  const std::vector<Vec3>* source = nullptr;
  std::vector<double> cdf;  // prefix sums of scalar(source), size slots + 1
  uint64_t seed = 0;
};

struct ShootVisitor {
  const RenderContext& context;
  const RadiosityMesh& mesh;
  bool from_light;
  ChunkOutput* out;
  ShadingPoint sp{};
  Vec3 arriving{0.0f}, reflected{0.0f};
  bool located = false;

  bool segment(const PathState& state, bool found, const Hit&) {
    if (!found) out->escaped.add(state.throughput);
    return found;
  }
  VertexStep vertex(PathState& state, const Hit& hit, const SurfaceInteraction& si) {
    arriving = state.throughput;
    sp = shade(context, si, -state.ray.direction);
    const Bsdf& bsdf = sp.bsdf;
    reflected = arriving * min(bsdf.diffuse_reflectance(), Vec3(1.0f));
    RadiosityLocation where;
    located = mesh.locate(hit.instance, hit.primitive, hit.u, hit.v, &where);
    if (!is_black(reflected) && located) {
      // bsdf.ng() faces the arriving ray: that side receives (and re-emits) the light.
      const uint32_t side = dot(bsdf.ng(), mesh.normal(where.element)) >= 0.0f ? 0u : 1u;
      const uint8_t kind = from_light ? (state.depth == 0      ? kDirect
                                         : !state.after_glossy ? kCaustic
                                                               : kIndirect)
                                      : kIndirect;
      out->deposits.push_back({2 * mesh.patch_of(where.element) + side, kind, reflected});
    } else {
      reflected = Vec3(0.0f);
    }
    return VertexStep::scatter(bsdf);
  }
  void scattered(const PathState& state, bool continues) {
    // Absorbed by this surface (or lost to the roulette / depth limit); balances on average.
    const Vec3 next = continues ? state.throughput : Vec3(0.0f);
    (located ? out->absorbed : out->absorbed_specular).add(arriving - reflected - next);
  }
};

// Follows one ray to the surfaces it reaches. At each surface with a diffuse lobe, rho_d (read
// from the BSDF at the hit, textures included) times the arriving power is deposited on the
// element; the rest continues through the glossy and specular lobes (the walker's power rules,
// path_walker.h: sampled, with Russian roulette on the bounce's albedo) or is absorbed. Rays
// that leave the scene escape. The books balance per ray: arriving = deposited + absorbed +
// continuing.
void trace_ray(const RenderContext& context, const RadiosityMesh& mesh, Ray ray, const Vec3& power,
               uint32_t mask, bool from_light, Sampler& sampler, ChunkOutput* out) {
  out->shot.add(power);
  PathState state;
  state.ray = ray;
  state.mask = mask;
  state.throughput = power;
  ShootVisitor visitor{context, mesh, from_light, out};
  walk_path(context, power_rules(context.settings->max_depth, kLobeGlossy | kLobeSpecular), &state,
            sampler, visitor);
}

void shoot_chunk(const RenderContext& context, const RadiosityMesh& mesh,
                 const PhotonSources& sources, const StepPlan& plan, uint64_t begin, uint64_t end,
                 ChunkOutput* out) {
  const double element_total = plan.cdf.empty() ? 0.0 : plan.cdf.back();
  const double offset = to_unit_float(mix64(plan.seed ^ 0x5157u));
  for (uint64_t r = begin; r < end; ++r) {
    if (r < plan.light_rays) {
      Sampler sampler(plan.seed, 1, static_cast<uint32_t>(r),
                      static_cast<uint32_t>(plan.light_rays));
      EmittedPhoton photon;
      if (!sources.emit_global(sampler, &photon)) continue;
      trace_ray(context, mesh, photon.ray, photon.power / static_cast<float>(plan.light_rays),
                kLightMask, true, sampler, out);
      continue;
    }
    const uint64_t k = r - plan.light_rays;
    Sampler sampler(plan.seed, 2, static_cast<uint32_t>(k),
                    static_cast<uint32_t>(plan.element_rays));
    // Systematic sampling: ray k takes the (k + offset) / N quantile of the power CDF, so
    // every source gets its expected number of rays to within one.
    const double target = (static_cast<double>(k) + offset) / plan.element_rays * element_total;
    size_t slot = static_cast<size_t>(std::upper_bound(plan.cdf.begin(), plan.cdf.end(), target) -
                                      plan.cdf.begin());
    slot = std::clamp<size_t>(slot, 1, plan.cdf.size() - 1) - 1;
    while (slot + 2 < plan.cdf.size() && !(plan.cdf[slot + 1] > plan.cdf[slot])) ++slot;
    const Vec3& p = (*plan.source)[slot];
    const double ps = scalar(p);
    if (!(ps > 0.0)) continue;
    // Every ray carries the same power P_T / N (in the mean of the channels).
    const Vec3 power = p * static_cast<float>(element_total / (plan.element_rays * ps));
    // A uniform point on the patch (an element of a cluster in proportion to its area); the
    // element's own normal orients the side (all of a patch's elements face its way).
    const uint32_t patch = static_cast<uint32_t>(slot / 2);
    const float u_element = mesh.patch_element_count(patch) > 1 ? sampler.get_1d() : 0.0f;
    uint32_t element = 0;
    const Vec3 origin = mesh.sample_patch(patch, u_element, sampler.get_2d(), &element);
    const Vec3 n = slot % 2 == 0 ? mesh.normal(element) : -mesh.normal(element);
    Ray ray;
    ray.direction = Frame(n).to_world(sample_cosine_hemisphere(sampler.get_2d()));
    ray.origin = offset_ray_origin(origin, n, ray.direction, context.accel->length_scale());
    trace_ray(context, mesh, ray, power, kVisibleDiffuse, false, sampler, out);
  }
}

// Traces a step in fixed chunks, in parallel, and adds the chunks' deposits in chunk order.
StepResult shoot(const RenderContext& context, const RadiosityMesh& mesh,
                 const PhotonSources& sources, const StepPlan& plan, const PrepareControl& control,
                 const std::function<void(uint64_t)>& progress) {
  StepResult result;
  const size_t slots = 2 * mesh.patch_count();
  for (auto& r : result.received) r.assign(slots, DVec3());
  result.hits.assign(slots, 0);
  const uint64_t total = plan.light_rays + plan.element_rays;
  const uint64_t chunks = (total + kChunkRays - 1) / kChunkRays;
  std::vector<ChunkOutput> outputs(kBatchChunks);
  for (uint64_t first = 0; first < chunks; first += kBatchChunks) {
    if (control.should_stop()) return result;
    const uint64_t count = std::min<uint64_t>(kBatchChunks, chunks - first);
    tbb::parallel_for(uint64_t(0), count, [&](uint64_t c) {
      ChunkOutput& out = outputs[c];
      out = ChunkOutput();
      const uint64_t begin = (first + c) * kChunkRays;
      shoot_chunk(context, mesh, sources, plan, begin, std::min(total, begin + kChunkRays), &out);
    });
    for (uint64_t c = 0; c < count; ++c) {
      const ChunkOutput& out = outputs[c];
      for (const Deposit& d : out.deposits) {
        result.received[d.kind][d.slot].add(d.power);
        ++result.hits[d.slot];
      }
      result.absorbed.add(out.absorbed);
      result.absorbed_specular.add(out.absorbed_specular);
      result.escaped.add(out.escaped);
      result.shot.add(out.shot);
    }
    result.rays = std::min(total, (first + count) * kChunkRays);
    if (progress) progress(result.rays);
  }
  result.complete = !control.should_stop();
  return result;
}

std::vector<double> power_cdf(const std::vector<Vec3>& power) {
  std::vector<double> cdf(power.size() + 1, 0.0);
  for (size_t i = 0; i < power.size(); ++i) cdf[i + 1] = cdf[i] + std::max(scalar(power[i]), 0.0);
  return cdf;
}

std::string percent(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f%%", 100.0 * x);
  return buf;
}

// The power still unshot when shooting stops would, bounced on, add about
// U r / (1 - r) more reflected power, r being the fraction of shot power that the last step
// returned as reflected power. Like the ambient term of progressive refinement radiosity
// (Cohen, Chen, Wallace, Greenberg 1988), that estimate is added up front, per channel, here
// spread in proportion to the solution, so stopping at a threshold does not darken bright,
// closed scenes; the regular iterations that follow correct its distribution.
void add_ambient(const DVec3& last_shot, std::vector<RadiosityPower>* solution,
                 const std::vector<Vec3>& unshot) {
  DVec3 u, total;
  for (size_t s = 0; s < unshot.size(); ++s) {
    u.add(unshot[s]);
    total.add((*solution)[s].total());
  }
  const double shot[3] = {last_shot.x, last_shot.y, last_shot.z};
  const double remaining[3] = {u.x, u.y, u.z}, sum[3] = {total.x, total.y, total.z};
  Vec3 scale(0.0f);
  for (int c = 0; c < 3; ++c) {
    if (!(shot[c] > 0.0) || !(sum[c] > 0.0)) continue;
    const double r = std::clamp(remaining[c] / shot[c], 0.0, 0.95);
    scale[c] = static_cast<float>(remaining[c] * r / (1.0 - r) / sum[c]);
  }
  for (RadiosityPower& p : *solution) p.indirect += p.total() * scale;
}

}  // namespace

std::vector<RadiosityPower> solve_radiosity(const RenderContext& context, const RadiosityMesh& mesh,
                                            const RadiositySolveSettings& settings,
                                            const PrepareControl& control,
                                            RadiositySolveStats* stats_out) {
  const auto t0 = Clock::now();
  RadiositySolveStats stats;
  const size_t slots = 2 * mesh.patch_count();
  std::vector<RadiosityPower> solution(slots);
  const PhotonSources sources(context);
  const double emitted = scalar(sources.total_power());
  stats.emitted = emitted;
  auto finish = [&](std::vector<RadiosityPower> result) {
    stats.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    if (stats_out) *stats_out = stats;
    return result;
  };
  if (slots == 0 || !sources.has_global() || !(emitted > 0.0)) return finish(std::move(solution));

  // Ray budget: the incremental phase and each regular iteration shoot (about) all the light
  // once, so each gets an equal share.
  const uint64_t budget = std::max<uint64_t>(settings.rays, 2 * kMinStepRays);
  const int iterations = std::clamp(settings.iterations, 0, kMaxRadiosityIterations);
  const uint64_t incremental_budget = budget / static_cast<uint64_t>(iterations + 1);
  const uint64_t regular_budget = iterations > 0 ? (budget - incremental_budget) / iterations : 0;
  const double threshold = std::clamp(static_cast<double>(settings.threshold),
                                      kMinRadiosityThreshold, kMaxRadiosityThreshold);
  uint64_t rays_done = 0;
  auto report = [&](const std::string& what, uint64_t step_rays) {
    control.report(what, static_cast<float>(
                             std::min(1.0, static_cast<double>(rays_done + step_rays) / budget)));
  };
  auto accumulate_balance = [&](const StepResult& r) {
    stats.absorbed += r.absorbed.mean();
    stats.absorbed_specular += r.absorbed_specular.mean();
    stats.escaped += r.escaped.mean();
  };
  auto step_seed = [&](int phase, int step) {
    return hash_combine(settings.seed,
                        (static_cast<uint64_t>(phase) << 32) | static_cast<uint32_t>(step));
  };

  // ---- Phase 1: incremental shooting, first from the lights themselves. ----
  std::vector<Vec3> unshot(slots);
  stats.hits.assign(slots, 0);
  auto count_hits = [&](const StepResult& r) {
    for (size_t s = 0; s < slots; ++s) stats.hits[s] += r.hits[s];
  };
  double unshot_total = emitted;
  double rays_per_watt = 0.0;
  DVec3 last_shot;  // power shot by the last completed step, per channel
  for (int step = 0;; ++step) {
    StepPlan plan;
    plan.seed = step_seed(1, step);
    if (step == 0) {
      // Half the phase's rays for the first shot; the rest is paced after it (below).
      plan.light_rays = std::max<uint64_t>(kMinStepRays, incremental_budget / 2);
    } else {
      if (unshot_total <= threshold * emitted) break;
      if (step > kMaxIncrementalSteps || rays_done >= 2 * incremental_budget) {
        if (control.warn)
          control.warn("Radiosity: unshot power still " + percent(unshot_total / emitted) +
                       " of the emitted power after " + std::to_string(step) +
                       " shooting steps (very bright, closed scene?); going on");
        break;
      }
      plan.source = &unshot;
      plan.cdf = power_cdf(unshot);
      plan.element_rays = std::max<uint64_t>(
          kMinStepRays, static_cast<uint64_t>(std::llround(rays_per_watt * unshot_total)));
    }
    const std::string status = "Radiosity: iteration " + std::to_string(step + 1) + ", unshot " +
                               percent(unshot_total / emitted);
    const StepResult r =
        shoot(context, mesh, sources, plan, control, [&](uint64_t n) { report(status, n); });
    if (!r.complete) break;  // stopped: keep the total of the completed steps
    last_shot = r.shot;
    rays_done += r.rays;
    stats.rays += r.rays;
    ++stats.incremental_iterations;
    accumulate_balance(r);
    count_hits(r);
    unshot_total = 0.0;
    for (size_t s = 0; s < slots; ++s) {
      const Vec3 d = r.received[kDirect][s].to_float(), c = r.received[kCaustic][s].to_float(),
                 i = r.received[kIndirect][s].to_float();
      solution[s].direct += d;
      solution[s].caustic += c;
      solution[s].indirect += i;
      unshot[s] = d + c + i;
      unshot_total += scalar(unshot[s]);
    }
    if (step == 0) {
      // Reflected / emitted estimates the effective albedo rho; the remaining power to shoot
      // is about unshot / (1 - rho), spread over the rest of the phase's rays.
      const double rho = std::min(unshot_total / emitted, 0.95);
      const double remaining = unshot_total / (1.0 - rho);
      const uint64_t left = incremental_budget > rays_done ? incremental_budget - rays_done : 0;
      rays_per_watt = remaining > 0.0 ? std::max<double>(left, kMinStepRays) / remaining : 0.0;
    }
  }
  stats.unshot = unshot_total;
  if (control.cancelled()) return finish({});
  add_ambient(last_shot, &solution, unshot);
  if (control.should_stop() || iterations == 0) {
    stats.stopped_early = control.should_stop();
    return finish(std::move(solution));
  }

  // ---- Phase 2: regular Jacobi iterations from the whole solution, averaged. ----
  std::vector<Vec3> current(slots);
  for (size_t s = 0; s < slots; ++s) current[s] = solution[s].total();
  std::vector<DVec3> average[3];
  for (auto& a : average) a.assign(slots, DVec3());
  int done = 0;
  const std::vector<uint32_t> shooting_hits = stats.hits;
  std::fill(stats.hits.begin(), stats.hits.end(), 0u);
  for (int it = 0; it < iterations; ++it) {
    StepPlan plan;
    plan.seed = step_seed(2, it);
    plan.source = &current;
    plan.cdf = power_cdf(current);
    const double element_total = plan.cdf.back();
    plan.light_rays = std::max<uint64_t>(
        1,
        static_cast<uint64_t>(std::llround(regular_budget * emitted / (emitted + element_total))));
    plan.element_rays = element_total > 0.0 && regular_budget > plan.light_rays
                            ? regular_budget - plan.light_rays
                            : 0;
    const std::string status =
        "Radiosity: iteration " + std::to_string(stats.incremental_iterations + it + 1) +
        " (averaging " + std::to_string(it + 1) + "/" + std::to_string(iterations) + "), unshot " +
        percent(unshot_total / emitted);
    const StepResult r =
        shoot(context, mesh, sources, plan, control, [&](uint64_t n) { report(status, n); });
    if (!r.complete) break;
    rays_done += r.rays;
    stats.rays += r.rays;
    ++done;
    count_hits(r);
    for (size_t s = 0; s < slots; ++s) {
      current[s] = Vec3(0.0f);
      for (int k = 0; k < 3; ++k) {
        average[k][s].add(r.received[k][s]);
        current[s] += r.received[k][s].to_float();
      }
    }
  }
  stats.regular_iterations = done;
  if (control.cancelled()) return finish({});
  stats.stopped_early = done < iterations;
  if (done == 0) stats.hits = shooting_hits;
  if (done > 0) {
    const double inv = 1.0 / done;
    for (size_t s = 0; s < slots; ++s)
      solution[s] = {average[kDirect][s].to_float(inv), average[kCaustic][s].to_float(inv),
                     average[kIndirect][s].to_float(inv)};
  }
  return finish(std::move(solution));
}

}  // namespace photon
