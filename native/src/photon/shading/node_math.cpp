#include "photon/shading/node_math.h"

#include <cfloat>
#include <climits>
#include <cmath>

namespace photon {

namespace {

constexpr float kCyclesPi = 3.1415926535897932f;

// Cycles' float_to_int is a C cast; on x86 an out-of-range or NaN float becomes INT_MIN. Done
// explicitly here so the comparison in safe_powf behaves the same without undefined behaviour.
float truncate_like_int_cast(float f) {
  if (!(std::fabs(f) < 2147483648.0f)) return -2147483648.0f;
  return static_cast<float>(static_cast<int32_t>(f));
}

Vec3 floor3(const Vec3& a) {
  return {std::floor(a.x), std::floor(a.y), std::floor(a.z)};
}

// Zero-safe normalisation for the Normal input of Reflect/Refract: Cycles divides by the length
// (a zero vector becomes NaN); Photon keeps the zero vector so no NaN reaches the film.
Vec3 normalize_or_zero(const Vec3& a) {
  float l = length(a);
  return l != 0.0f ? a / l : Vec3(0.0f);
}

}  // namespace

bool vector_math_op_is_value(VectorMathOp op) {
  return op == VectorMathOp::kDotProduct || op == VectorMathOp::kDistance ||
         op == VectorMathOp::kLength;
}

float safe_divide(float a, float b) {
  return b != 0.0f ? a / b : 0.0f;
}
float safe_modulo(float a, float b) {
  return b != 0.0f ? std::fmod(a, b) : 0.0f;
}

float safe_powf(float a, float b) {
  if (a < 0.0f && b != truncate_like_int_cast(b)) return 0.0f;
  return std::pow(a, b);
}

float safe_logf(float a, float b) {
  if (a <= 0.0f || b <= 0.0f) return 0.0f;
  return safe_divide(std::log(a), std::log(b));
}

float safe_sqrtf(float a) {
  return std::sqrt(cy_max(a, 0.0f));
}
float inverse_sqrtf(float a) {
  return a > 0.0f ? 1.0f / std::sqrt(a) : 0.0f;
}

float compatible_signf(float a) {
  if (a == 0.0f) return 0.0f;
  return a < 0.0f ? -1.0f : 1.0f;
}

float wrapf(float value, float max, float min) {
  float range = max - min;
  return range != 0.0f ? value - range * std::floor((value - min) / range) : min;
}

float pingpongf(float a, float b) {
  if (b == 0.0f) return 0.0f;
  float t = (a - b) / (b * 2.0f);
  return std::fabs((t - std::floor(t)) * b * 2.0f - b);
}

float smoothminf(float a, float b, float k) {
  if (k == 0.0f) return std::fmin(a, b);
  float h = std::fmax(k - std::fabs(a - b), 0.0f) / k;
  return std::fmin(a, b) - h * h * h * k * (1.0f / 6.0f);
}

float eval_math(MathOp op, float a, float b, float c) {
  switch (op) {
    case MathOp::kAdd:
      return a + b;
    case MathOp::kSubtract:
      return a - b;
    case MathOp::kMultiply:
      return a * b;
    case MathOp::kDivide:
      return safe_divide(a, b);
    case MathOp::kMultiplyAdd:
      return a * b + c;
    case MathOp::kPower:
      return safe_powf(a, b);
    case MathOp::kLogarithm:
      return safe_logf(a, b);
    case MathOp::kSqrt:
      return safe_sqrtf(a);
    case MathOp::kInverseSqrt:
      return inverse_sqrtf(a);
    case MathOp::kAbsolute:
      return std::fabs(a);
    case MathOp::kExponent:
      return std::exp(a);
    case MathOp::kMinimum:
      return std::fmin(a, b);
    case MathOp::kMaximum:
      return std::fmax(a, b);
    case MathOp::kLessThan:
      return a < b ? 1.0f : 0.0f;
    case MathOp::kGreaterThan:
      return a > b ? 1.0f : 0.0f;
    case MathOp::kSign:
      return compatible_signf(a);
    case MathOp::kCompare:
      return (a == b || std::fabs(a - b) <= std::fmax(c, FLT_EPSILON)) ? 1.0f : 0.0f;
    case MathOp::kSmoothMin:
      return smoothminf(a, b, c);
    case MathOp::kSmoothMax:
      return -smoothminf(-a, -b, c);
    case MathOp::kRound:
      return std::floor(a + 0.5f);
    case MathOp::kFloor:
      return std::floor(a);
    case MathOp::kCeil:
      return std::ceil(a);
    case MathOp::kTrunc:
      return a >= 0.0f ? std::floor(a) : std::ceil(a);
    case MathOp::kFract:
      return a - std::floor(a);
    case MathOp::kModulo:
      return safe_modulo(a, b);
    case MathOp::kWrap:
      return wrapf(a, b, c);
    case MathOp::kSnap:
      return std::floor(safe_divide(a, b)) * b;
    case MathOp::kPingpong:
      return pingpongf(a, b);
    case MathOp::kSine:
      return std::sin(a);
    case MathOp::kCosine:
      return std::cos(a);
    case MathOp::kTangent:
      return std::tan(a);
    case MathOp::kArcsine:
      return std::asin(cy_clamp(a, -1.0f, 1.0f));
    case MathOp::kArccosine:
      return std::acos(cy_clamp(a, -1.0f, 1.0f));
    case MathOp::kArctangent:
      return std::atan(a);
    case MathOp::kArctan2:
      return std::atan2(a, b);
    case MathOp::kSinh:
      return std::sinh(a);
    case MathOp::kCosh:
      return std::cosh(a);
    case MathOp::kTanh:
      return std::tanh(a);
    case MathOp::kRadians:
      return a * (kCyclesPi / 180.0f);
    case MathOp::kDegrees:
      return a * (180.0f / kCyclesPi);
    case MathOp::kFlooredModulo:  // Cycles 4.x's safe_floored_modulo
      return b != 0.0f ? a - std::floor(a / b) * b : 0.0f;
    case MathOp::kCount:
      break;
  }
  return 0.0f;
}

VectorMathResult eval_vector_math(VectorMathOp op, const Vec3& a, const Vec3& b, const Vec3& c,
                                  float scale) {
  VectorMathResult r;
  switch (op) {
    case VectorMathOp::kAdd:
      r.vector = a + b;
      break;
    case VectorMathOp::kSubtract:
      r.vector = a - b;
      break;
    case VectorMathOp::kMultiply:
      r.vector = a * b;
      break;
    case VectorMathOp::kDivide:
      r.vector = {safe_divide(a.x, b.x), safe_divide(a.y, b.y), safe_divide(a.z, b.z)};
      break;
    case VectorMathOp::kMultiplyAdd:
      r.vector = a * b + c;
      break;
    case VectorMathOp::kCrossProduct:
      r.vector = cross(a, b);
      break;
    case VectorMathOp::kProject: {
      float len_sq = dot(b, b);
      r.vector = len_sq != 0.0f ? b * (dot(a, b) / len_sq) : Vec3(0.0f);
      break;
    }
    case VectorMathOp::kReflect: {
      Vec3 n = normalize_or_zero(b);
      r.vector = a - n * (2.0f * dot(a, n));
      break;
    }
    case VectorMathOp::kRefract: {
      // GLSL refract with eta = Scale ("IOR" in the UI) and a normalised Normal.
      Vec3 n = normalize_or_zero(b);
      float cos_i = dot(n, a);
      float k = 1.0f - scale * scale * (1.0f - cos_i * cos_i);
      r.vector = k < 0.0f ? Vec3(0.0f) : a * scale - n * (scale * cos_i + std::sqrt(k));
      break;
    }
    case VectorMathOp::kFaceforward:
      r.vector = dot(c, b) < 0.0f ? a : -a;
      break;
    case VectorMathOp::kDotProduct:
      r.value = dot(a, b);
      break;
    case VectorMathOp::kDistance:
      r.value = length(a - b);
      break;
    case VectorMathOp::kLength:
      r.value = length(a);
      break;
    case VectorMathOp::kScale:
      r.vector = a * scale;
      break;
    case VectorMathOp::kNormalize: {
      float l = length(a);
      r.vector = l != 0.0f ? a * (1.0f / l) : a;
      break;
    }
    case VectorMathOp::kAbsolute:
      r.vector = {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)};
      break;
    case VectorMathOp::kMinimum:
      r.vector = {cy_min(a.x, b.x), cy_min(a.y, b.y), cy_min(a.z, b.z)};
      break;
    case VectorMathOp::kMaximum:
      r.vector = {cy_max(a.x, b.x), cy_max(a.y, b.y), cy_max(a.z, b.z)};
      break;
    case VectorMathOp::kFloor:
      r.vector = floor3(a);
      break;
    case VectorMathOp::kCeil:
      r.vector = {std::ceil(a.x), std::ceil(a.y), std::ceil(a.z)};
      break;
    case VectorMathOp::kFraction:
      r.vector = a - floor3(a);
      break;
    case VectorMathOp::kModulo:
      r.vector = {safe_modulo(a.x, b.x), safe_modulo(a.y, b.y), safe_modulo(a.z, b.z)};
      break;
    case VectorMathOp::kWrap:
      r.vector = {wrapf(a.x, b.x, c.x), wrapf(a.y, b.y, c.y), wrapf(a.z, b.z, c.z)};
      break;
    case VectorMathOp::kSnap: {
      Vec3 q = {safe_divide(a.x, b.x), safe_divide(a.y, b.y), safe_divide(a.z, b.z)};
      r.vector = floor3(q) * b;
      break;
    }
    case VectorMathOp::kSine:
      r.vector = {std::sin(a.x), std::sin(a.y), std::sin(a.z)};
      break;
    case VectorMathOp::kCosine:
      r.vector = {std::cos(a.x), std::cos(a.y), std::cos(a.z)};
      break;
    case VectorMathOp::kTangent:
      r.vector = {std::tan(a.x), std::tan(a.y), std::tan(a.z)};
      break;
    case VectorMathOp::kCount:
      break;
  }
  return r;
}

