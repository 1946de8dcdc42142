#include "photon/lights/environment.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "photon/base/sampling.h"
#include "photon/lights/photon_aim.h"
#include "photon/lights/world_light.h"

namespace photon {
namespace {

constexpr double kTwoPiD = 6.28318530717958647692;

// Negative, NaN and infinite channels (a broken node tree) count as 0: they would poison the
// table and every estimate that meets them.
Vec3 sanitized(const Vec3& v) {
  auto ok = [](float c) { return std::isfinite(c) && c > 0.0f ? c : 0.0f; };
  return {ok(v.x), ok(v.y), ok(v.z)};
}

Vec3 direction_at(double z, double phi) {
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {static_cast<float>(sin_theta * std::cos(phi)),
          static_cast<float>(sin_theta * std::sin(phi)), static_cast<float>(z)};
}

}  // namespace

EnvironmentEmitter::EnvironmentEmitter(EnvironmentFunction radiance, int width, int subsamples,
                                       const std::atomic<bool>* cancel)
    : radiance_(std::move(radiance)) {
  width_ = clamped_width(width);
  height_ = width_ / 2;
  const int k = std::clamp(subsamples, 1, 8);
  z_edge_.resize(static_cast<size_t>(height_) + 1);
  for (int i = 0; i <= height_; ++i) z_edge_[i] = std::cos(kTwoPiD * 0.5 * i / height_);
  z_edge_.front() = 1.0;
  z_edge_.back() = -1.0;

  value_.assign(static_cast<size_t>(width_) * height_, 0.0f);
  columns_.resize(height_);
  std::vector<double> row_value(height_, 0.0);
  std::vector<Vec3> row_color(height_, Vec3(0.0f));
  if (radiance_) {
    // The world's mean channel value at each texel's (sub)sample points.
    std::vector<float> centre(value_.size(), 0.0f);
    // Whether each row's evaluations all equal its first one, and that one.
    std::vector<uint8_t> row_flat(height_, 0);
    std::vector<Vec3> row_first(height_, Vec3(0.0f));
    tbb::parallel_for(
        tbb::blocked_range<int>(0, height_, 1), [&](const tbb::blocked_range<int>& r) {
          for (int i = r.begin(); i != r.end(); ++i) {
            if (cancel && cancel->load(std::memory_order_relaxed)) return;
            double red = 0.0, green = 0.0, blue = 0.0;
            bool flat = true;
            Vec3 first(0.0f);
            for (int j = 0; j < width_; ++j) {
              double texel[3] = {0.0, 0.0, 0.0};
              for (int a = 0; a < k; ++a) {
                const double z = z_edge_[i] + (a + 0.5) / k * (z_edge_[i + 1] - z_edge_[i]);
                for (int b = 0; b < k; ++b) {
                  const double phi = kTwoPiD * (j + (b + 0.5) / k) / width_;
                  const Vec3 l = sanitized(radiance_(direction_at(z, phi)));
                  if (j == 0 && a == 0 && b == 0) first = l;
                  flat = flat && l.x == first.x && l.y == first.y && l.z == first.z;
                  texel[0] += l.x;
                  texel[1] += l.y;
                  texel[2] += l.z;
                }
              }
              red += texel[0];
              green += texel[1];
              blue += texel[2];
              centre[static_cast<size_t>(i) * width_ + j] =
                  static_cast<float>((texel[0] + texel[1] + texel[2]) / (3.0 * k * k));
            }
            row_color[i] =
                Vec3(static_cast<float>(red), static_cast<float>(green), static_cast<float>(blue)) *
                (1.0f / static_cast<float>(k * k));
            row_flat[i] = flat;
            row_first[i] = first;
          }
        });
    const Vec3 first = row_first.front();
    flat_ = !(cancel && cancel->load()) && !is_black(first);
    for (int i = 0; i < height_ && flat_; ++i)
      flat_ = row_flat[i] && row_first[i].x == first.x && row_first[i].y == first.y &&
              row_first[i].z == first.z;
    // A texel's sampling weight is the largest value of it and its eight neighbours: the
    // texture's bilinear filter spreads a bright pixel (a sun a few pixels wide) half a pixel
    // into its neighbours, and where the radiance stood far above its texel's weight, BSDF
    // samples that found it would be fireflies. The weight must bound the radiance over the
    // texel, as pbrt-v3's image infinite light builds its distribution from a filtered lookup.
    tbb::parallel_for(
        tbb::blocked_range<int>(0, height_, 1), [&](const tbb::blocked_range<int>& r) {
          std::vector<double> weights(width_);
          for (int i = r.begin(); i != r.end(); ++i) {
            if (cancel && cancel->load(std::memory_order_relaxed)) return;
            double row_sum = 0.0;
            for (int j = 0; j < width_; ++j) {
              float v = 0.0f;
              for (int di = std::max(i - 1, 0); di <= std::min(i + 1, height_ - 1); ++di)
                for (int dj = j - 1; dj <= j + 1; ++dj)
                  v = std::max(v, centre[static_cast<size_t>(di) * width_ +
                                         static_cast<size_t>((dj + width_) % width_)]);
              value_[static_cast<size_t>(i) * width_ + j] = v;
              // The float that pdfs read, so the sampled and looked-up densities agree.
              weights[j] = v;
              row_sum += weights[j];
            }
            columns_[i] = Distribution1D(weights);
            row_value[i] = row_sum;
          }
        });
  }
  // Each row's texels share one solid angle: (2 pi / width) (cos theta_top - cos theta_bottom).
  std::vector<double> row_weight(height_);
  double total = 0.0, integral[3] = {0.0, 0.0, 0.0};
  for (int i = 0; i < height_; ++i) {
    const double solid_angle = kTwoPiD / width_ * (z_edge_[i] - z_edge_[i + 1]);
    row_weight[i] = row_value[i] * solid_angle;
    total += row_weight[i];
    for (int c = 0; c < 3; ++c) integral[c] += row_color[i][c] * solid_angle;
  }
  rows_ = Distribution1D(row_weight);
  integral_ = Vec3(static_cast<float>(integral[0]), static_cast<float>(integral[1]),
                   static_cast<float>(integral[2]));
  if (total > 0.0 && std::isfinite(total)) {
    inv_total_ = 1.0 / total;
    uniform_share_ = kUniformShare;
  }
}

Vec3 EnvironmentEmitter::radiance_at_infinity(const Vec3& direction, bool) const {
  return radiance_ ? sanitized(radiance_(direction)) : Vec3(0.0f);
}

float EnvironmentEmitter::mixed_pdf(int row, int col) const {
  const float uniform = uniform_share_ * kInv4Pi;
  if (uniform_share_ >= 1.0f) return uniform;
  return (1.0f - uniform_share_) * map_pdf(row, col) + uniform;
}

float EnvironmentEmitter::pdf_at_infinity(const Vec3& direction, bool) const {
  if (!is_finite(direction)) return 0.0f;
  double phi = std::atan2(static_cast<double>(direction.y), static_cast<double>(direction.x));
  if (phi < 0.0) phi += kTwoPiD;
  const int col = std::clamp(static_cast<int>(phi / kTwoPiD * width_), 0, width_ - 1);
  const double z = std::clamp(static_cast<double>(direction.z), -1.0, 1.0);
  int row = std::clamp(static_cast<int>(std::acos(z) / (0.5 * kTwoPiD) * height_), 0, height_ - 1);
  // The rows sample() draws from are bounded by z_edge_: settle rounding at an edge with them.
  while (row > 0 && z > z_edge_[row]) --row;
  while (row + 1 < height_ && z < z_edge_[row + 1]) ++row;
  return mixed_pdf(row, col);
}

bool EnvironmentEmitter::sample_direction(Vec2 u, Vec3* direction, float* pdf) const {
  if (!(u.x >= 0.0f && u.x < 1.0f && u.y >= 0.0f && u.y < 1.0f)) return false;
  if (u.x < uniform_share_) {
    const float ux = std::min(u.x / uniform_share_, 0.99999994f);
    *direction = sample_uniform_sphere(Vec2(ux, u.y));
    *pdf = pdf_at_infinity(*direction);
    return *pdf > 0.0f;
  }
  const float u_row = std::min((u.x - uniform_share_) / (1.0f - uniform_share_), 0.99999994f);
  float r_row, r_col;
  const size_t row = rows_.sample(u_row, &r_row);
  const size_t col = columns_[row].sample(u.y, &r_col);
  // Uniform in solid angle inside the texel: cos(theta) and phi uniform.
  const double z = z_edge_[row] + r_row * (z_edge_[row + 1] - z_edge_[row]);
  const double phi = kTwoPiD * (col + static_cast<double>(r_col)) / width_;
  *direction = direction_at(z, phi);
  *pdf = mixed_pdf(static_cast<int>(row), static_cast<int>(col));
  return *pdf > 0.0f;
}

bool EnvironmentEmitter::sample_li(const Vec3&, const LightSampleU& u,
                                   const PhotonFrame* bidirectional, LightSample* out) const {
  out->surface_normal = Vec3(0.0f);
  if (bidirectional) {
    float pdf;
    if (!sample_direction(u.uv, &out->wi, &pdf) || !(pdf > 0.0f)) return false;
    out->distance = INFINITY;
    out->radiance = radiance_at_infinity(out->wi);
    out->direct_pdf = pdf;
    out->emission_pdf = pdf * scene_disc_pdf(*bidirectional);
    out->cos_light = 1.0f;
    return !is_black(out->radiance) && is_finite(out->radiance);
  }
  if (flat_) return false;  // reached by BSDF samples (flags())
  Vec3 wi;
  float pdf;
  if (!sample_direction(u.uv, &wi, &pdf)) return false;
  const Vec3 l = radiance_at_infinity(wi);
  if (is_black(l)) return false;
  out->wi = wi;
  out->distance = INFINITY;
  out->pdf = pdf;
  out->weight = l / pdf;
  return is_finite(out->weight);
}

Vec3 EnvironmentEmitter::power(float scene_radius) const {
  return integral_ * (kPi * scene_radius * scene_radius);
}

bool EnvironmentEmitter::sample_le(const PhotonFrame& frame, float, Vec2 u_pos, Vec2 u_dir,
                                   bool bidirectional, EmittedPhoton* out) const {
  if (bidirectional) {
    Vec3 w;
    float pdf;
    if (!sample_direction(u_dir, &w, &pdf) || !(pdf > 0.0f)) return false;
    ray_from_infinity(frame, -w, u_pos, &out->ray);
    out->radiance = radiance_at_infinity(w);
    out->pdf_pos = scene_disc_pdf(frame);
    out->pdf_dir = out->direct_pdf = pdf;
    out->cos_light = 1.0f;
    return !is_black(out->radiance) && is_finite(out->radiance);
  }
  out->power = Vec3(0.0f);
  Vec3 w;
  float pdf = 0.0f;
  if (!sample_direction(u_dir, &w, &pdf)) {
    w = Vec3(0.0f, 0.0f, 1.0f);
    pdf = 0.0f;
  }
  // The light arrives from w, so the photon travels along -w, entering through a disc
  // perpendicular to it that covers the scene (as the uniform world's photons).
  ray_from_infinity(frame, -w, u_pos, &out->ray);
  if (pdf > 0.0f) out->power = radiance_at_infinity(w) * (kPi * frame.radius * frame.radius / pdf);
  return pdf > 0.0f;
}

bool EnvironmentEmitter::sample_le_towards(const std::vector<BoundingSphere>& targets,
                                           const PhotonFrame& frame, float u_pick, Vec2 u_pos,
                                           Vec2 u_dir, Sampler&, EmittedPhoton* out) const {
  Vec3 w;
  float pdf_dir = 0.0f;
  if (!sample_direction(u_dir, &w, &pdf_dir)) return false;
  const Vec3 d = -w;
  const DiscMixture discs(d, targets);
  if (discs.empty()) return false;
  Vec3 p;
  float pdf_area = 0.0f;
  discs.sample(u_pick, u_pos, &p, &pdf_area);
  if (!(pdf_area > 0.0f)) return false;
  // From the plane through the origin back to 2 R before the scene's centre along the beam.
  const float back = dot(frame.center, d) - 2.0f * frame.radius;
  set_emitted_ray(p + d * back, d, &out->ray);
  out->power = radiance_at_infinity(w) / (pdf_dir * pdf_area);
  return is_finite(out->power) && !is_black(out->power);
}

float EnvironmentEmitter::coverage(const std::vector<BoundingSphere>& targets,
                                   float scene_radius) const {
  if (targets.empty()) return 0.0f;
  const DiscMixture discs(Vec3(0.0f, 0.0f, 1.0f), targets);
  return std::min(1.0f, discs.total_area() / (kPi * scene_radius * scene_radius));
}

LightBounds EnvironmentEmitter::bounds() const {
  LightBounds b;
  b.infinite = true;
  b.lo = b.hi = Vec3(0.0f);
  b.power = mean_power(integral_) * kInv4Pi;  // mean radiance, as the uniform world's
  return b;
}

}  // namespace photon
