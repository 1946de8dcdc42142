#include "photon/session/bake.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <chrono>

#include "photon/integrators/registry.h"
#include "photon/session/render_session.h"
#include "photon/session/scene_resources.h"

namespace photon {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Per mesh: the caller's triangle index -> the index after clean_mesh dropped triangles
// (-1 for dropped ones). Empty when nothing was dropped (the numberings agree).
std::vector<std::vector<int32_t>> kept_triangle_maps(const Scene& scene) {
  std::vector<std::vector<int32_t>> maps(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const std::vector<uint32_t>& source = scene.meshes[m].source_triangles;
    if (source.empty()) continue;
    uint32_t count = 0;
    for (uint32_t s : source) count = std::max(count, s + 1);
    maps[m].assign(count, -1);
    for (size_t kept = 0; kept < source.size(); ++kept)
      maps[m][source[kept]] = static_cast<int32_t>(kept);
  }
  return maps;
}

constexpr int kProbeSamples = 2;        // per side, to choose the brighter side
constexpr float kBackSideRatio = 2.0f;  // how much brighter the back must be to be baked
constexpr size_t kChunk = 256;          // points per parallel task (a few ms of work)

std::string count_message(size_t n, const char* what) {
  return std::to_string(n) + " point(s) " + what;
}

}  // namespace