namespace {

float smoothstep_cycles(float edge0, float edge1, float x) {
  if (x < edge0) return 0.0f;
  if (x >= edge1) return 1.0f;
  float t = (x - edge0) / (edge1 - edge0);
  return (3.0f - 2.0f * t) * (t * t);
}

float smootherstep_cycles(float edge0, float edge1, float x) {
  x = cy_clamp(safe_divide(x - edge0, edge1 - edge0), 0.0f, 1.0f);
  return x * x * x * (x * (x * 6.0f - 15.0f) + 10.0f);
}

float clamp_either_order(float v, float a, float b) {
  return a > b ? cy_clamp(v, b, a) : cy_clamp(v, a, b);
}

}  // namespace

float map_range_float(MapRangeType type, float value, float from_min, float from_max, float to_min,
                      float to_max, float steps, bool clamp) {
  float result = 0.0f;
  if (from_max != from_min) {
    float factor = value;
    switch (type) {
      case MapRangeType::kLinear:
        factor = (value - from_min) / (from_max - from_min);
        break;
      case MapRangeType::kStepped:
        factor = (value - from_min) / (from_max - from_min);
        factor = steps > 0.0f ? std::floor(factor * (steps + 1.0f)) / steps : 0.0f;
        break;
      case MapRangeType::kSmoothstep:
        factor = from_min > from_max ? 1.0f - smoothstep_cycles(from_max, from_min, factor)
                                     : smoothstep_cycles(from_min, from_max, factor);
        break;
      case MapRangeType::kSmootherstep:
        factor = from_min > from_max ? 1.0f - smootherstep_cycles(from_max, from_min, factor)
                                     : smootherstep_cycles(from_min, from_max, factor);
        break;
    }
    result = to_min + factor * (to_max - to_min);
  }
  // Cycles expands the node's clamp into a Range Clamp node after it (MapRangeNode::expand).
  return clamp ? clamp_either_order(result, to_min, to_max) : result;
}

