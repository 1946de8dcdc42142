// Camera-ray throughput of the RAY_TRACE integrator against a bare Embree rtcIntersect1 loop over
// the same rays (and, for reference, the same rays as coherent rtcIntersect1M streams).
// Run: build/photon_bench --benchmark_filter=Camera
// Target: integrator camera rays >= 70% of the bare rtcIntersect1 loop.
#include <benchmark/benchmark.h>

#include <atomic>
#include <memory>

#include "photon/film/film.h"
#include "photon/integrators/ray_trace/ray_trace_integrator.h"
#include "photon/render/accel.h"
#include "photon/scene/camera.h"
#include "photon/session/scene_resources.h"
#include "photon/testing/test_scenes.h"

using namespace photon;

namespace {

constexpr int kSize = 256;

struct Fixture {
  Scene scene;
  std::vector<std::string> warnings;
  RenderSettings settings;
  std::unique_ptr<SceneResources> resources;
  const Accel* accel = nullptr;
  std::vector<Ray> rays;

  explicit Fixture(bool with_lights) {
    scene = make_cornell_box();
    // A dense sphere so the BVH is not trivially small.
    add_mesh_instance(&scene, make_uv_sphere({0.4f, 0.3f, 0.9f}, 0.3f, 256, 128), 0);
    if (!with_lights) scene.lights.clear();
    resources = std::make_unique<SceneResources>(scene, settings, &warnings);
    accel = &resources->accel();
    settings.full_width = settings.full_height = kSize;
    settings.x1 = settings.y1 = kSize;
    settings.max_depth = 0;
    settings.samples = 1;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x)
        rays.push_back(generate_camera_ray(scene.camera, (x + 0.5f) / kSize, (y + 0.5f) / kSize,
                                           Vec2(0.5f, 0.5f)));
  }
  const RenderContext& context() const { return resources->context(); }
};

void BM_CameraRays_BareEmbree(benchmark::State& state) {
  Fixture f(false);
  RTCScene top = f.accel->top_level();
  uint64_t hits = 0;
  for (auto _ : state) {
    for (const Ray& r : f.rays) {
      RTCRayHit rh;
      rh.ray.org_x = r.origin.x, rh.ray.org_y = r.origin.y, rh.ray.org_z = r.origin.z;
      rh.ray.dir_x = r.direction.x, rh.ray.dir_y = r.direction.y, rh.ray.dir_z = r.direction.z;
      rh.ray.tnear = r.tmin, rh.ray.tfar = r.tmax, rh.ray.time = 0, rh.ray.mask = kVisibleCamera;
      rh.ray.id = 0, rh.ray.flags = 0;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      embree::intersect1(top, &rh);
      hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
  }
  benchmark::DoNotOptimize(hits);
  state.SetItemsProcessed(state.iterations() * f.rays.size());
}

// The same rays as coherent batches of one 64-pixel tile row (a stream in Embree 3).
void BM_CameraRays_EmbreeStream(benchmark::State& state) {
  Fixture f(false);
  RTCScene top = f.accel->top_level();
  std::vector<RTCRayHit> batch(64);
  uint64_t hits = 0;
  for (auto _ : state) {
    for (size_t base = 0; base < f.rays.size(); base += batch.size()) {
      const size_t n = std::min(batch.size(), f.rays.size() - base);
      for (size_t i = 0; i < n; ++i) {
        const Ray& r = f.rays[base + i];
        RTCRayHit& rh = batch[i];
        rh.ray.org_x = r.origin.x, rh.ray.org_y = r.origin.y, rh.ray.org_z = r.origin.z;
        rh.ray.dir_x = r.direction.x, rh.ray.dir_y = r.direction.y, rh.ray.dir_z = r.direction.z;
        rh.ray.tnear = r.tmin, rh.ray.tfar = r.tmax, rh.ray.time = 0, rh.ray.mask = kVisibleCamera;
        rh.ray.id = 0, rh.ray.flags = 0;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      }
      embree::intersect_coherent(top, batch.data(), static_cast<unsigned>(n));
      for (size_t i = 0; i < n; ++i) hits += batch[i].hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
  }
  benchmark::DoNotOptimize(hits);
  state.SetItemsProcessed(state.iterations() * f.rays.size());
}

// One sample per pixel of the whole frame through the pixel loop, exactly as the renderer runs it.
void render_frame(benchmark::State& state, bool with_lights) {
  Fixture f(with_lights);
  RayTraceIntegrator integrator;
  RenderContext ctx = f.context();
  ctx.settings = &f.settings;
  Film film(film_frame(f.scene.camera, kSize, kSize, 0, 0, kSize, kSize), film_options(f.settings));
  std::atomic<bool> cancel{false};
  RenderControl control;
  control.end_pass = 1;
  control.cancel = &cancel;
  control.tile_size = kSize;  // one tile: a single thread, as the loop this measures used to be
  for (auto _ : state) integrator.render(ctx, film, control);
  benchmark::DoNotOptimize(film.non_finite());
  state.SetItemsProcessed(state.iterations() * kSize * kSize);
}

// Camera rays through the RAY_TRACE integrator: ray generation, coherent first-hit streams, hit
// shading setup and material lookup, with no lights so that no shadow rays are traced.
void BM_CameraRays_RayTraceIntegrator(benchmark::State& state) {
  render_frame(state, false);
}

// The full RAY_TRACE shading of one sample per pixel: camera ray plus one shadow ray.
void BM_ShadedSamples_RayTraceIntegrator(benchmark::State& state) {
  render_frame(state, true);
}

}  // namespace

BENCHMARK(BM_CameraRays_BareEmbree)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CameraRays_EmbreeStream)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CameraRays_RayTraceIntegrator)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ShadedSamples_RayTraceIntegrator)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
