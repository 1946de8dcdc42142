// Compiling node descriptions into a ShaderProgram and running it at a shading point.
#pragma once

#include <string>
#include <vector>

#include "photon/shading/program.h"

namespace photon {

// Appends the instruction for `desc` to `program` through the node family that knows its type.
// kUnknownNode when no family does; kError with `error` set when the node cannot be compiled.
CompileStatus compile_node(const NodeDesc& desc, ShaderProgram* program, std::string* error);

// Registers large enough for most programs live on the stack; bigger ones on the heap.
class ProgramRegisters {
 public:
  explicit ProgramRegisters(const ShaderProgram& program);
  float* data() { return heap_.empty() ? stack_ : heap_.data(); }

 private:
  static constexpr size_t kStack = 512;
  float stack_[kStack];
  std::vector<float> heap_;
};

// Runs the program: `registers` holds its initial values (ProgramRegisters) and afterwards every
// node's outputs.
void run_program(const ShaderProgram& program, const ShaderGlobals& globals, float* registers);

}  // namespace photon
