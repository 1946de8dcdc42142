#include "photon/integrators/pixel_integrator.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <memory>
#include <vector>

#include "photon/base/check.h"
#include "photon/integrators/data_passes.h"

namespace photon {
namespace {

// One tile's rows, sample after sample: the camera rays of a row and their first hits.
class TileTracer {
 public:
  // The pixels' samples are stratified over [block_first, block_first + count).
  TileTracer(const RenderContext& context, Film& film, size_t width, uint32_t count,
             uint32_t block_first)
      : context_(context),
        film_(film),
        count_(count),
        block_first_(block_first),
        samplers_(width, Sampler(0, 0, 0)),
        rays_(width),
        hits_(width),
        found_(new bool[width]) {}

  // Sample k of the film pixels `cols[0..n)` of `row`: each pixel's sampler (its stream depends
  // on the pixel's place in the whole frame only), its camera ray, traced with the row's others
  // as one coherent Embree stream, and the first hit.
  void trace(const int* cols, int row, int k, size_t n) {
    const RenderSettings& s = *context_.settings;
    for (size_t i = 0; i < n; ++i) {
      samplers_[i] = Sampler(s.seed, film_.frame_pixel(cols[i], row), static_cast<uint32_t>(k),
                             count_, block_first_);
      rays_[i] = film_.camera_ray(film_.frame_x(cols[i]), film_.frame_y(row), samplers_[i]);
    }
    context_.accel->intersect_coherent(rays_.data(), n, kVisibleCamera, hits_.data(), found_.get());
  }
  CameraHit first_hit(size_t i) const {
    CameraHit first;
    first.found = found_[i];
    if (first.found) first.hit = hits_[i];
    return first;
  }
  const Ray& ray(size_t i) const { return rays_[i]; }
  Sampler& sampler(size_t i) { return samplers_[i]; }

 private:
  const RenderContext& context_;
  Film& film_;
  uint32_t count_, block_first_;
  std::vector<Sampler> samplers_;
  std::vector<Ray> rays_;
  std::vector<Hit> hits_;
  std::unique_ptr<bool[]> found_;
};

// Renders passes [first, end) of the film pixels of `rect` with `integrator` (null: data passes
// only) and returns how many of its rows are finished (fewer than its height when stopped).
int render_tile(const RenderContext& context, const PixelIntegrator* integrator, Film& film,
                const FilmRect& rect, int first, int end, const RenderControl& control) {
  const size_t n = static_cast<size_t>(rect.width);
  // Data passes need every sample of a pixel in one go (their first sample decides Depth).
  const int samples = context.settings->samples;
  const bool block = integrator && control.stratify_each_call;
  TileTracer tracer(context, film, n, static_cast<uint32_t>(block ? end - first : samples),
                    static_cast<uint32_t>(block ? first : 0));
  // An adaptive film's pixels leave the loop as they converge; its data passes are rendered
  // apart, for the samples the render reached.
  const bool adaptive = integrator && film.adaptive();
  const bool data = film.data_floats() > 0 && first == 0 && end >= samples && !adaptive;
  std::unique_ptr<DataPassRow> data_row;
  if (data) data_row = std::make_unique<DataPassRow>(context, film.options().data_passes, n);
  std::vector<float> data_out(data ? n * film.data_floats() : 0);
  const int sample_end = integrator ? end : samples;
  std::vector<int> cols(n);
  for (int r = 0; r < rect.height; ++r) {
    const int row = rect.y + r;
    if (data_row) data_row->clear();
    size_t m = 0;
    for (size_t i = 0; i < n; ++i) {
      const int col = rect.x + static_cast<int>(i);
      if (!adaptive || film.pixel_active(film.index(col, row))) cols[m++] = col;
    }
    for (int k = first; k < sample_end && m > 0; ++k) {
      if (control.stopped()) return r;
      tracer.trace(cols.data(), row, k, m);
      for (size_t i = 0; i < m; ++i) {
        const int col = cols[i];
        const CameraHit hit = tracer.first_hit(i);
        if (data_row) data_row->add(i, k, film.frame_pixel(col, row), tracer.ray(i), hit);
        if (!integrator) continue;
        const RadianceSample sample =
            integrator->radiance_from_hit(context, tracer.ray(i), hit, tracer.sampler(i));
        if (adaptive)
          film.add_adaptive_sample(film.index(col, row), sample, k);
        else
          film.add_sample(film.index(col, row), sample);
      }
    }
    if (data_row) {
      data_row->finish(samples, data_out.data());
      std::copy(data_out.begin(), data_out.end(),
                film.data_row(row) + static_cast<size_t>(rect.x) * film.data_floats());
    }
  }
  return rect.height;
}

// The tiles of the film in reading order, handed out from a shared counter so they finish
// roughly top to bottom (Blender's image editor fills that way); which thread renders a tile
// does not change its pixels. False when stopped.
bool render_tiles(const RenderContext& context, const PixelIntegrator* integrator, Film& film,
                  const RenderControl& control) {
  const int ts = std::max(control.tile_size, 1);
  const int tiles_x = (film.width() + ts - 1) / ts;
  const int tiles_y = (film.height() + ts - 1) / ts;
  const size_t tile_count = static_cast<size_t>(tiles_x) * tiles_y;
  const int first = control.first_pass, end = control.end_pass;
  std::atomic<size_t> next_tile{0}, tiles_done{0};
  std::atomic<bool> stopped{false};
  const int workers = std::max(1, tbb::this_task_arena::max_concurrency());
  tbb::parallel_for(0, workers, [&](int) {
    for (size_t t = next_tile++; t < tile_count && !stopped; t = next_tile++) {
      FilmRect rect;
      rect.x = static_cast<int>(t % tiles_x) * ts;
      rect.y = static_cast<int>(t / tiles_x) * ts;
      rect.width = std::min(ts, film.width() - rect.x);
      rect.height = std::min(ts, film.height() - rect.y);
      const int rows = render_tile(context, integrator, film, rect, first, end, control);
      if (rows < rect.height) {
        stopped = true;
        // The finished rows are kept: their samples are complete.
        rect.height = rows;
        if (rows > 0 && control.update) control.update(rect, end, false);
        return;
      }
      if (control.update) control.update(rect, end, false);
      const size_t done = ++tiles_done;
      if (control.progress) control.progress(static_cast<float>(done) / tile_count);
    }
  });
  return !stopped && !control.stopped();
}

}  // namespace

int PixelIntegrator::render(const RenderContext& context, Film& film,
                            const RenderControl& control) {
  CHECK_LE(control.first_pass, control.end_pass);
  if (control.first_pass == 0) film.clear();
  return render_tiles(context, this, film, control) ? control.end_pass : control.first_pass;
}

bool render_data_passes(const RenderContext& context, Film& film, const RenderControl& control) {
  if (film.data_floats() == 0) return true;
  RenderControl data = control;
  data.first_pass = 0;
  data.end_pass = context.settings->samples;
  data.update = nullptr;
  data.progress = nullptr;
  return render_tiles(context, nullptr, film, data);
}

}  // namespace photon
