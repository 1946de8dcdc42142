// Spectral rendering's costs: per path vertex, the RGB -> spectrum uplift (blend of the table's
// node sigmoids), evaluating it at the N = 4 hero wavelengths and the XYZ estimate of 4 samples;
// per render, the time of a camera sample spectral vs RGB and the noise at equal time (the
// Cornell box and the caustic box, photon mapping).
// Run: build/spectral_bench  (renders only: --benchmark_filter=Render)
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "photon/session/render_session.h"
#include "photon/spectral/colorimetry.h"
#include "photon/spectral/rgb_uplift.h"
#include "photon/testing/test_scenes.h"

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

constexpr int kSize = 128;

struct Rendered {
  std::vector<float> rgba;
  double render_seconds = 0.0;   // the pixels, after the photon maps
  double prepare_seconds = 0.0;  // photon maps and irradiance cache
};

Rendered render(const Scene& scene, bool spectral, uint64_t seed, int spp) {
  RenderSettings s;
  s.full_width = s.full_height = s.x1 = s.y1 = kSize;
  s.samples = spp;
  s.seed = seed;
  s.spectral = spectral;
  s.photons = 100000;
  s.caustic_photons = 100000;
  RenderSession session(std::make_shared<Scene>(scene), s);
  session.start();
  session.wait();
  const RenderStats stats = session.stats();
  return {session.image(), stats.render_seconds, stats.prepare_seconds};
}

// Per-pixel noise of one render: the RMS difference of two renders of different seeds / sqrt 2.
double noise(const std::vector<float>& a, const std::vector<float>& b) {
  double sq = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    if (i % 4 == 3) continue;
    sq += (a[i] - b[i]) * (a[i] - b[i]);
    ++n;
  }
  return std::sqrt(sq / n / 2.0);
}

// Arg 0: the Cornell box; 1: the caustic box with a glass ball of Abbe number 30.
void BM_RenderSpectralVsRgb(benchmark::State& state) {
  Scene scene = state.range(0) == 0 ? make_cornell_box() : make_caustic_box();
  if (state.range(0) == 1) scene.materials[3].closures[0].abbe = 30.0f;
  constexpr int kSpp = 16;
  Rendered rgb_a, rgb_b, spec_a, spec_b;
  for (auto _ : state) {
    rgb_a = render(scene, false, 1, kSpp);
    rgb_b = render(scene, false, 2, kSpp);
    spec_a = render(scene, true, 1, kSpp);
    spec_b = render(scene, true, 2, kSpp);
  }
  const double samples = static_cast<double>(kSize) * kSize * kSpp;
  const double t_rgb = 0.5 * (rgb_a.render_seconds + rgb_b.render_seconds) / samples;
  const double t_spec = 0.5 * (spec_a.render_seconds + spec_b.render_seconds) / samples;
  const double n_rgb = noise(rgb_a.rgba, rgb_b.rgba), n_spec = noise(spec_a.rgba, spec_b.rgba);
  state.counters["rgb_us_per_sample"] = 1e6 * t_rgb;
  state.counters["spectral_us_per_sample"] = 1e6 * t_spec;
  state.counters["time_ratio"] = t_spec / t_rgb;
  state.counters["rgb_prepare_s"] = 0.5 * (rgb_a.prepare_seconds + rgb_b.prepare_seconds);
  state.counters["spectral_prepare_s"] = 0.5 * (spec_a.prepare_seconds + spec_b.prepare_seconds);
  state.counters["rgb_noise"] = n_rgb;
  state.counters["spectral_noise"] = n_spec;
  // Noise falls as 1 / sqrt(samples): spectral's at the samples RGB renders in the same time.
  state.counters["spectral_noise_equal_time"] = n_spec * std::sqrt(t_spec / t_rgb);
}
BENCHMARK(BM_RenderSpectralVsRgb)->Arg(0)->Arg(1)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
