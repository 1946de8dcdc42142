#include "photon/testing/progressive_checkpoints.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>

#include "photon/integrators/registry.h"
#include "photon/session/scene_resources.h"

namespace photon {

std::vector<Checkpoint> render_checkpoints(const Scene& scene, const RenderSettings& settings,
                                           const std::vector<int>& iterations) {
  const auto t0 = std::chrono::steady_clock::now();
  RenderSettings s = settings;
  s.x0 = s.y0 = 0;
  s.x1 = s.full_width;
  s.y1 = s.full_height;
  const int last = iterations.empty() ? 0 : *std::max_element(iterations.begin(), iterations.end());
  // The samplers stratify over the render's iteration count, as the session sets it.
  s.sppm_iterations = last;
  s.vcm_iterations = last;
  const SceneResources resources(scene, s, nullptr);
  const RenderContext& context = resources.context();
  const std::unique_ptr<Integrator> integrator = make_integrator(s.integrator);
  integrator->prepare(context, PrepareControl{});
  Film film(
      film_frame(scene.camera, s.full_width, s.full_height, 0, 0, s.full_width, s.full_height),
      film_options(s));
  const std::atomic<bool> cancel{false};
  std::vector<Checkpoint> out;
  RenderControl control;
  control.end_pass = last;
  control.cancel = &cancel;
  control.update = [&](const FilmRect& rect, int k, bool) {
    if (std::find(iterations.begin(), iterations.end(), k) == iterations.end()) return;
    Checkpoint c;
    c.iterations = k;
    c.rgba.resize(static_cast<size_t>(s.full_width) * s.full_height * 4);
    film.resolve_rgba(rect, k, c.rgba.data());
    c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    out.push_back(std::move(c));
  };
  integrator->render(context, film, control);
  return out;
}

Rgb rgb_of(const std::vector<float>& rgba, int width, int height) {
  Rgb out{width, height, {}};
  const size_t pixels = std::min(static_cast<size_t>(width) * height, rgba.size() / 4);
  out.rgb.reserve(pixels * 3);
  for (size_t p = 0; p < pixels; ++p)
    out.rgb.insert(out.rgb.end(), {rgba[4 * p], rgba[4 * p + 1], rgba[4 * p + 2]});
  return out;
}

Rgb downsample(const Rgb& image, int factor) {
  Rgb out{image.width / factor, image.height / factor, {}};
  out.rgb.assign(static_cast<size_t>(out.width) * out.height * 3, 0.0f);
  const float scale = 1.0f / static_cast<float>(factor * factor);
  for (int y = 0; y < out.height * factor; ++y)
    for (int x = 0; x < out.width * factor; ++x)
      for (int c = 0; c < 3; ++c)
        out.rgb[(static_cast<size_t>(y / factor) * out.width + x / factor) * 3 + c] +=
            image.rgb[(static_cast<size_t>(y) * image.width + x) * 3 + c] * scale;
  return out;
}

double mean_value(const Rgb& image) {
  double sum = 0.0;
  for (float v : image.rgb) sum += v;
  return image.rgb.empty() ? 0.0 : sum / static_cast<double>(image.rgb.size());
}

double relative_rmse(const Rgb& a, const Rgb& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.rgb.size() && i < b.rgb.size(); ++i) {
    const double d = static_cast<double>(a.rgb[i]) - b.rgb[i];
    sum += d * d;
  }
  return std::sqrt(sum / static_cast<double>(std::max<size_t>(b.rgb.size(), 1))) / mean_value(b);
}

double relative_mae(const Rgb& a, const Rgb& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.rgb.size() && i < b.rgb.size(); ++i)
    sum += std::fabs(static_cast<double>(a.rgb[i]) - b.rgb[i]);
  return sum / static_cast<double>(std::max<size_t>(b.rgb.size(), 1)) / mean_value(b);
}

double relative_mean_difference(const Rgb& a, const Rgb& b) {
  return mean_value(a) / mean_value(b) - 1.0;
}

}  // namespace photon