Vec3 map_range_vector(MapRangeType type, const Vec3& value, const Vec3& from_min,
                      const Vec3& from_max, const Vec3& to_min, const Vec3& to_max,
                      const Vec3& steps, bool clamp) {
  Vec3 result;
  for (int i = 0; i < 3; ++i) {
    float factor = safe_divide(value[i] - from_min[i], from_max[i] - from_min[i]);
    switch (type) {
      case MapRangeType::kLinear:
        break;
      case MapRangeType::kStepped:
        factor = steps[i] > 0.0f ? std::floor(factor * (steps[i] + 1.0f)) / steps[i] : 0.0f;
        break;
      case MapRangeType::kSmoothstep:
        factor = cy_clamp(factor, 0.0f, 1.0f);
        factor = (3.0f - 2.0f * factor) * (factor * factor);
        break;
      case MapRangeType::kSmootherstep:
        factor = cy_clamp(factor, 0.0f, 1.0f);
        factor = factor * factor * factor * (factor * (factor * 6.0f - 15.0f) + 10.0f);
        break;
    }
    result[i] = to_min[i] + factor * (to_max[i] - to_min[i]);
    bool clamps = clamp && (type == MapRangeType::kLinear || type == MapRangeType::kStepped);
    if (clamps) result[i] = clamp_either_order(result[i], to_min[i], to_max[i]);
  }
  return result;
}

float clamp_node(ClampType type, float value, float min, float max) {
  if (type == ClampType::kRange && min > max) return cy_clamp(value, max, min);
  return cy_clamp(value, min, max);
}

