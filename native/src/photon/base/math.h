// Small vector and transform types shared by the whole renderer.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace photon {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kInvPi = 1.0f / kPi;
constexpr float kInv4Pi = 1.0f / (4.0f * kPi);

struct Vec2 {
  float x = 0, y = 0;
  Vec2() = default;
  Vec2(float x_, float y_) : x(x_), y(y_) {}
  Vec2 operator+(Vec2 b) const { return {x + b.x, y + b.y}; }
  Vec2 operator-(Vec2 b) const { return {x - b.x, y - b.y}; }
  Vec2 operator*(float s) const { return {x * s, y * s}; }
};

struct Vec3 {
  float x = 0, y = 0, z = 0;
  Vec3() = default;
  constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
  explicit constexpr Vec3(float s) : x(s), y(s), z(s) {}
  float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  Vec3 operator+(const Vec3& b) const { return {x + b.x, y + b.y, z + b.z}; }
  Vec3 operator-(const Vec3& b) const { return {x - b.x, y - b.y, z - b.z}; }
  Vec3 operator*(const Vec3& b) const { return {x * b.x, y * b.y, z * b.z}; }
  Vec3 operator/(const Vec3& b) const { return {x / b.x, y / b.y, z / b.z}; }
  Vec3 operator*(float s) const { return {x * s, y * s, z * s}; }
  Vec3 operator/(float s) const { return *this * (1.0f / s); }
  Vec3 operator-() const { return {-x, -y, -z}; }
  Vec3& operator+=(const Vec3& b) {
    x += b.x;
    y += b.y;
    z += b.z;
    return *this;
  }
  Vec3& operator*=(const Vec3& b) {
    x *= b.x;
    y *= b.y;
    z *= b.z;
    return *this;
  }
  Vec3& operator*=(float s) {
    x *= s;
    y *= s;
    z *= s;
    return *this;
  }
};

inline Vec3 operator*(float s, const Vec3& v) {
  return v * s;
}
inline float dot(const Vec3& a, const Vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(const Vec3& v) {
  return std::sqrt(dot(v, v));
}
inline float length_squared(const Vec3& v) {
  return dot(v, v);
}
inline Vec3 normalize(const Vec3& v) {
  float l = length(v);
  return l > 0.0f ? v / l : Vec3(0.0f, 0.0f, 1.0f);
}
inline float max_component(const Vec3& v) {
  return std::max(v.x, std::max(v.y, v.z));
}
inline float max_abs_component(const Vec3& v) {
  return std::max(std::fabs(v.x), std::max(std::fabs(v.y), std::fabs(v.z)));
}
inline bool is_finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
inline bool is_black(const Vec3& v) {
  return v.x <= 0.0f && v.y <= 0.0f && v.z <= 0.0f;
}
inline float luminance(const Vec3& c) {
  return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}
inline Vec3 lerp(const Vec3& a, const Vec3& b, float t) {
  return a * (1.0f - t) + b * t;
}
inline Vec3 min(const Vec3& a, const Vec3& b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
inline Vec3 max(const Vec3& a, const Vec3& b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}

// Orthonormal basis around a unit normal (Duff et al. 2017, "Building an Orthonormal Basis,
// Revisited"), so local directions can be mapped to world space without branches.
struct Frame {
  Vec3 t, b, n;
  Frame() = default;
  explicit Frame(const Vec3& normal) : n(normal) {
    float sign = std::copysign(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float c = n.x * n.y * a;
    t = Vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
    b = Vec3(c, sign + n.y * n.y * a, -n.y);
  }
  Vec3 to_world(const Vec3& v) const { return t * v.x + b * v.y + n * v.z; }
  Vec3 to_local(const Vec3& v) const { return {dot(v, t), dot(v, b), dot(v, n)}; }
};

// Affine transform stored as a row-major 3x4 matrix (the last row of the 4x4 is 0 0 0 1).
struct Transform {
  float m[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};

  static Transform from_rows(const float* rows12) {
    Transform t;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) t.m[r][c] = rows12[r * 4 + c];
    return t;
  }
  static Transform translation(const Vec3& t) {
    Transform x;
    x.m[0][3] = t.x;
    x.m[1][3] = t.y;
    x.m[2][3] = t.z;
    return x;
  }
  Vec3 point(const Vec3& p) const {
    return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
            m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
            m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
  }
  Vec3 vector(const Vec3& v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
  Vec3 column(int c) const { return {m[0][c], m[1][c], m[2][c]}; }
  float determinant3() const {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  }
  // Inverse transpose of the 3x3 part, used to carry normals. Returns false when singular.
  bool normal_matrix(float out[3][3]) const;
  bool is_finite() const {
    for (auto& row : m)
      for (float v : row)
        if (!std::isfinite(v)) return false;
    return true;
  }
};

inline bool Transform::normal_matrix(float out[3][3]) const {
  float det = determinant3();
  if (!(std::fabs(det) > 1e-30f) || !std::isfinite(det)) return false;
  float inv_det = 1.0f / det;
  // Cofactor matrix divided by the determinant equals the inverse transpose.
  out[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) * inv_det;
  out[0][1] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) * inv_det;
  out[0][2] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) * inv_det;
  out[1][0] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * inv_det;
  out[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * inv_det;
  out[1][2] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * inv_det;
  out[2][0] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * inv_det;
  out[2][1] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * inv_det;
  out[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * inv_det;
  return true;
}

struct Ray {
  Vec3 origin;
  Vec3 direction;  // unit length
  float tmin = 0.0f;
  float tmax = INFINITY;
};

}  // namespace photon
