// Photon map kernels: balancing the kd-tree, k-nearest queries, radiance estimates, and the
// same queries through nanoflann (Debian's libnanoflann-dev) for comparison when it is present.
#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <random>

#include "photon/base/rng.h"
#include "photon/base/sampling.h"
#include "photon/integrators/photon_map/photon_map.h"
#include "photon/integrators/photon_map/photon_tracer.h"
#include "photon/integrators/photon_map/radiance_cache.h"
#include "photon/session/scene_resources.h"
#include "photon/testing/test_scenes.h"

#if __has_include(<nanoflann.hpp>)
#include <nanoflann.hpp>
#define PHOTON_HAVE_NANOFLANN 1
#endif

namespace photon {
namespace {

// Photons on the six faces of a 2 m box, as in a Cornell box: realistic surface density.
std::vector<Photon> box_photons(size_t n) {
  std::vector<Photon> photons(n);
  for (size_t i = 0; i < n; ++i) {
    const uint64_t h = mix64(i);
    const float a = to_unit_float(h) * 2 - 1, b = to_unit_float(h << 24) * 2 - 1;
    const int face = static_cast<int>(mix64(h) % 6);
    Vec3 p = face < 2   ? Vec3(a, b, face ? 1.0f : -1.0f)
             : face < 4 ? Vec3(a, face == 3 ? 1.0f : -1.0f, b)
                        : Vec3(face == 5 ? 1.0f : -1.0f, a, b);
    photons[i] = Photon::make(p, -p, Vec3(1e-6f), kPhotonIndirect, p);
  }
  return photons;
}

Vec3 query_point(uint64_t i) {
  const uint64_t h = mix64(i + 12345);
  return {to_unit_float(h) * 2 - 1, to_unit_float(h << 24) * 2 - 1, -1.0f};
}

void BM_Build(benchmark::State& state) {
  const auto photons = box_photons(static_cast<size_t>(state.range(0)));
  for (auto _ : state) {
    PhotonMap map(photons);
    benchmark::DoNotOptimize(map.size());
  }
  state.counters["bytes"] = static_cast<double>(photons.size() * sizeof(Photon));
  state.counters["photons/s"] = benchmark::Counter(static_cast<double>(photons.size()),
                                                   benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_Build)->Arg(1000000)->Arg(10000000)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_KNearest(benchmark::State& state) {
  static const PhotonMap map(box_photons(1000000));
  const size_t k = static_cast<size_t>(state.range(0));
  std::vector<PhotonNeighbor> out;
  uint64_t i = 0;
  for (auto _ : state) {
    map.k_nearest(query_point(i++), k, 0.2f, kPhotonAny, &out);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["queries/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_KNearest)->Arg(8)->Arg(50)->Arg(100);

void BM_RadianceEstimate(benchmark::State& state) {
  static const PhotonMap map(box_photons(1000000));
  std::vector<PhotonNeighbor> out;
  uint64_t i = 0;
  Vec3 sum(0.0f);
  for (auto _ : state)
    sum += map.radiance_estimate(query_point(i++), Vec3(0, 0, 1), 100, 0.2f, kPhotonAny, &out);
  benchmark::DoNotOptimize(sum);
  state.counters["queries/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RadianceEstimate);

// Final-gather lookups: the nearest precomputed radiance record through the hashed grid, for
// records at a quarter of the photons (as the integrator makes them), vs an 8-nearest query.
void BM_RadianceCacheLookup(benchmark::State& state) {
  static const RadianceCache cache = [] {
    std::vector<RadianceRecord> records;
    for (const Photon& ph : box_photons(250000)) {
      RadianceRecord r;
      r.p = ph.pos();
      // The inward normal of the record's face of the box.
      const Vec3 p = ph.pos();
      const int axis = std::fabs(p.x) >= std::fabs(p.y) && std::fabs(p.x) >= std::fabs(p.z) ? 0
                       : std::fabs(p.y) >= std::fabs(p.z)                                   ? 1
                                                                                            : 2;
      r.n = Vec3(0.0f);
      (axis == 0   ? r.n.x
       : axis == 1 ? r.n.y
                   : r.n.z) = (axis == 0   ? p.x
                               : axis == 1 ? p.y
                                           : p.z) > 0
                                  ? -1.0f
                                  : 1.0f;
      r.radiance = Vec3(1.0f);
      records.push_back(r);
    }
    // Two record spacings: 24 m^2 / 250k records.
    return RadianceCache(std::move(records), 2.0f * std::sqrt(24.0f / 250000.0f));
  }();
  uint64_t i = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(cache.nearest(query_point(i++), Vec3(0, 0, 1), 0.5f));
  state.counters["queries/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RadianceCacheLookup);

// Photon tracing in the caustic box against bare Embree rays of the same lengths: photons per
// second and the fraction of the raw ray rate that tracing keeps.
struct TraceScene {
  TraceScene()
      : scene(make_caustic_box()),
        resources(scene, settings, &warnings),
        context(resources.context()),
        accel(resources.accel()) {}
  Scene scene;
  std::vector<std::string> warnings;
  RenderSettings settings;
  SceneResources resources;
  const RenderContext& context;
  const Accel& accel;
};

void BM_TracePhotons(benchmark::State& state) {
  static TraceScene t;
  const PhotonSources sources(t.context);
  PhotonTraceSettings ts;
  ts.global_photons = 200000;
  ts.caustic_photons = 0;
  PrepareControl control;
  uint64_t rays = 0, photons = 0;
  for (auto _ : state) {
    const PhotonTraceResult r = trace_photons(t.context, sources, ts, control);
    rays += r.rays;
    photons += r.global_emitted;
  }
  state.counters["photons/s"] =
      benchmark::Counter(static_cast<double>(photons), benchmark::Counter::kIsRate);
  state.counters["rays/s"] =
      benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_TracePhotons)->Unit(benchmark::kMillisecond)->UseRealTime();

// The same number of incoherent rays (random origins in the box, random directions), one
// rtcIntersect1 each, on all threads.
void BM_BareIncoherentRays(benchmark::State& state) {
  static TraceScene t;
  constexpr uint64_t kRays = 400000;
  uint64_t total = 0;
  for (auto _ : state) {
    tbb::parallel_for(tbb::blocked_range<uint64_t>(0, kRays, 2048), [&](const auto& r) {
      for (uint64_t i = r.begin(); i != r.end(); ++i) {
        const uint64_t h = mix64(i);
        Ray ray;
        ray.origin = Vec3(to_unit_float(h) * 1.8f - 0.9f, to_unit_float(h << 20) * 1.8f - 0.9f,
                          0.1f + to_unit_float(mix64(h)) * 1.8f);
        ray.direction =
            sample_uniform_sphere(Vec2(to_unit_float(mix64(h + 1)), to_unit_float(mix64(h + 2))));
        Hit hit;
        benchmark::DoNotOptimize(t.accel.intersect(ray, kVisibleAll, &hit));
      }
    });
    total += kRays;
  }
  state.counters["rays/s"] =
      benchmark::Counter(static_cast<double>(total), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_BareIncoherentRays)->Unit(benchmark::kMillisecond)->UseRealTime();

#ifdef PHOTON_HAVE_NANOFLANN
struct Cloud {
  const std::vector<Photon>* photons;
  size_t kdtree_get_point_count() const { return photons->size(); }
  float kdtree_get_pt(size_t i, size_t d) const { return (*photons)[i].position[d]; }
  template <class B>
  bool kdtree_get_bbox(B&) const {
    return false;
  }
};
using NanoTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Cloud>,
                                                     Cloud, 3, uint32_t>;

void BM_NanoflannBuild(benchmark::State& state) {
  const auto photons = box_photons(static_cast<size_t>(state.range(0)));
  Cloud cloud{&photons};
  for (auto _ : state) {
    NanoTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    benchmark::DoNotOptimize(&tree);
  }
}
BENCHMARK(BM_NanoflannBuild)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_NanoflannKNearest(benchmark::State& state) {
  static const auto photons = box_photons(1000000);
  static Cloud cloud{&photons};
  static NanoTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  const size_t k = static_cast<size_t>(state.range(0));
  std::vector<uint32_t> idx(k);
  std::vector<float> d2(k);
  uint64_t i = 0;
  for (auto _ : state) {
    const Vec3 q = query_point(i++);
    const float p[3] = {q.x, q.y, q.z};
    // nanoflann 1.4 has no radius limit on k-nearest queries: the full k are always found.
    tree.knnSearch(p, k, idx.data(), d2.data());
    benchmark::DoNotOptimize(idx.data());
  }
  state.counters["queries/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_NanoflannKNearest)->Arg(8)->Arg(50)->Arg(100);
#endif

}  // namespace
}  // namespace photon

BENCHMARK_MAIN();