BakeResult bake_points(const Scene& scene, const RenderSettings& input_settings,
                       const BakeOptions& options, const std::vector<BakePoint>& points,
                       const PrepareControl& control, const std::function<void()>& on_prepared,
                       std::atomic<size_t>* points_done) {
  BakeResult result;
  RenderSettings settings = sanitized_settings(input_settings, &result.warnings);
  // The camera's irradiance cache is never read by a bake (prepare_bake places its own).
  settings.irradiance_cache = false;
  const size_t n = points.size();
  result.radiance.assign(n, Vec3(0.0f));
  result.position.assign(n, Vec3(0.0f));
  result.normal.assign(n, Vec3(0.0f));
  result.status.assign(n, kBakeNotDone);
  const IntegratorCapabilities capabilities = integrator_capabilities(settings.integrator);
  if (!capabilities.bake) {
    result.error = capabilities.no_bake_reason;
    return result;
  }

  result.threads = run_in_arena(settings.threads, [&] {
    auto t0 = Clock::now();
    control.report("Building BVH, lights and textures", 0.0f);
    const SceneResources resources(scene, settings, &result.warnings);
    const Accel& accel = resources.accel();
    result.build_seconds = seconds_since(t0);
    if (control.cancelled()) return;
    const RenderContext& context = resources.context();
    std::unique_ptr<Integrator> integrator = make_integrator(settings.integrator);

    t0 = Clock::now();
    PrepareControl prepare = control;
    prepare.warn = [&result](const std::string& w) { result.warnings.push_back(w); };
    integrator->prepare(context, prepare);
    result.prepare_seconds = seconds_since(t0);
    result.integrator_stats = integrator->prepare_stats();
    if (control.cancelled()) return;
    control.report("Locating " + std::to_string(n) + " points", 1.0f);

    const std::vector<std::vector<int32_t>> kept = kept_triangle_maps(scene);
    // Point i on the scene (its triangle renumbered past dropped ones), on the side that is
    // baked (`back` flips the normals).
    auto resolve = [&](size_t i, bool back, Hit* hit, SurfaceInteraction* si) {
      const BakePoint& point = points[i];
      uint32_t triangle = point.triangle;
      // An instance of a mesh that does not exist has no surface: accel rejects the point.
      if (point.instance < scene.instances.size() &&
          scene.instances[point.instance].mesh < kept.size()) {
        const std::vector<int32_t>& map = kept[scene.instances[point.instance].mesh];
        if (!map.empty())
          triangle = triangle < map.size() ? static_cast<uint32_t>(map[triangle]) : UINT32_MAX;
      }
      if (triangle == UINT32_MAX ||
          !accel.surface_hit(point.instance, triangle, point.u, point.v, hit))
        return false;
      *si = accel.interaction(*hit);
      // Barycentrics far outside the triangle (or NaN) put the point at infinity.
      if (!is_finite(si->p) || !is_finite(si->ns) || !is_finite(si->ng)) return false;
      if (back) si->ng = -si->ng, si->ns = -si->ns;
      return true;
    };
    RenderSettings probe_settings = settings;
    probe_settings.samples = std::min(settings.samples, kProbeSamples);
    RenderContext probe_context = context;
    probe_context.settings = &probe_settings;
    t0 = Clock::now();
    // Chunks of kChunk points: cancellation is polled between chunks, a few ms apart.
    const tbb::blocked_range<size_t> all(0, n, kChunk);

    // 1. Where each point is, and which side is baked.
    std::vector<uint8_t> back_side(n, 0);
    tbb::parallel_for(
        all,
        [&](const auto& range) {
          if (control.cancelled()) return;
          for (size_t i = range.begin(); i != range.end(); ++i) {
            Hit hit;
            SurfaceInteraction front;
            if (!resolve(i, false, &hit, &front)) {
              result.status[i] = kBakeInvalidPoint;
              continue;
            }
            SurfaceInteraction side = front;
            if (options.brighter_side) {
              // A cheap estimate of both sides picks the side, then only that side gets the full
              // estimate.
              SurfaceInteraction back = front;
              back.ng = -back.ng;
              back.ns = -back.ns;
              Sampler front_probe(settings.seed, 3 * i + 1, 0, 1),
                  back_probe(settings.seed, 3 * i + 2, 0, 1);
              Vec3 front_radiance, back_radiance;
              const bool front_ok =
                  integrator->baked_probe(probe_context, hit, front, front_probe, &front_radiance);
              const bool back_ok =
                  integrator->baked_probe(probe_context, hit, back, back_probe, &back_radiance);
              // The front side keeps the point unless the back is clearly brighter: two dim
              // sides (a box face outside, the light leaking into its closed inside) would
              // otherwise be picked by sampling noise, point by point.
              if (back_ok && (!front_ok || luminance(back_radiance) >
                                               kBackSideRatio * luminance(front_radiance))) {
                side = back;
                back_side[i] = 1;
              }
            }
            result.position[i] = side.p;
            result.normal[i] = side.ns;
          }
        },
        tbb::simple_partitioner());
    if (control.cancelled()) return;
    result.locate_seconds = seconds_since(t0);

    // 2. Work shared between points (an irradiance cache among them).
    t0 = Clock::now();
    std::vector<uint8_t> valid(n);
    for (size_t i = 0; i < n; ++i) valid[i] = result.status[i] != kBakeInvalidPoint;
    BakePointSet set;
    set.count = n;
    set.positions = result.position.data();
    set.normals = result.normal.data();
    set.valid = valid.data();
    set.interaction = [&](size_t i, SurfaceInteraction* si) {
      Hit hit;
      return resolve(i, back_side[i] != 0, &hit, si);
    };
    integrator->prepare_bake(context, set, control);
    result.integrator_stats = integrator->prepare_stats();
    if (control.cancelled()) return;
    result.share_seconds = seconds_since(t0);
    if (on_prepared) on_prepared();
    control.report("Baking " + std::to_string(n) + " points", 0.0f);

    // 3. The estimate of every point.
    t0 = Clock::now();
    tbb::parallel_for(
        all,
        [&](const auto& range) {
          if (control.cancelled()) return;
          for (size_t i = range.begin(); i != range.end(); ++i) {
            if (!valid[i]) continue;
            Hit hit;
            SurfaceInteraction side;
            resolve(i, back_side[i] != 0, &hit, &side);
            // The streams follow the point's index, so the result does not depend on which thread
            // shades it.
            Sampler sampler(settings.seed, 3 * i, 0, 1);
            Vec3 radiance;
            const bool ok = integrator->baked_radiance(context, hit, side, sampler, &radiance);
            if (!ok) {
              result.status[i] = kBakeUnsupported;
            } else if (!is_finite(radiance)) {
              result.status[i] = kBakeNonFinite;
            } else {
              result.radiance[i] = radiance;
              result.status[i] = kBakeOk;
            }
          }
          if (points_done) *points_done += range.size();
        },
        tbb::simple_partitioner());
    result.bake_seconds = seconds_since(t0);
  });

  result.cancelled = control.cancelled();
  size_t counts[5] = {0, 0, 0, 0, 0};
  for (uint8_t s : result.status) ++counts[s];
  if (!result.cancelled && n > 0 && counts[kBakeOk] == 0 && counts[kBakeUnsupported] > 0)
    result.error = "the integrator returned no view-independent radiance for any of the " +
                   std::to_string(n) +
                   " points: it has no bake support, or every point is on a mirror or glass "
                   "surface";
  if (counts[kBakeInvalidPoint])
    result.warnings.push_back(count_message(counts[kBakeInvalidPoint],
                                            "name no existing instance or triangle (or a "
                                            "degenerate triangle that was dropped)"));
  if (counts[kBakeUnsupported])
    result.warnings.push_back(count_message(counts[kBakeUnsupported],
                                            "lie on surfaces without view-independent radiance "
                                            "(mirror, glass) and were baked black"));
  if (counts[kBakeNonFinite])
    result.warnings.push_back(count_message(counts[kBakeNonFinite],
                                            "had a NaN or infinite estimate and were baked black"));
  return result;
}

BakeSession::BakeSession(std::shared_ptr<const Scene> scene, const RenderSettings& settings,
                         const BakeOptions& options, std::vector<BakePoint> points)
    : Job("Bake"),
      scene_(std::move(scene)),
      settings_(settings),
      options_(options),
      points_(std::move(points)) {
  set_work_total(points_.size());
}

BakeSession::~BakeSession() {
  stop_worker();
}

BakeResult BakeSession::result() const {
  BakeResult result;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    result = result_;
  }
  const std::string failure = error();
  if (!failure.empty() && result.error.empty()) result.error = "bake failed: " + failure;
  return result;
}

void BakeSession::run() {
  // The bake's warnings go into its result (bake_points collects them).
  const PrepareControl control = prepare_control();
  set_preparing(true);
  BakeResult result = bake_points(
      *scene_, settings_, options_, points_, control, [this] { set_preparing(false); },
      &work_done());
  std::lock_guard<std::mutex> lock(mutex_);
  result_ = std::move(result);
}

}  // namespace photon
