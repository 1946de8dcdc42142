#include "photon/session/lightmap.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace photon {
namespace {

float cross2(Vec2 a, Vec2 b) {
  return a.x * b.y - a.y * b.x;
}

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
    const float lo_x = std::min({p[0].x, p[1].x, p[2].x}),
                hi_x = std::max({p[0].x, p[1].x, p[2].x});
    const float lo_y = std::min({p[0].y, p[1].y, p[2].y}),
                hi_y = std::max({p[0].y, p[1].y, p[2].y});
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
                                  const LightmapFilter& filter, std::vector<uint8_t>* covered_out) {
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

void upsample_lightmap_rgba(const Vec3* values, int width, int height, int factor, float* rgba) {
  if (width <= 0 || height <= 0 || factor <= 0) return;
  const int out_w = width * factor, out_h = height * factor;
  const float inv = 1.0f / static_cast<float>(factor);
  // Source coordinate of an output texel centre, and its two neighbours and weight.
  auto tap = [inv](int o, int n, int* i0, int* i1, float* t) {
    const float x = (static_cast<float>(o) + 0.5f) * inv - 0.5f;
    const float f = std::floor(x);
    *t = x - f;
    *i0 = std::clamp(static_cast<int>(f), 0, n - 1);
    *i1 = std::clamp(static_cast<int>(f) + 1, 0, n - 1);
  };
  tbb::parallel_for(tbb::blocked_range<int>(0, out_h, 16), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y != r.end(); ++y) {
      int y0, y1;
      float ty;
      tap(y, height, &y0, &y1, &ty);
      const Vec3* row0 = values + static_cast<size_t>(y0) * width;
      const Vec3* row1 = values + static_cast<size_t>(y1) * width;
      float* out = rgba + static_cast<size_t>(y) * out_w * 4;
      for (int x = 0; x < out_w; ++x) {
        int x0, x1;
        float tx;
        tap(x, width, &x0, &x1, &tx);
        const Vec3 v = (row0[x0] * (1.0f - tx) + row0[x1] * tx) * (1.0f - ty) +
                       (row1[x0] * (1.0f - tx) + row1[x1] * tx) * ty;
        out[4 * x] = v.x;
        out[4 * x + 1] = v.y;
        out[4 * x + 2] = v.z;
        out[4 * x + 3] = 1.0f;
      }
    }
  });
}

}  // namespace photon
