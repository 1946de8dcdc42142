#include "photon/lightmap.h"

#include <algorithm>
#include <cmath>

namespace photon {
namespace {

float cross2(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }

constexpr float kConeC = 1.1f;  // Jensen's cone filter constant

}  // namespace

std::vector<TexelPoint> rasterize_uv_triangles(const Vec2* uvs, const Vec3* positions,
                                               size_t triangle_count, int width, int height) {
  std::vector<TexelPoint> out;
  if (width <= 0 || height <= 0) return out;
  std::vector<uint8_t> taken(static_cast<size_t>(width) * height, 0);
  for (size_t t = 0; t < triangle_count; ++t) {
    // In texel units, so texel (x, y) has its centre at (x + 0.5, y + 0.5).
    Vec2 p[3];
    bool finite = true;
    for (int c = 0; c < 3; ++c) {
      p[c] = Vec2(uvs[3 * t + c].x * width, uvs[3 * t + c].y * height);
      finite = finite && std::isfinite(p[c].x) && std::isfinite(p[c].y);
    }
    if (!finite) continue;
    const Vec2 e1(p[1].x - p[0].x, p[1].y - p[0].y), e2(p[2].x - p[0].x, p[2].y - p[0].y);
    const float area2 = cross2(e1, e2);
    if (!(std::fabs(area2) > 1e-12f)) continue;
    float world_size = 0.0f;
    if (positions) {
      const Vec3* q = positions + 3 * t;
      const float world_area2 = length(cross(q[1] - q[0], q[2] - q[0]));
      if (std::isfinite(world_area2)) world_size = std::sqrt(world_area2 / std::fabs(area2));
    }
    const float lo_x = std::min({p[0].x, p[1].x, p[2].x}), hi_x = std::max({p[0].x, p[1].x, p[2].x});
    const float lo_y = std::min({p[0].y, p[1].y, p[2].y}), hi_y = std::max({p[0].y, p[1].y, p[2].y});
    const int x0 = std::max(0, static_cast<int>(std::floor(lo_x - 0.5f)));
    const int x1 = std::min(width - 1, static_cast<int>(std::ceil(hi_x - 0.5f)));
    const int y0 = std::max(0, static_cast<int>(std::floor(lo_y - 0.5f)));
    const int y1 = std::min(height - 1, static_cast<int>(std::ceil(hi_y - 0.5f)));
    const float inv = 1.0f / area2;
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const size_t texel = static_cast<size_t>(y) * width + x;
        if (taken[texel]) continue;
        const Vec2 d(x + 0.5f - p[0].x, y + 0.5f - p[0].y);
        const float b1 = cross2(d, e2) * inv, b2 = cross2(e1, d) * inv;
        // A small tolerance keeps texels on a shared edge from falling through both triangles.
        constexpr float kEps = -1e-5f;
        if (b1 < kEps || b2 < kEps || b1 + b2 > 1.0f - kEps) continue;
        taken[texel] = 1;
        TexelPoint tp;
        tp.texel = static_cast<uint32_t>(texel);
        tp.triangle = static_cast<uint32_t>(t);
        tp.u = std::clamp(b1, 0.0f, 1.0f);
        tp.v = std::clamp(b2, 0.0f, 1.0f - tp.u);
        tp.world_size = world_size;
        out.push_back(tp);
      }
    }
  }
  return out;
}

std::vector<Vec3> filter_lightmap(int width, int height, const std::vector<Vec3>& values,
                                  const std::vector<uint8_t>& covered,
                                  const std::vector<Vec3>& positions,
                                  const std::vector<Vec3>& normals,
                                  const std::vector<float>& world_size,
                                  const LightmapFilter& filter,
                                  std::vector<uint8_t>* covered_out) {
  const size_t count = static_cast<size_t>(std::max(width, 0)) * std::max(height, 0);
  std::vector<Vec3> out(count, Vec3(0.0f));
  std::vector<uint8_t> mask(count, 0);
  const int r = std::max(filter.radius, 0);
  const float support = kConeC * (static_cast<float>(r) + 0.5f);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const size_t i = static_cast<size_t>(y) * width + x;
      if (!covered[i]) continue;
      Vec3 sum(0.0f);
      float weight_sum = 0.0f;
      for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
          const size_t j = static_cast<size_t>(ny) * width + nx;
          if (!covered[j]) continue;
          const float d = std::sqrt(static_cast<float>(dx * dx + dy * dy));
          if (j != i) {
            if (dot(normals[i], normals[j]) < filter.min_normal_cos) continue;
            const float reach = filter.max_stretch * d * std::max(world_size[i], world_size[j]);
            if (length(positions[i] - positions[j]) > reach) continue;
          }
          const float w = 1.0f - d / support;
          sum += values[j] * w;
          weight_sum += w;
        }
      }
      out[i] = sum / weight_sum;  // the texel itself always has weight 1
      mask[i] = 1;
    }
  }
  // Dilation: each pass reads the previous pass's coverage only, so the order of texels in a
  // pass does not matter.
  for (int pass = 0; pass < filter.dilate; ++pass) {
    std::vector<uint8_t> next = mask;
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        const size_t i = static_cast<size_t>(y) * width + x;
        if (mask[i]) continue;
        Vec3 sum(0.0f);
        int k = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx, ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
            const size_t j = static_cast<size_t>(ny) * width + nx;
            if (mask[j]) sum += out[j], ++k;
          }
        if (k) {
          out[i] = sum / static_cast<float>(k);
          next[i] = 1;
        }
      }
    }
    mask.swap(next);
  }
  if (covered_out) *covered_out = std::move(mask);
  return out;
}

}  // namespace photon
