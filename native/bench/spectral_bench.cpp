// Spectral foundation costs per path vertex: RGB -> spectrum uplift (blend of the table's node
// sigmoids), evaluating it at the N = 4 hero wavelengths, and the XYZ estimate of 4 samples.
// Run: build/spectral_bench
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "photon/spectral/colorimetry.h"
#include "photon/spectral/rgb_uplift.h"

using namespace photon;
using namespace photon::spectral;

namespace {

std::vector<Vec3> random_colours() {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Vec3> c(4096);
  for (auto& v : c) v = Vec3(u(rng), u(rng), u(rng));
  return c;
}

std::vector<SampledWavelengths> random_wavelengths() {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<SampledWavelengths> w;
  for (int i = 0; i < 4096; ++i) w.push_back(SampledWavelengths::sample_visible(u(rng)));
  return w;
}

void BM_UpliftLookup(benchmark::State& state) {
  const auto& table = RgbToSpectrumTable::rec709();
  const auto colours = random_colours();
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(table(colours[i++ & 4095]));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_UpliftLookup);

void BM_UpliftAndSample4(benchmark::State& state) {
  const auto& table = RgbToSpectrumTable::rec709();
  const auto colours = random_colours();
  const auto wls = random_wavelengths();
  size_t i = 0;
  for (auto _ : state) {
    const RgbAlbedoSpectrum s(table, colours[i & 4095]);
    benchmark::DoNotOptimize(s.sample(wls[i & 4095]));
    ++i;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_UpliftAndSample4);

// The single-sigmoid evaluation the blend replaces (Jakob & Hanika's interpolated
// coefficients): the cost floor of an uplift lookup + 4 evaluations.
void BM_OneSigmoidSample4(benchmark::State& state) {
  const auto wls = random_wavelengths();
  const SigmoidPolynomial p{12.0f, -7.0f, 0.4f};
  size_t i = 0;
  for (auto _ : state) {
    const auto& wl = wls[i++ & 4095];
    SampledSpectrum s;
    for (int k = 0; k < kSpectrumSamples; ++k) s[k] = p(wl.lambda(k));
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_OneSigmoidSample4);

void BM_UpliftSample4AndXyz(benchmark::State& state) {
  const auto& table = RgbToSpectrumTable::rec709();
  const auto colours = random_colours();
  const auto wls = random_wavelengths();
  size_t i = 0;
  for (auto _ : state) {
    const auto& wl = wls[i & 4095];
    const RgbAlbedoSpectrum s(table, colours[i & 4095]);
    benchmark::DoNotOptimize(sampled_to_xyz(s.sample(wl), wl));
    ++i;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_UpliftSample4AndXyz);

void BM_SampleWavelengths(benchmark::State& state) {
  const bool visible = state.range(0) != 0;
  float u = 0.0f;
  for (auto _ : state) {
    u += 0.6180339f;
    if (u >= 1.0f) u -= 1.0f;
    benchmark::DoNotOptimize(visible ? SampledWavelengths::sample_visible(u)
                                     : SampledWavelengths::sample_uniform(u));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SampleWavelengths)->Arg(0)->Arg(1);

}  // namespace

BENCHMARK_MAIN();
