#include "photon/shading/math_nodes.h"

#include <cmath>
#include <iterator>

#include "photon/shading/node_math.h"

namespace photon {

namespace {

// Enum identifiers in Blender 3.4's order, then those Blender 4.x added; the index is the
// operation's value.
const char* const kMathOps[] = {
    "ADD",        "SUBTRACT",  "MULTIPLY",     "DIVIDE",     "MULTIPLY_ADD",  "POWER",
    "LOGARITHM",  "SQRT",      "INVERSE_SQRT", "ABSOLUTE",   "EXPONENT",      "MINIMUM",
    "MAXIMUM",    "LESS_THAN", "GREATER_THAN", "SIGN",       "COMPARE",       "SMOOTH_MIN",
    "SMOOTH_MAX", "ROUND",     "FLOOR",        "CEIL",       "TRUNC",         "FRACT",
    "MODULO",     "WRAP",      "SNAP",         "PINGPONG",   "SINE",          "COSINE",
    "TANGENT",    "ARCSINE",   "ARCCOSINE",    "ARCTANGENT", "ARCTAN2",       "SINH",
    "COSH",       "TANH",      "RADIANS",      "DEGREES",    "FLOORED_MODULO"};
static_assert(std::size(kMathOps) == static_cast<size_t>(MathOp::kCount));

const char* const kVectorMathOps[] = {
    "ADD",     "SUBTRACT", "MULTIPLY",  "DIVIDE",      "MULTIPLY_ADD", "CROSS_PRODUCT",
    "PROJECT", "REFLECT",  "REFRACT",   "FACEFORWARD", "DOT_PRODUCT",  "DISTANCE",
    "LENGTH",  "SCALE",    "NORMALIZE", "ABSOLUTE",    "MINIMUM",      "MAXIMUM",
    "FLOOR",   "CEIL",     "FRACTION",  "MODULO",      "WRAP",         "SNAP",
    "SINE",    "COSINE",   "TANGENT"};
static_assert(std::size(kVectorMathOps) == static_cast<size_t>(VectorMathOp::kCount));

const char* const kMapRangeTypes[] = {"LINEAR", "STEPPED", "SMOOTHSTEP", "SMOOTHERSTEP"};
const char* const kClampTypes[] = {"MINMAX", "RANGE"};
const char* const kMappingTypes[] = {"POINT", "TEXTURE", "VECTOR", "NORMAL"};
const char* const kRotateTypes[] = {"AXIS_ANGLE", "X_AXIS", "Y_AXIS", "Z_AXIS", "EULER_XYZ"};
const char* const kTransformTypes[] = {"POINT", "VECTOR", "NORMAL"};
const char* const kSpaces[] = {"WORLD", "OBJECT", "CAMERA"};

template <size_t N>
bool lookup_enum(const NodeDesc& desc, const char* property, const char* fallback,
                 const char* const (&names)[N], uint32_t* value, std::string* error) {
  std::string name = enum_value(desc, property, fallback);
  for (size_t i = 0; i < N; ++i) {
    if (name == names[i]) {
      *value = static_cast<uint32_t>(i);
      return true;
    }
  }
  if (error) *error = desc.type + ": unknown " + property + " '" + name + "'";
  return false;
}

bool flag(const NodeDesc& desc, const char* property, bool fallback) {
  auto it = desc.enums.find(property);
  if (it == desc.enums.end()) return fallback;
  return it->second == "True" || it->second == "true" || it->second == "1";
}

// The register of an input; an input the add-on did not send reads Blender's default value from
// a constant register appended to the program.
int32_t input_or_default(const NodeDesc& desc, const char* identifier, ShaderProgram* program,
                         Vec3 fallback, int size) {
  int32_t r = input_register(desc, identifier);
  if (r >= 0) return r;
  r = static_cast<int32_t>(program->registers.size());
  for (int i = 0; i < size; ++i) program->registers.push_back(fallback[i]);
  return r;
}
int32_t input_float(const NodeDesc& desc, const char* id, ShaderProgram* p, float fallback) {
  return input_or_default(desc, id, p, Vec3(fallback), 1);
}
int32_t input_vec(const NodeDesc& desc, const char* id, ShaderProgram* p, Vec3 fallback) {
  return input_or_default(desc, id, p, fallback, 3);
}

// Normalisation that leaves a zero vector zero (Cycles' normalize would make it NaN).
Vec3 normalize_keep_zero(const Vec3& v) {
  float l = length(v);
  return l != 0.0f ? v / l : v;
}

}  // namespace

Vec3 vector_transform(VectorTransformType type, VectorTransformSpace from, VectorTransformSpace to,
                      const Vec3& v, const ShaderGlobals& g) {
  // Cycles 3.4's svm_node_vector_transform: through world space, a Normal is carried like a
  // Vector (the direction part of each transform, not its inverse transpose) and normalised at
  // the end. Without an object (the world shader) object space is world space.
  using S = VectorTransformSpace;
  const bool is_point = type == VectorTransformType::kPoint;
  const bool is_object = !g.is_background;
  auto apply = [&](const Transform& to_space, const Vec3& x) {
    return is_point ? to_space.point(x) : to_space.vector(x);
  };
  auto inverse_of = [](const Transform& t) {
    Transform inv;
    invert_transform(t, &inv);
    return inv;
  };
  Vec3 out = v;
  if (from == S::kWorld) {
    if (to == S::kCamera)
      out = apply(g.world_to_camera, out);
    else if (to == S::kObject && is_object)
      out = apply(g.world_to_object, out);
  } else if (from == S::kCamera) {
    if (to == S::kWorld || to == S::kObject) out = apply(inverse_of(g.world_to_camera), out);
    if (to == S::kObject && is_object) out = apply(g.world_to_object, out);
  } else {  // from object
    if ((to == S::kWorld || to == S::kCamera) && is_object)
      out = apply(inverse_of(g.world_to_object), out);
    if (to == S::kCamera) out = apply(g.world_to_camera, out);
  }
  return type == VectorTransformType::kNormal ? normalize_keep_zero(out) : out;
}

namespace {

// Cycles 4.x's svm_node_vector_transform of a Normal: each step carries it by the inverse
// transpose of that step's transform and normalises it there; world to world (or camera to
// camera, object to object) leaves it as it is.
Vec3 vector_transform_normal_4x(VectorTransformSpace from, VectorTransformSpace to, const Vec3& v,
                                const ShaderGlobals& g) {
  using S = VectorTransformSpace;
  const bool is_object = !g.is_background;
  auto carry = [](const Transform& t, const Vec3& x) {
    float m[3][3];
    if (!t.normal_matrix(m)) return Vec3(0.0f);
    return normalize_keep_zero(Vec3(m[0][0] * x.x + m[0][1] * x.y + m[0][2] * x.z,
                                    m[1][0] * x.x + m[1][1] * x.y + m[1][2] * x.z,
                                    m[2][0] * x.x + m[2][1] * x.y + m[2][2] * x.z));
  };
  auto inverse_of = [](const Transform& t) {
    Transform inv;
    invert_transform(t, &inv);
    return inv;
  };
  Vec3 out = v;
  if (from == S::kWorld) {
    if (to == S::kCamera)
      out = carry(g.world_to_camera, out);
    else if (to == S::kObject && is_object)
      out = carry(g.world_to_object, out);
  } else if (from == S::kCamera) {
    if (to == S::kWorld || to == S::kObject) out = carry(inverse_of(g.world_to_camera), out);
    if (to == S::kObject && is_object) out = carry(g.world_to_object, out);
  } else {  // from object
    if ((to == S::kWorld || to == S::kCamera) && is_object)
      out = carry(inverse_of(g.world_to_object), out);
    if (to == S::kCamera) out = carry(g.world_to_camera, out);
  }
  return out;
}

}  // namespace

CompileStatus compile_math_node(const NodeDesc& desc, ShaderProgram* program, Instruction* out,
                                std::string* error) {
  Instruction ins;
  ins.family = NodeFamily::kMath;
  const std::string& t = desc.type;
  ShaderProgram* p = program;
  if (t == "ShaderNodeMath") {
    ins.kind = static_cast<uint16_t>(MathNodeKind::kMath);
    if (!lookup_enum(desc, "operation", "ADD", kMathOps, &ins.mode, error))
      return CompileStatus::kError;
    ins.in[0] = input_float(desc, "Value", p, 0.5f);
    ins.in[1] = input_float(desc, "Value_001", p, 0.5f);
    ins.in[2] = input_float(desc, "Value_002", p, 0.5f);
    ins.out[0] = output_register(desc, "Value");
    ins.param[0] = flag(desc, "use_clamp", false) ? 1.0f : 0.0f;
  } else if (t == "ShaderNodeVectorMath") {
    ins.kind = static_cast<uint16_t>(MathNodeKind::kVectorMath);
    if (!lookup_enum(desc, "operation", "ADD", kVectorMathOps, &ins.mode, error))
      return CompileStatus::kError;
    ins.in[0] = input_vec(desc, "Vector", p, Vec3(0.0f));
    ins.in[1] = input_vec(desc, "Vector_001", p, Vec3(0.0f));
    ins.in[2] = input_vec(desc, "Vector_002", p, Vec3(0.0f));
    ins.in[3] = input_float(desc, "Scale", p, 1.0f);
    ins.out[0] = output_register(desc, "Vector");
    ins.out[1] = output_register(desc, "Value");
  } else if (t == "ShaderNodeMapRange") {
    uint32_t data_type = 0;
    const char* const kDataTypes[] = {"FLOAT", "FLOAT_VECTOR"};
    if (!lookup_enum(desc, "data_type", "FLOAT", kDataTypes, &data_type, error) ||
        !lookup_enum(desc, "interpolation_type", "LINEAR", kMapRangeTypes, &ins.mode, error))
      return CompileStatus::kError;
    ins.param[0] = flag(desc, "clamp", true) ? 1.0f : 0.0f;
    if (data_type == 0) {
      ins.kind = static_cast<uint16_t>(MathNodeKind::kMapRange);
      ins.in[0] = input_float(desc, "Value", p, 1.0f);
      ins.in[1] = input_float(desc, "From Min", p, 0.0f);
      ins.in[2] = input_float(desc, "From Max", p, 1.0f);
      ins.in[3] = input_float(desc, "To Min", p, 0.0f);
      ins.in[4] = input_float(desc, "To Max", p, 1.0f);
      ins.in[5] = input_float(desc, "Steps", p, 4.0f);
      ins.out[0] = output_register(desc, "Result");
    } else {
      ins.kind = static_cast<uint16_t>(MathNodeKind::kVectorMapRange);
      ins.in[0] = input_vec(desc, "Vector", p, Vec3(0.0f));
      ins.in[1] = input_vec(desc, "From_Min_FLOAT3", p, Vec3(0.0f));
      ins.in[2] = input_vec(desc, "From_Max_FLOAT3", p, Vec3(1.0f));
      ins.in[3] = input_vec(desc, "To_Min_FLOAT3", p, Vec3(0.0f));
      ins.in[4] = input_vec(desc, "To_Max_FLOAT3", p, Vec3(1.0f));
      ins.in[5] = input_vec(desc, "Steps_FLOAT3", p, Vec3(4.0f));
      ins.out[0] = output_register(desc, "Vector");
    }
  } else if (t == "ShaderNodeClamp") {
    ins.kind = static_cast<uint16_t>(MathNodeKind::kClamp);
    if (!lookup_enum(desc, "clamp_type", "MINMAX", kClampTypes, &ins.mode, error))
      return CompileStatus::kError;
    ins.in[0] = input_float(desc, "Value", p, 1.0f);
    ins.in[1] = input_float(desc, "Min", p, 0.0f);
    ins.in[2] = input_float(desc, "Max", p, 1.0f);
    ins.out[0] = output_register(desc, "Result");
  } else if (t == "ShaderNodeMapping") {
    ins.kind = static_cast<uint16_t>(MathNodeKind::kMapping);
    if (!lookup_enum(desc, "vector_type", "POINT", kMappingTypes, &ins.mode, error))
      return CompileStatus::kError;
    ins.in[0] = input_vec(desc, "Vector", p, Vec3(0.0f));
    ins.in[1] = input_vec(desc, "Location", p, Vec3(0.0f));
    ins.in[2] = input_vec(desc, "Rotation", p, Vec3(0.0f));
    ins.in[3] = input_vec(desc, "Scale", p, Vec3(1.0f));
    ins.out[0] = output_register(desc, "Vector");
  } else if (t == "ShaderNodeVectorRotate") {
    ins.kind = static_cast<uint16_t>(MathNodeKind::kVectorRotate);
    if (!lookup_enum(desc, "rotation_type", "AXIS_ANGLE", kRotateTypes, &ins.mode, error))
      return CompileStatus::kError;
    ins.in[0] = input_vec(desc, "Vector", p, Vec3(0.0f));
    ins.in[1] = input_vec(desc, "Center", p, Vec3(0.0f));
    ins.in[2] = input_vec(desc, "Axis", p, Vec3(0.0f, 0.0f, 1.0f));
    ins.in[3] = input_float(desc, "Angle", p, 0.0f);
    ins.in[4] = input_vec(desc, "Rotation", p, Vec3(0.0f));
    ins.out[0] = output_register(desc, "Vector");
    ins.param[0] = flag(desc, "invert", false) ? 1.0f : 0.0f;
  } else if (t == "ShaderNodeVectorTransform") {
    ins.kind = static_cast<uint16_t>(MathNodeKind::kVectorTransform);
    uint32_t type = 0, from = 0, to = 0;
    if (!lookup_enum(desc, "vector_type", "VECTOR", kTransformTypes, &type, error) ||
        !lookup_enum(desc, "convert_from", "WORLD", kSpaces, &from, error) ||
        !lookup_enum(desc, "convert_to", "OBJECT", kSpaces, &to, error))
      return CompileStatus::kError;
    ins.mode = type | from << 4 | to << 8;
    // Blender 4.x (the add-on's enum "photon_cycles"): normals by the inverse transpose.
    ins.param[0] = enum_value(desc, "photon_cycles", "3") >= "4" ? 1.0f : 0.0f;
    ins.in[0] = input_vec(desc, "Vector", p, Vec3(0.5f));
    ins.out[0] = output_register(desc, "Vector");
  } else if (t == "ShaderNodeNormal") {
    ins.kind = static_cast<uint16_t>(MathNodeKind::kNormal);
    ins.in[0] = input_vec(desc, "Normal", p, Vec3(0.0f, 0.0f, 1.0f));
    ins.in[1] = input_vec(desc, "Normal_const", p, Vec3(0.0f, 0.0f, 1.0f));
    ins.out[0] = output_register(desc, "Normal");
    ins.out[1] = output_register(desc, "Dot");
  } else {
    return CompileStatus::kUnknownNode;
  }
  *out = ins;
  return CompileStatus::kCompiled;
}

void eval_math_node(const Instruction& ins, const ShaderProgram& /*program*/,
                    const ShaderGlobals& globals, float* r) {
  switch (static_cast<MathNodeKind>(ins.kind)) {
    case MathNodeKind::kMath: {
      float v = eval_math(static_cast<MathOp>(ins.mode), load1(r, ins.in[0]), load1(r, ins.in[1]),
                          load1(r, ins.in[2]));
      // use_clamp: Cycles appends a Min Max Clamp node to [0, 1] (MathNode::expand).
      if (ins.param[0] != 0.0f) v = cy_clamp(v, 0.0f, 1.0f);
      store1(r, ins.out[0], v);
      break;
    }
    case MathNodeKind::kVectorMath: {
      VectorMathResult v =
          eval_vector_math(static_cast<VectorMathOp>(ins.mode), load3(r, ins.in[0]),
                           load3(r, ins.in[1]), load3(r, ins.in[2]), load1(r, ins.in[3]));
      store3(r, ins.out[0], v.vector);
      store1(r, ins.out[1], v.value);
      break;
    }
    case MathNodeKind::kMapRange:
      store1(r, ins.out[0],
             map_range_float(static_cast<MapRangeType>(ins.mode), load1(r, ins.in[0]),
                             load1(r, ins.in[1]), load1(r, ins.in[2]), load1(r, ins.in[3]),
                             load1(r, ins.in[4]), load1(r, ins.in[5]), ins.param[0] != 0.0f));
      break;
    case MathNodeKind::kVectorMapRange:
      store3(r, ins.out[0],
             map_range_vector(static_cast<MapRangeType>(ins.mode), load3(r, ins.in[0]),
                              load3(r, ins.in[1]), load3(r, ins.in[2]), load3(r, ins.in[3]),
                              load3(r, ins.in[4]), load3(r, ins.in[5]), ins.param[0] != 0.0f));
      break;
    case MathNodeKind::kClamp:
      store1(r, ins.out[0],
             clamp_node(static_cast<ClampType>(ins.mode), load1(r, ins.in[0]), load1(r, ins.in[1]),
                        load1(r, ins.in[2])));
      break;
    case MathNodeKind::kMapping:
      store3(r, ins.out[0],
             mapping(static_cast<MappingType>(ins.mode), load3(r, ins.in[0]), load3(r, ins.in[1]),
                     load3(r, ins.in[2]), load3(r, ins.in[3])));
      break;
    case MathNodeKind::kVectorRotate:
      store3(r, ins.out[0],
             vector_rotate(static_cast<VectorRotateType>(ins.mode), load3(r, ins.in[0]),
                           load3(r, ins.in[1]), load3(r, ins.in[2]), load1(r, ins.in[3]),
                           load3(r, ins.in[4]), ins.param[0] != 0.0f));
      break;
    case MathNodeKind::kVectorTransform:
      if (ins.param[0] != 0.0f &&
          (ins.mode & 0xFu) == static_cast<uint32_t>(VectorTransformType::kNormal)) {
        store3(r, ins.out[0],
               vector_transform_normal_4x(static_cast<VectorTransformSpace>((ins.mode >> 4) & 0xFu),
                                          static_cast<VectorTransformSpace>((ins.mode >> 8) & 0xFu),
                                          load3(r, ins.in[0]), globals));
        break;
      }
      store3(r, ins.out[0],
             vector_transform(static_cast<VectorTransformType>(ins.mode & 0xFu),
                              static_cast<VectorTransformSpace>((ins.mode >> 4) & 0xFu),
                              static_cast<VectorTransformSpace>((ins.mode >> 8) & 0xFu),
                              load3(r, ins.in[0]), globals));
      break;
    case MathNodeKind::kNormal: {
      // The output socket's direction (normalised) and its dot with the normalised input.
      Vec3 direction = normalize_keep_zero(load3(r, ins.in[1]));
      store3(r, ins.out[0], direction);
      store1(r, ins.out[1], dot(direction, normalize_keep_zero(load3(r, ins.in[0]))));
      break;
    }
  }
}

}  // namespace photon
