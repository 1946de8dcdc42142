// Whole-frame renders through the render session, as Blender and the CLI run them: scene
// resources, the integrator's preparation and every pixel. The figures to watch when the
// renderer's structure changes (film, integrators, lights): wall time per frame of the Cornell
// box and the caustic box under photon mapping, and of the caustic box under SPPM and VCM.
// Run: build/render_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// Machine noise on a shared 2-core machine is about 1-2%; for a finer comparison count
// instructions of one configuration with callgrind (docs/benchmarks.md).
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "photon/session/render_session.h"
#include "photon/testing/test_scenes.h"

using namespace photon;

namespace {

constexpr int kSize = 128;

RenderSettings frame_settings(IntegratorType integrator) {
  RenderSettings s;
  s.integrator = integrator;
  s.full_width = s.full_height = kSize;
  s.x1 = s.y1 = kSize;
  s.samples = 16;
  s.photons = 100000;
  s.caustic_photons = 50000;
  s.sppm_iterations = 16;
  s.sppm_photons_per_iteration = 50000;
  s.vcm_iterations = 16;
  s.vcm_light_paths = 50000;
  return s;
}

void render_frame(benchmark::State& state, Scene (*make)(float), IntegratorType integrator) {
  const auto scene = std::make_shared<const Scene>(make(make == make_cornell_box ? 40.0f : 60.0f));
  const RenderSettings settings = frame_settings(integrator);
  for (auto _ : state) {
    RenderSession session(scene, settings);
    session.start();
    session.wait();
    benchmark::DoNotOptimize(session.image().data());
  }
  state.SetItemsProcessed(state.iterations() * kSize * kSize);
}

void BM_CornellBox_PhotonMap(benchmark::State& state) {
  render_frame(state, make_cornell_box, IntegratorType::kPhotonMap);
}
void BM_CausticBox_PhotonMap(benchmark::State& state) {
  render_frame(state, make_caustic_box, IntegratorType::kPhotonMap);
}
void BM_CausticBox_Sppm(benchmark::State& state) {
  render_frame(state, make_caustic_box, IntegratorType::kSppm);
}
void BM_CausticBox_Vcm(benchmark::State& state) {
  render_frame(state, make_caustic_box, IntegratorType::kVcm);
}
void BM_CornellBox_RayTrace(benchmark::State& state) {
  render_frame(state, make_cornell_box, IntegratorType::kRayTrace);
}

}  // namespace

BENCHMARK(BM_CornellBox_PhotonMap)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CausticBox_PhotonMap)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CausticBox_Sppm)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CausticBox_Vcm)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CornellBox_RayTrace)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
