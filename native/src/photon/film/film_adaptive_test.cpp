// Adaptive sampling on the film: Cycles' per-pixel error measure, the 3 x 3 neighbourhood that
// keeps sampling round a noisy pixel, pixels resolved by their own sample count, and the
// thresholds and judging schedule Cycles derives from its settings.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "photon/film/film.h"
#include "photon/integrators/sampling_params.h"

namespace photon {
namespace film_adaptive_test {
namespace {

RadianceSample light(float v) {
  RadianceSample s;
  s.direct = Vec3(v);
  s.alpha = 1.0f;
  return s;
}

std::unique_ptr<Film> adaptive_film(int width, int height) {
  auto film = std::make_unique<Film>(film_frame(Camera{}, width, height, 0, 0, width, height),
                                     FilmOptions{});
  film->enable_adaptive_sampling();
  return film;
}

// Cycles' error of a pixel whose even samples are `even` and odd ones `odd`, n of each.
float cycles_error(float even, float odd, int n) {
  const float sum = 3.0f * n * (even + odd), a = 2.0f * 3.0f * n * even;
  const float samples = 2.0f * n;
  return std::fabs(sum - a) / samples / (1e-4f + std::sqrt(sum / samples));
}

TEST(FilmAdaptive, SteadyPixelsStopAndANoisyOneKeepsItsNeighboursOn) {
  std::unique_ptr<Film> owned = adaptive_film(7, 5);
  Film& film = *owned;
  const size_t noisy = film.index(2, 2);
  for (int k = 0; k < 16; ++k)
    for (size_t p = 0; p < film.pixel_count(); ++p)
      // The noisy pixel's even and odd samples differ by 20% of its mean: error 0.3 / sqrt(3).
      film.add_adaptive_sample(p, light(p == noisy ? (k % 2 ? 0.9f : 1.1f) : 0.25f), k);
  EXPECT_NEAR(cycles_error(1.1f, 0.9f, 8), 0.1732f, 1e-3f);
  EXPECT_EQ(film.update_convergence(0.05f), 9u);  // the noisy pixel and its 8 neighbours
  for (int row = 0; row < 5; ++row)
    for (int col = 0; col < 7; ++col)
      EXPECT_EQ(film.pixel_active(film.index(col, row)),
                std::abs(col - 2) <= 1 && std::abs(row - 2) <= 1)
          << col << "," << row;
  // Above its error the same pixel counts as converged.
  std::unique_ptr<Film> owned_lax = adaptive_film(7, 5);
  Film& lax = *owned_lax;
  for (int k = 0; k < 16; ++k)
    for (size_t p = 0; p < lax.pixel_count(); ++p)
      lax.add_adaptive_sample(p, light(p == noisy ? (k % 2 ? 0.9f : 1.1f) : 0.25f), k);
  EXPECT_EQ(lax.update_convergence(0.18f), 0u);
}

TEST(FilmAdaptive, PixelsResolveByTheirOwnSamples) {
  std::unique_ptr<Film> owned = adaptive_film(2, 1);
  Film& film = *owned;
  for (int k = 0; k < 8; ++k) film.add_adaptive_sample(0, light(0.5f), k);
  for (int k = 0; k < 24; ++k) film.add_adaptive_sample(1, light(2.0f), k);
  EXPECT_EQ(film.total_samples(), 32u);
  float rgba[8];
  film.resolve_rgba(FilmRect{0, 0, 2, 1}, 24, rgba);
  EXPECT_FLOAT_EQ(rgba[0], 0.5f);
  EXPECT_FLOAT_EQ(rgba[3], 1.0f);  // coverage by the pixel's own count too
  EXPECT_FLOAT_EQ(rgba[4], 2.0f);
  // A sample that is not finite counts as black, as without adaptive sampling.
  RadianceSample bad = light(0.0f);
  bad.direct.x = NAN;
  EXPECT_FALSE(film.add_adaptive_sample(0, bad, 8));
  film.resolve_rgba(FilmRect{0, 0, 2, 1}, 24, rgba);
  EXPECT_FLOAT_EQ(rgba[0], 0.5f * 8.0f / 9.0f);
}

// A neighbour that was judged converged but kept on is judged again, as Cycles clears its flag:
// once its noisy neighbour has settled, both stop.
TEST(FilmAdaptive, PixelsKeptOnAreJudgedAgain) {
  std::unique_ptr<Film> owned = adaptive_film(3, 1);
  Film& film = *owned;
  for (int k = 0; k < 16; ++k)
    for (size_t p = 0; p < 3; ++p) film.add_adaptive_sample(p, light(p == 0 ? k % 2 : 1.0f), k);
  EXPECT_EQ(film.update_convergence(0.05f), 2u);  // pixel 0 and its neighbour 1
  EXPECT_FALSE(film.pixel_active(2));
  for (int k = 16; k < 4096; ++k)
    for (size_t p = 0; p < 2; ++p) film.add_adaptive_sample(p, light(p == 0 ? 0.5f : 1.0f), k);
  EXPECT_EQ(film.update_convergence(0.05f), 0u);
}

TEST(FilmAdaptive, ThresholdsAndScheduleAsCyclesDerivesThem) {
  SamplingParams p;
  p.samples = 512;
  EXPECT_EQ(adaptive_sampling(p).threshold, 0.0f);  // off
  p.adaptive_sampling = true;
  p.adaptive_threshold = 0.01f;
  AdaptiveSampling a = adaptive_sampling(p);
  EXPECT_FLOAT_EQ(a.threshold, 0.05f);
  EXPECT_EQ(a.min_samples, 64);
  // Judged after sample s (0-based) with s > 64 and s + 1 a multiple of 16: 80, 96, ...
  EXPECT_EQ(a.next_check(0), 80);
  EXPECT_EQ(a.next_check(79), 80);
  EXPECT_EQ(a.next_check(80), 96);
  p.adaptive_threshold = 0.1f;
  EXPECT_EQ(adaptive_sampling(p).min_samples, 32);
  p.adaptive_threshold = 0.0f;  // automatic: max(0.001, 1 / samples)
  a = adaptive_sampling(p);
  EXPECT_FLOAT_EQ(a.threshold, 5.0f / 512.0f);
  EXPECT_EQ(a.min_samples, static_cast<int>(std::ceil(16.0f / std::pow(1.0f / 512.0f, 0.3f))));
  p.adaptive_min_samples = 2;  // at least 4
  EXPECT_EQ(adaptive_sampling(p).min_samples, 4);
  EXPECT_EQ(adaptive_sampling(p).next_check(0), 16);
}

}  // namespace
}  // namespace film_adaptive_test
}  // namespace photon
