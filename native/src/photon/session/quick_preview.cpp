#include "photon/session/quick_preview.h"

#include <algorithm>
#include <cmath>

#include "photon/integrators/ray_trace/ray_trace_integrator.h"

namespace photon {

int preview_block_size(int width, int height) {
  const double pixels = static_cast<double>(std::max(width, 1)) * std::max(height, 1);
  return std::max(
      1, static_cast<int>(std::ceil(std::sqrt(pixels * kPreviewSamples / kPreviewSampleBudget))));
}

std::vector<float> render_quick_preview(const RenderContext& context,
                                        const std::atomic<bool>& cancel) {
  const RenderSettings& full = *context.settings;
  const int width = full.x1 - full.x0, height = full.y1 - full.y0;
  const int block = preview_block_size(width, height);

  // A frame `block` times smaller in each direction sees the same camera: camera rays are made
  // from coordinates normalised by the frame size, so each of its pixels covers one block.
  RenderSettings coarse = full;
  coarse.full_width = (full.full_width + block - 1) / block;
  coarse.full_height = (full.full_height + block - 1) / block;
  coarse.samples = kPreviewSamples;
  coarse.filter_width = 1.0f;  // samples spread over the block
  coarse.light_passes = false;
  coarse.data_passes = DataPassSettings{};
  RenderContext coarse_context = context;
  coarse_context.settings = &coarse;

  const int cx0 = full.x0 / block, cy0 = full.y0 / block;
  const int cx1 = (full.x1 + block - 1) / block, cy1 = (full.y1 + block - 1) / block;
  const int cw = cx1 - cx0, ch = cy1 - cy0;
  Film film(
      film_frame(context.scene->camera, coarse.full_width, coarse.full_height, cx0, cy0, cx1, cy1),
      film_options(coarse));
  RayTraceIntegrator integrator;
  RenderControl control;
  control.end_pass = kPreviewSamples;
  control.cancel = &cancel;
  control.tile_size = coarse.tile_size;
  if (integrator.render(coarse_context, film, control) < kPreviewSamples || cancel) return {};
  std::vector<float> small(static_cast<size_t>(cw) * ch * 4, 0.0f);
  film.resolve_rgba(FilmRect{0, 0, cw, ch}, kPreviewSamples, small.data());

  std::vector<float> image(static_cast<size_t>(width) * height * 4);
  for (int y = 0; y < height; ++y) {
    const int sy = std::min((full.y0 + y) / block - cy0, ch - 1);
    for (int x = 0; x < width; ++x) {
      const int sx = std::min((full.x0 + x) / block - cx0, cw - 1);
      const float* src = &small[(static_cast<size_t>(sy) * cw + sx) * 4];
      std::copy(src, src + 4, &image[(static_cast<size_t>(y) * width + x) * 4]);
    }
  }
  return image;
}

}  // namespace photon
