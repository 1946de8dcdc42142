#include "photon/shading/voronoi.h"

#include <algorithm>
#include <cmath>

#include "photon/shading/hash.h"

namespace photon::voronoi {
namespace {

// A point of the N-dimensional cell lattice (N = 1..4), component 0 being x (or w in 1D).
template <int N>
struct Point {
  float v[N];
};

template <int N>
Point<N> operator+(const Point<N>& a, const Point<N>& b) {
  Point<N> r;
  for (int i = 0; i < N; ++i) r.v[i] = a.v[i] + b.v[i];
  return r;
}
template <int N>
Point<N> operator-(const Point<N>& a, const Point<N>& b) {
  Point<N> r;
  for (int i = 0; i < N; ++i) r.v[i] = a.v[i] - b.v[i];
  return r;
}
template <int N>
Point<N> operator*(const Point<N>& a, float s) {
  Point<N> r;
  for (int i = 0; i < N; ++i) r.v[i] = a.v[i] * s;
  return r;
}
template <int N>
Point<N> floor_point(const Point<N>& a) {
  Point<N> r;
  for (int i = 0; i < N; ++i) r.v[i] = std::floor(a.v[i]);
  return r;
}
template <int N>
Point<N> zero_point() {
  Point<N> r;
  for (int i = 0; i < N; ++i) r.v[i] = 0.0f;
  return r;
}
// Summation order as Cycles' dot products (4D: the two halves of an SSE dot, then their sum).
template <int N>
float dot(const Point<N>& a, const Point<N>& b) {
  if constexpr (N == 4) {
    return (a.v[0] * b.v[0] + a.v[1] * b.v[1]) + (a.v[2] * b.v[2] + a.v[3] * b.v[3]);
  } else {
    float s = a.v[0] * b.v[0];
    for (int i = 1; i < N; ++i) s += a.v[i] * b.v[i];
    return s;
  }
}
template <int N>
float length(const Point<N>& a) {
  if constexpr (N == 1) {
    return std::fabs(a.v[0]);
  } else {
    return std::sqrt(dot(a, a));
  }
}
template <int N>
Point<N> normalize(const Point<N>& a) {
  return a * (1.0f / length(a));
}

// Cycles' mix() and smoothstep() (util/math), which the smooth minimum is written in.
inline float mix(float a, float b, float t) {
  return a + t * (b - a);
}
inline float smoothstep(float edge0, float edge1, float x) {
  if (x < edge0) return 0.0f;
  if (x >= edge1) return 1.0f;
  const float t = (x - edge0) / (edge1 - edge0);
  return (3.0f - 2.0f * t) * (t * t);
}

// The feature point's jitter in a cell, in [0, 1]^N (Cycles' hash_floatN_to_floatN: the cell's
// float bits hashed, with a constant 1.0 appended (2D, 3D) or the components rotated (4D) to get
// independent further components).
inline float hash4(float a, float b, float c, float d) {
  return hash::hash_float4_to_float(Vec3(a, b, c), d);
}
Point<1> cell_jitter(const Point<1>& c) {
  return {{hash::hash_float_to_float(c.v[0])}};
}
Point<2> cell_jitter(const Point<2>& c) {
  return {{hash::hash_float2_to_float(c.v[0], c.v[1]),
           hash::hash_float3_to_float(Vec3(c.v[0], c.v[1], 1.0f))}};
}
Point<3> cell_jitter(const Point<3>& c) {
  const Vec3 k(c.v[0], c.v[1], c.v[2]);
  return {{hash::hash_float3_to_float(k), hash::hash_float4_to_float(k, 1.0f),
           hash::hash_float4_to_float(k, 2.0f)}};
}
Point<4> cell_jitter(const Point<4>& c) {
  const float x = c.v[0], y = c.v[1], z = c.v[2], w = c.v[3];
  return {{hash4(x, y, z, w), hash4(w, x, y, z), hash4(z, w, x, y), hash4(y, z, w, x)}};
}

// A cell's colour (Cycles' hash_floatN_to_float3).
Vec3 cell_color(const Point<1>& c) {
  const float k = c.v[0];
  return {hash::hash_float_to_float(k), hash::hash_float2_to_float(k, 1.0f),
          hash::hash_float2_to_float(k, 2.0f)};
}
Vec3 cell_color(const Point<2>& c) {
  const float x = c.v[0], y = c.v[1];
  return {hash::hash_float2_to_float(x, y), hash::hash_float3_to_float(Vec3(x, y, 1.0f)),
          hash::hash_float3_to_float(Vec3(x, y, 2.0f))};
}
Vec3 cell_color(const Point<3>& c) {
  const Point<3> j = cell_jitter(c);
  return {j.v[0], j.v[1], j.v[2]};
}
Vec3 cell_color(const Point<4>& c) {
  const float x = c.v[0], y = c.v[1], z = c.v[2], w = c.v[3];
  return {hash4(x, y, z, w), hash4(z, x, w, y), hash4(w, z, y, x)};
}

// The distance the features rank points by: 1D is always |a - b|; higher dimensions use the
// node's metric, summed component by component in x, y, z, w order.
template <int N>
float metric_distance(const Point<N>& a, const Point<N>& b, const Params& params) {
  if constexpr (N == 1) {
    return std::fabs(b.v[0] - a.v[0]);
  } else {
    switch (params.metric) {
      case Metric::kEuclidean:
        return length(a - b);
      case Metric::kManhattan: {
        float s = std::fabs(a.v[0] - b.v[0]);
        for (int i = 1; i < N; ++i) s += std::fabs(a.v[i] - b.v[i]);
        return s;
      }
      case Metric::kChebychev: {
        float m = std::fabs(a.v[0] - b.v[0]);
        for (int i = 1; i < N; ++i) m = std::max(m, std::fabs(a.v[i] - b.v[i]));
        return m;
      }
      case Metric::kMinkowski: {
        const float e = params.exponent;
        float s = std::pow(std::fabs(a.v[0] - b.v[0]), e);
        for (int i = 1; i < N; ++i) s += std::pow(std::fabs(a.v[i] - b.v[i]), e);
        return std::pow(s, 1.0f / e);
      }
    }
    return 0.0f;
  }
}

// Calls f(offset) for every cell offset in [-R, R]^N, x varying fastest (Cycles' loop nesting, so
// ties and the order-dependent smooth blend resolve the same way).
template <int N, int R, typename F>
void for_each_offset(F&& f) {
  constexpr int side = 2 * R + 1;
  int count = 1;
  for (int i = 0; i < N; ++i) count *= side;
  for (int n = 0; n < count; ++n) {
    Point<N> offset;
    int m = n;
    for (int i = 0; i < N; ++i, m /= side) offset.v[i] = static_cast<float>(m % side - R);
    f(offset);
  }
}

template <int N>
void set_position(const Point<N>& p, Result* r) {
  if constexpr (N == 1) {
    r->position[3] = p.v[0];
  } else {
    for (int i = 0; i < N; ++i) r->position[i] = p.v[i];
  }
}

// 8.0 is Cycles' "farther than any point in the window" start for the searches below.
constexpr float kFar = 8.0f;

template <int N>
Result f1(const Point<N>& coord, const Params& params) {
  const Point<N> cell = floor_point(coord);
  const Point<N> local = coord - cell;
  float min_distance = kFar;
  Point<N> target_offset = zero_point<N>(), target_position = zero_point<N>();
  for_each_offset<N, 1>([&](const Point<N>& offset) {
    const Point<N> point = offset + cell_jitter(cell + offset) * params.randomness;
    const float d = metric_distance(point, local, params);
    if (d < min_distance) {
      target_offset = offset;
      min_distance = d;
      target_position = point;
    }
  });
  Result r;
  r.distance = min_distance;
  r.color = cell_color(cell + target_offset);
  set_position(target_position + cell, &r);
  return r;
}

template <int N>
Result f2(const Point<N>& coord, const Params& params) {
  const Point<N> cell = floor_point(coord);
  const Point<N> local = coord - cell;
  float distance_f1 = kFar, distance_f2 = kFar;
  Point<N> offset_f1 = zero_point<N>(), position_f1 = zero_point<N>();
  Point<N> offset_f2 = zero_point<N>(), position_f2 = zero_point<N>();
  for_each_offset<N, 1>([&](const Point<N>& offset) {
    const Point<N> point = offset + cell_jitter(cell + offset) * params.randomness;
    const float d = metric_distance(point, local, params);
    if (d < distance_f1) {
      distance_f2 = distance_f1;
      distance_f1 = d;
      offset_f2 = offset_f1;
      offset_f1 = offset;
      position_f2 = position_f1;
      position_f1 = point;
    } else if (d < distance_f2) {
      distance_f2 = d;
      offset_f2 = offset;
      position_f2 = point;
    }
  });
  Result r;
  r.distance = distance_f2;
  r.color = cell_color(cell + offset_f2);
  set_position(position_f2 + cell, &r);
  return r;
}

// Quilez's polynomial smooth minimum folded over the 5^N window: each point pulls the running
// distance, colour and position towards its own by h, minus a correction that keeps the blend
// below both (Blender's "Smooth F1", GSoC 2019 documentation).
template <int N>
Result smooth_f1(const Point<N>& coord, const Params& params) {
  const Point<N> cell = floor_point(coord);
  const Point<N> local = coord - cell;
  const float s = params.smoothness;
  float smooth_distance = kFar;
  Vec3 smooth_color(0.0f);
  Point<N> smooth_position = zero_point<N>();
  for_each_offset<N, 2>([&](const Point<N>& offset) {
    const Point<N> point = offset + cell_jitter(cell + offset) * params.randomness;
    const float d = metric_distance(point, local, params);
    const float h = smoothstep(0.0f, 1.0f, 0.5f + 0.5f * (smooth_distance - d) / s);
    float correction = s * h * (1.0f - h);
    smooth_distance = mix(smooth_distance, d, h) - correction;
    correction /= 1.0f + 3.0f * s;
    const Vec3 color = cell_color(cell + offset);
    for (int i = 0; i < 3; ++i) smooth_color[i] = mix(smooth_color[i], color[i], h) - correction;
    for (int i = 0; i < N; ++i)
      smooth_position.v[i] = mix(smooth_position.v[i], point.v[i], h) - correction;
  });
  Result r;
  r.distance = smooth_distance;
  r.color = smooth_color;
  set_position(cell + smooth_position, &r);
  return r;
}

// 1D: the nearer of the two midpoints between this cell's point and its neighbours'.
Result distance_to_edge(const Point<1>& coord, const Params& params) {
  const float cell = std::floor(coord.v[0]);
  const float local = coord.v[0] - cell;
  const float r = params.randomness;
  const float mid = hash::hash_float_to_float(cell) * r;
  const float left = -1.0f + hash::hash_float_to_float(cell - 1.0f) * r;
  const float right = 1.0f + hash::hash_float_to_float(cell + 1.0f) * r;
  const float to_left = std::fabs((mid + left) / 2.0f - local);
  const float to_right = std::fabs((mid + right) / 2.0f - local);
  Result out;
  out.distance = std::min(to_left, to_right);
  return out;
}

// 2D-4D: the nearest point, then the distance to each bisector plane between it and the others
// (Quilez, "Voronoi edges"), always Euclidean.
template <int N>
Result distance_to_edge(const Point<N>& coord, const Params& params) {
  const Point<N> cell = floor_point(coord);
  const Point<N> local = coord - cell;
  auto vector_to = [&](const Point<N>& offset) {
    return offset + cell_jitter(cell + offset) * params.randomness - local;
  };
  Point<N> to_closest = zero_point<N>();
  float min_distance = kFar;
  for_each_offset<N, 1>([&](const Point<N>& offset) {
    const Point<N> v = vector_to(offset);
    const float d = dot(v, v);
    if (d < min_distance) {
      min_distance = d;
      to_closest = v;
    }
  });
  min_distance = kFar;
  for_each_offset<N, 1>([&](const Point<N>& offset) {
    const Point<N> v = vector_to(offset);
    const Point<N> perpendicular = v - to_closest;
    if (dot(perpendicular, perpendicular) > 0.0001f) {
      const float d = dot((to_closest + v) * 0.5f, normalize(perpendicular));
      min_distance = std::min(min_distance, d);
    }
  });
  Result out;
  out.distance = min_distance;
  return out;
}

// Half the distance from the nearest point to its own nearest neighbour (searched around the
// nearest point's cell): the radius of the largest sphere centred on the point inside its cell.
template <int N>
Result n_sphere_radius(const Point<N>& coord, const Params& params) {
  const Point<N> cell = floor_point(coord);
  const Point<N> local = coord - cell;
  Point<N> closest = zero_point<N>(), closest_offset = zero_point<N>();
  float min_distance = kFar;
  for_each_offset<N, 1>([&](const Point<N>& offset) {
    const Point<N> point = offset + cell_jitter(cell + offset) * params.randomness;
    const float d = length(point - local);
    if (d < min_distance) {
      min_distance = d;
      closest = point;
      closest_offset = offset;
    }
  });
  min_distance = kFar;
  Point<N> closest_to_closest = zero_point<N>();
  for_each_offset<N, 1>([&](const Point<N>& step) {
    bool centre = true;
    for (int i = 0; i < N; ++i) centre = centre && step.v[i] == 0.0f;
    if (centre) return;
    const Point<N> offset = step + closest_offset;
    const Point<N> point = offset + cell_jitter(cell + offset) * params.randomness;
    const float d = length(closest - point);
    if (d < min_distance) {
      min_distance = d;
      closest_to_closest = point;
    }
  });
  Result out;
  out.radius = length(closest_to_closest - closest) / 2.0f;
  return out;
}

template <int N>
Result evaluate(const Point<N>& coord, const Params& params) {
  switch (params.feature) {
    case Feature::kF1:
      return f1(coord, params);
    case Feature::kF2:
      return f2(coord, params);
    case Feature::kSmoothF1:
      return smooth_f1(coord, params);
    case Feature::kDistanceToEdge:
      return distance_to_edge(coord, params);
    case Feature::kNSphereRadius:
      return n_sphere_radius(coord, params);
  }
  return Result{};
}

}  // namespace

Result voronoi_1d(float w, const Params& params) {
  return evaluate(Point<1>{{w}}, params);
}
Result voronoi_2d(float x, float y, const Params& params) {
  return evaluate(Point<2>{{x, y}}, params);
}
Result voronoi_3d(const Vec3& p, const Params& params) {
  return evaluate(Point<3>{{p.x, p.y, p.z}}, params);
}
Result voronoi_4d(const Vec3& p, float w, const Params& params) {
  return evaluate(Point<4>{{p.x, p.y, p.z, w}}, params);
}

}  // namespace photon::voronoi