Transform euler_xyz_to_transform(const Vec3& e) {
  float cx = std::cos(e.x), cy = std::cos(e.y), cz = std::cos(e.z);
  float sx = std::sin(e.x), sy = std::sin(e.y), sz = std::sin(e.z);
  // R = Rz * Ry * Rx (Blender's XYZ Euler order: X first).
  Transform t;
  t.m[0][0] = cy * cz;
  t.m[0][1] = sy * sx * cz - cx * sz;
  t.m[0][2] = sy * cx * cz + sx * sz;
  t.m[1][0] = cy * sz;
  t.m[1][1] = sy * sx * sz + cx * cz;
  t.m[1][2] = sy * cx * sz - sx * cz;
  t.m[2][0] = -sy;
  t.m[2][1] = cy * sx;
  t.m[2][2] = cy * cx;
  return t;
}

Vec3 transform_direction_transposed(const Transform& t, const Vec3& v) {
  return {t.m[0][0] * v.x + t.m[1][0] * v.y + t.m[2][0] * v.z,
          t.m[0][1] * v.x + t.m[1][1] * v.y + t.m[2][1] * v.z,
          t.m[0][2] * v.x + t.m[1][2] * v.y + t.m[2][2] * v.z};
}

Vec3 mapping(MappingType type, const Vec3& vector, const Vec3& location, const Vec3& rotation,
             const Vec3& scale) {
  Transform r = euler_xyz_to_transform(rotation);
  auto safe_div3 = [](const Vec3& a, const Vec3& b) {
    return Vec3(safe_divide(a.x, b.x), safe_divide(a.y, b.y), safe_divide(a.z, b.z));
  };
  switch (type) {
    case MappingType::kPoint:
      return r.vector(vector * scale) + location;
    case MappingType::kTexture:
      return safe_div3(transform_direction_transposed(r, vector - location), scale);
    case MappingType::kVector:
      return r.vector(vector * scale);
    case MappingType::kNormal: {
      Vec3 n = r.vector(safe_div3(vector, scale));
      float l = length(n);
      return l != 0.0f ? n * (1.0f / l) : n;
    }
  }
  return Vec3(0.0f);
}

Vec3 rotate_around_axis(const Vec3& p, const Vec3& axis, float angle) {
  float c = std::cos(angle), s = std::sin(angle), t = 1.0f - c;
  const Vec3& a = axis;
  return {
      (c + t * a.x * a.x) * p.x + (t * a.x * a.y - a.z * s) * p.y + (t * a.x * a.z + a.y * s) * p.z,
      (t * a.x * a.y + a.z * s) * p.x + (c + t * a.y * a.y) * p.y + (t * a.y * a.z - a.x * s) * p.z,
      (t * a.x * a.z - a.y * s) * p.x + (t * a.y * a.z + a.x * s) * p.y +
          (c + t * a.z * a.z) * p.z};
}

Vec3 vector_rotate(VectorRotateType type, const Vec3& vector, const Vec3& center, const Vec3& axis,
                   float angle, const Vec3& rotation, bool invert) {
  if (type == VectorRotateType::kEulerXyz) {
    Transform r = euler_xyz_to_transform(rotation);
    Vec3 d = vector - center;
    return (invert ? transform_direction_transposed(r, d) : r.vector(d)) + center;
  }
  Vec3 a = axis;
  float axis_length = 1.0f;
  switch (type) {
    case VectorRotateType::kXAxis:
      a = Vec3(1.0f, 0.0f, 0.0f);
      break;
    case VectorRotateType::kYAxis:
      a = Vec3(0.0f, 1.0f, 0.0f);
      break;
    case VectorRotateType::kZAxis:
      a = Vec3(0.0f, 0.0f, 1.0f);
      break;
    default:
      axis_length = length(axis);
      break;
  }
  if (axis_length == 0.0f) return vector;
  return rotate_around_axis(vector - center, a / axis_length, invert ? -angle : angle) + center;
}

bool invert_transform(const Transform& t, Transform* inverse) {
  float n[3][3];
  *inverse = Transform();
  if (!t.normal_matrix(n)) return false;
  // normal_matrix is the inverse transpose; the inverse's 3x3 part is its transpose.
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) inverse->m[r][c] = n[c][r];
  Vec3 offset = inverse->vector(t.column(3));
  inverse->m[0][3] = -offset.x;
  inverse->m[1][3] = -offset.y;
  inverse->m[2][3] = -offset.z;
  return true;
}

}  // namespace photon
