// RenderSession's render of an iterative integrator (integrator_capabilities: iterative), SPPM
// or VCM: instead of tiles rendered once, the whole region is refined by iterations
// (integrators/sppm/sppm_renderer.h, integrators/vcm/vcm_renderer.h), and the image after a
// complete iteration is handed over as one tile of the whole region, which the add-on writes over
// the last one: the render refines in place. Iterations stop at sppm_iterations, after the
// iteration that passes sppm_time, or on cancel; the tile of the last complete iteration is always
// handed over. The data passes are rendered once, before the first iteration, and every tile
// carries them.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <string>
#include <vector>

#include "photon/integrators/vcm/vcm_renderer.h"
#include "photon/session/data_passes.h"
#include "photon/session/pixel_renderer.h"
#include "photon/session/render_session.h"

namespace photon {
namespace {

using Clock = std::chrono::steady_clock;
// Between two images handed to Blender: writing a large frame's passes takes a while, and short
// iterations would spend their time there.
constexpr double kPublishSeconds = 1.0;
constexpr size_t kProgressSteps = 1000;

}  // namespace

void RenderSession::run_iterative(const RenderContext& context, tbb::task_arena& arena) {
  const std::atomic<bool>& cancel = cancel_flag();
  const int total = settings_.sppm_iterations;
  const double time_limit = settings_.sppm_time;
  const int w = region_width(), h = region_height();
  const size_t pixels = static_cast<size_t>(w) * h;
  const int data_floats = data_pass_pixel_floats(settings_.data_passes);
  const bool vcm = settings_.integrator == IntegratorType::kVcm;
  if (vcm && settings_.light_passes)
    add_warning("light passes are not rendered by the VCM integrator yet: they are left at zero");
  set_work_total(kProgressSteps);
  const auto t0 = Clock::now();

  // The data passes do not change from iteration to iteration: they are rendered once, from the
  // camera rays of the Sampling panel's samples, as the tiled integrators render them.
  std::vector<float> data(pixels * data_floats);
  if (data_floats) {
    set_status("Data passes");
    std::atomic<bool> complete{true};
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<int>(0, h, 4), [&](const tbb::blocked_range<int>& rows) {
        float* out = data.data() + static_cast<size_t>(rows.begin()) * w * data_floats;
        if (!render_data_passes(context, settings_.x0, settings_.y0 + rows.begin(), w,
                                static_cast<int>(rows.size()), out, cancel))
          complete = false;
      });
    });
    if (!complete) return;  // cancelled before any image: Blender keeps the preview
  }

  std::unique_ptr<IterativeRenderer> sppm;
  std::vector<std::string> warnings;
  if (vcm && !VcmRenderer::supports_camera(context)) {
    add_warning(
        "the VCM integrator renders pinhole perspective cameras only (no orthographic camera, "
        "no depth of field): rendering with SPPM instead");
    warnings.clear();
  }
  arena.execute([&] {
    if (vcm && VcmRenderer::supports_camera(context))
      sppm = std::make_unique<VcmRenderer>(context, &warnings);
    else
      sppm = std::make_unique<SppmRenderer>(context, &warnings);
  });
  add_warnings(warnings);
  Tile latest;  // the image of the last complete iteration
  bool latest_published = true;
  auto last_publish = t0;
  const auto publish = [&] {
    {
      // An image not yet taken is superseded: at most one waits, whatever the poller's pace.
      std::lock_guard<std::mutex> lock(mutex_);
      queue_.clear();
    }
    deliver_tile(latest);
    latest_published = true;
    last_publish = Clock::now();
  };

  while (sppm->iterations() < total && !cancel) {
    const double elapsed = std::chrono::duration<double>(Clock::now() - t0).count();
    if (time_limit > 0.0 && elapsed >= time_limit) break;
    set_status("Iteration " + std::to_string(sppm->iterations() + 1) + " / " +
               std::to_string(total));
    bool complete = false;
    arena.execute([&] { complete = sppm->iterate(cancel); });
    if (!complete) break;

    latest = Tile{0, 0, w, h, {}, {}, {}};
    latest.rgba.resize(pixels * 4);
    if (settings_.light_passes) latest.passes.resize(pixels * kPassFloats);
    latest.data = data;
    sppm->write_image(latest.rgba.data(), settings_.light_passes ? latest.passes.data() : nullptr);
    latest_published = false;

    const double now = std::chrono::duration<double>(Clock::now() - t0).count();
    double fraction = static_cast<double>(sppm->iterations()) / total;
    if (time_limit > 0.0) fraction = std::max(fraction, now / time_limit);
    work_done() = static_cast<size_t>(std::min(fraction, 1.0) * kProgressSteps);
    const bool last = sppm->iterations() >= total || (time_limit > 0.0 && now >= time_limit);
    const bool first = sppm->iterations() == 1;
    if (first || last ||
        std::chrono::duration<double>(Clock::now() - last_publish).count() >= kPublishSeconds)
      publish();
  }
  if (!latest_published) publish();

  std::lock_guard<std::mutex> lock(mutex_);
  stats_.render_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  stats_.sppm = sppm->stats();
  stats_.camera_samples = static_cast<uint64_t>(pixels) * sppm->iterations();
  stats_.non_finite_samples += sppm->stats().non_finite;
}

}  // namespace photon
