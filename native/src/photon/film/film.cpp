#include "photon/film/film.h"

#include <algorithm>

#include "photon/base/check.h"

namespace photon {
namespace {

// Whether `rect` lies inside a film of width x height pixels: a caller's bug otherwise, which
// would read past the sums.
void check_inside(const FilmRect& rect, int width, int height) {
  CHECK(rect.x >= 0 && rect.y >= 0 && rect.width >= 0 && rect.height >= 0);
  CHECK(rect.x + rect.width <= width && rect.y + rect.height <= height);
}

}  // namespace

FilmFrame film_frame(const Camera& camera, int full_width, int full_height, int x0, int y0, int x1,
                     int y1, int step) {
  FilmFrame f;
  f.camera = camera;
  f.full_width = full_width;
  f.full_height = full_height;
  f.x0 = x0;
  f.y0 = y0;
  f.x1 = x1;
  f.y1 = y1;
  f.step = std::max(step, 1);
  return f;
}

Film::Film(const FilmFrame& frame, const FilmOptions& options)
    : frame_(frame), options_(options), filter_(options.filter_type, options.filter_width) {
  frame_.step = std::max(frame_.step, 1);
  width_ = std::max(0, (frame_.x1 - frame_.x0 + frame_.step - 1) / frame_.step);
  height_ = std::max(0, (frame_.y1 - frame_.y0 + frame_.step - 1) / frame_.step);
  data_floats_ = data_pass_pixel_floats(options_.data_passes);
  sums_.assign(pixel_count() * 4, 0.0f);
  if (options_.light_passes) pass_sums_.assign(pixel_count() * kPassCount, Vec3(0.0f));
  data_.assign(pixel_count() * data_floats_, 0.0f);
}

float Film::coverage(float alpha, float holdout) const {
  const float c = options_.transparent_background ? alpha : 1.0f;
  return holdout > 0.0f ? std::max(c - holdout, 0.0f) : c;
}

bool Film::add_sample(size_t pixel, const RadianceSample& sample) {
  DCHECK_LT(pixel, pixel_count());
  const Vec3 radiance = sample.radiance();
  if (!is_finite(radiance) || !is_finite(sample.photon_map)) {
    count_non_finite(1);
    return false;
  }
  float* s = &sums_[4 * pixel];
  s[0] += radiance.x;
  s[1] += radiance.y;
  s[2] += radiance.z;
  s[3] += coverage(sample.alpha, sample.holdout);
  if (!pass_sums_.empty()) {
    Vec3* p = &pass_sums_[pixel * kPassCount];
    p[0] += sample.direct;
    p[1] += sample.indirect;
    p[2] += sample.caustic;
    p[3] += sample.photon_map;
  }
  return true;
}

bool Film::add_light(size_t pixel, const Vec3& radiance, float coverage) {
  DCHECK_LT(pixel, pixel_count());
  if (!is_finite(radiance)) {
    count_non_finite(1);
    return false;
  }
  float* s = &sums_[4 * pixel];
  s[0] += radiance.x;
  s[1] += radiance.y;
  s[2] += radiance.z;
  s[3] += coverage;
  return true;
}

void Film::set_sums(size_t pixel, const Vec3& light, float coverage, const Vec3* light_passes) {
  DCHECK_LT(pixel, pixel_count());
  float* s = &sums_[4 * pixel];
  s[0] = light.x;
  s[1] = light.y;
  s[2] = light.z;
  s[3] = coverage;
  if (!pass_sums_.empty()) {
    Vec3* p = &pass_sums_[pixel * kPassCount];
    for (int k = 0; k < kPassCount; ++k) p[k] = light_passes ? light_passes[k] : Vec3(0.0f);
  }
}

void Film::clear() {
  std::fill(sums_.begin(), sums_.end(), 0.0f);
  std::fill(pass_sums_.begin(), pass_sums_.end(), Vec3(0.0f));
  std::fill(data_.begin(), data_.end(), 0.0f);
  std::fill(pixel_samples_.begin(), pixel_samples_.end(), 0u);
  std::fill(even_sums_.begin(), even_sums_.end(), Vec3(0.0f));
  std::fill(converged_.begin(), converged_.end(), uint8_t{0});
  std::fill(active_.begin(), active_.end(), uint8_t{1});
  non_finite_ = 0;
}

float gamut_blend(const Vec3& c) {
  const float lowest = std::min(c.x, std::min(c.y, c.z));
  if (lowest >= 0.0f) return 1.0f;
  const float y = luminance(c);
  if (!(y > 0.0f)) return 0.0f;
  return y / (y - lowest);
}

float Film::pixel_gamut_blend(size_t pixel, float colour_scale) const {
  if (!options_.into_gamut) return 1.0f;
  const float* s = &sums_[4 * pixel];
  return gamut_blend(Vec3(finite_average(s[0], colour_scale), finite_average(s[1], colour_scale),
                          finite_average(s[2], colour_scale)));
}

Vec3 Film::resolved_colour(const Vec3& sum, float colour_scale, float blend) const {
  const Vec3 c(finite_average(sum.x, colour_scale), finite_average(sum.y, colour_scale),
               finite_average(sum.z, colour_scale));
  if (blend == 1.0f) return c;
  // The clamp takes rounding's last bits, a pixel whose luminance is not positive (noise about
  // black) to black, and a pass more saturated than its pixel into the gamut.
  return max(blend_towards_grey(c, blend), Vec3(0.0f));
}

void Film::resolve_rgba(const FilmRect& rect, int samples, float* rgba) const {
  check_inside(rect, width_, height_);
  for (int row = 0; row < rect.height; ++row)
    for (int col = 0; col < rect.width; ++col) {
      const size_t pixel = index(rect.x + col, rect.y + row);
      const float inv_spp = inv_samples(pixel, samples);
      const float colour_scale = inv_spp * options_.exposure;  // the exposure scales colour only
      const float* s = &sums_[4 * pixel];
      float* out = rgba + (static_cast<size_t>(row) * rect.width + col) * 4;
      const Vec3 c = resolved_colour(Vec3(s[0], s[1], s[2]), colour_scale,
                                     pixel_gamut_blend(pixel, colour_scale));
      out[0] = c.x;
      out[1] = c.y;
      out[2] = c.z;
      out[3] = s[3] * inv_spp;
    }
}

std::vector<PassImage> Film::resolve_passes(const FilmRect& rect, int samples) const {
  check_inside(rect, width_, height_);
  std::vector<PassImage> out;
  const size_t pixels = static_cast<size_t>(rect.width) * rect.height;
  if (!pass_sums_.empty()) {
    for (int k = 0; k < kPassCount; ++k) {
      PassImage pass{light_pass_names()[k], 3, "RGB", std::vector<float>(pixels * 3)};
      for (int row = 0; row < rect.height; ++row)
        for (int col = 0; col < rect.width; ++col) {
          const size_t pixel = index(rect.x + col, rect.y + row);
          const float colour_scale = inv_samples(pixel, samples) * options_.exposure;
          const Vec3 c = resolved_colour(pass_sums_[pixel * kPassCount + k], colour_scale,
                                         pixel_gamut_blend(pixel, colour_scale));
          float* p = &pass.pixels[(static_cast<size_t>(row) * rect.width + col) * 3];
          p[0] = c.x;
          p[1] = c.y;
          p[2] = c.z;
        }
      out.push_back(std::move(pass));
    }
  }
  for (const DataPassSlot& slot : data_pass_slots(options_.data_passes)) {
    PassImage pass{slot.name, slot.channels, slot.channel_ids,
                   std::vector<float>(pixels * slot.channels)};
    for (int row = 0; row < rect.height; ++row)
      for (int col = 0; col < rect.width; ++col) {
        const float* src = &data_[index(rect.x + col, rect.y + row) * data_floats_ + slot.offset];
        std::copy(src, src + slot.channels,
                  &pass.pixels[(static_cast<size_t>(row) * rect.width + col) * slot.channels]);
      }
    out.push_back(std::move(pass));
  }
  return out;
}

}  // namespace photon
