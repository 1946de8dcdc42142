// The scalar and vector functions behind Blender's Math, Vector Math, Map Range, Clamp,
// Mapping and Vector Rotate nodes, with the guards Cycles 3.4 applies (division by zero gives 0,
// roots and logarithms of out-of-domain values give 0, ...), so a procedural material evaluates
// to the same numbers in Photon as in Cycles' SVM (intern/cycles/kernel/svm/math_util.h,
// util/math.h, util/math_float3.h, util/transform.h).
#pragma once

#include <cstdint>

#include "photon/base/math.h"

namespace photon {

// Operations in the order of Blender 3.4's ShaderNodeMath.operation enum.
enum class MathOp : uint32_t {
  kAdd,
  kSubtract,
  kMultiply,
  kDivide,
  kMultiplyAdd,
  kPower,
  kLogarithm,
  kSqrt,
  kInverseSqrt,
  kAbsolute,
  kExponent,
  kMinimum,
  kMaximum,
  kLessThan,
  kGreaterThan,
  kSign,
  kCompare,
  kSmoothMin,
  kSmoothMax,
  kRound,
  kFloor,
  kCeil,
  kTrunc,
  kFract,
  kModulo,
  kWrap,
  kSnap,
  kPingpong,
  kSine,
  kCosine,
  kTangent,
  kArcsine,
  kArccosine,
  kArctangent,
  kArctan2,
  kSinh,
  kCosh,
  kTanh,
  kRadians,
  kDegrees,
  kFlooredModulo,  // Blender 4.x (after MODULO in its enum; here last, as ops match by name)
  kCount,
};

// Operations in the order of Blender 3.4's ShaderNodeVectorMath.operation enum.
enum class VectorMathOp : uint32_t {
  kAdd,
  kSubtract,
  kMultiply,
  kDivide,
  kMultiplyAdd,
  kCrossProduct,
  kProject,
  kReflect,
  kRefract,
  kFaceforward,
  kDotProduct,
  kDistance,
  kLength,
  kScale,
  kNormalize,
  kAbsolute,
  kMinimum,
  kMaximum,
  kFloor,
  kCeil,
  kFraction,
  kModulo,
  kWrap,
  kSnap,
  kSine,
  kCosine,
  kTangent,
  kCount,
};

// Whether an operation's result is the Value output (dot, distance, length) rather than Vector.
bool vector_math_op_is_value(VectorMathOp op);

// Cycles' ternary min/max/clamp (NaN in `a` falls to the bound, unlike std::clamp's UB).
inline float cy_min(float a, float b) {
  return a < b ? a : b;
}
inline float cy_max(float a, float b) {
  return a > b ? a : b;
}
inline float cy_clamp(float a, float lo, float hi) {
  return cy_min(cy_max(a, lo), hi);
}

float safe_divide(float a, float b);
float safe_modulo(float a, float b);
float safe_powf(float a, float b);
float safe_logf(float a, float b);
float safe_sqrtf(float a);
float inverse_sqrtf(float a);
float compatible_signf(float a);
// wrapf(value, max, min): `value` wrapped into [min, max) (Godot's Math::wrapf).
float wrapf(float value, float max, float min);
float pingpongf(float a, float b);
// Polynomial smooth minimum with blend width k (Quilez, "smooth minimum", cubic variant).
float smoothminf(float a, float b, float k);

float eval_math(MathOp op, float a, float b, float c);

struct VectorMathResult {
  Vec3 vector{0.0f};
  float value = 0.0f;
};
VectorMathResult eval_vector_math(VectorMathOp op, const Vec3& a, const Vec3& b, const Vec3& c,
                                  float scale);

enum class MapRangeType : uint32_t { kLinear, kStepped, kSmoothstep, kSmootherstep };
// The Float Map Range (svm_node_map_range); `clamp` clamps the result to [To Min, To Max] in
// either order, the Range clamp Cycles inserts after the node.
float map_range_float(MapRangeType type, float value, float from_min, float from_max, float to_min,
                      float to_max, float steps, bool clamp);
// The Vector Map Range (svm_node_vector_map_range): per component, zero-width ranges give
// To Min, and the clamp applies to Linear and Stepped only.
Vec3 map_range_vector(MapRangeType type, const Vec3& value, const Vec3& from_min,
                      const Vec3& from_max, const Vec3& to_min, const Vec3& to_max,
                      const Vec3& steps, bool clamp);

enum class ClampType : uint32_t { kMinMax, kRange };
float clamp_node(ClampType type, float value, float min, float max);

// Blender's Euler XYZ rotation (X applied first) as a 3x3 matrix in a Transform.
Transform euler_xyz_to_transform(const Vec3& euler);
Vec3 transform_direction_transposed(const Transform& t, const Vec3& v);

enum class MappingType : uint32_t { kPoint, kTexture, kVector, kNormal };
Vec3 mapping(MappingType type, const Vec3& vector, const Vec3& location, const Vec3& rotation,
             const Vec3& scale);

enum class VectorRotateType : uint32_t { kAxisAngle, kXAxis, kYAxis, kZAxis, kEulerXyz };
Vec3 vector_rotate(VectorRotateType type, const Vec3& vector, const Vec3& center, const Vec3& axis,
                   float angle, const Vec3& rotation, bool invert);

// Rodrigues' rotation of p about the unit axis by angle (right-handed).
Vec3 rotate_around_axis(const Vec3& p, const Vec3& axis, float angle);

// Inverse of an affine transform; false (and identity) when the 3x3 part is singular.
bool invert_transform(const Transform& t, Transform* inverse);

}  // namespace photon
