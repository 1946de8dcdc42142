// Node family kMath: Math, Vector Math, Map Range, Clamp, Mapping, Vector Rotate, Vector
// Transform and Normal, compiled from the add-on's NodeDesc into instructions and evaluated as
// Cycles 3.4's SVM evaluates them (the pure functions are in shading/node_math.h).
#pragma once

#include <string>

#include "photon/shading/program.h"

namespace photon {

// Instruction::kind within NodeFamily::kMath.
enum class MathNodeKind : uint16_t {
  kMath,
  kVectorMath,
  kMapRange,        // data_type FLOAT
  kVectorMapRange,  // data_type FLOAT_VECTOR
  kClamp,
  kMapping,
  kVectorRotate,
  kVectorTransform,
  kNormal,
};

CompileStatus compile_math_node(const NodeDesc& desc, ShaderProgram* program, Instruction* out,
                                std::string* error);
void eval_math_node(const Instruction& ins, const ShaderProgram& program,
                    const ShaderGlobals& globals, float* registers);

// Vector Transform's vector_type and spaces, packed into Instruction::mode as
// type | from << 4 | to << 8.
enum class VectorTransformType : uint32_t { kPoint, kVector, kNormal };
enum class VectorTransformSpace : uint32_t { kWorld, kObject, kCamera };
Vec3 vector_transform(VectorTransformType type, VectorTransformSpace from, VectorTransformSpace to,
                      const Vec3& v, const ShaderGlobals& globals);

}  // namespace photon
