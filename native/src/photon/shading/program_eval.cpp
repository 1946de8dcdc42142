#include "photon/shading/program_eval.h"

#include <algorithm>
#include <cstring>

#include "photon/shading/node_registry.h"

namespace photon {

ProgramRegisters::ProgramRegisters(const ShaderProgram& program) {
  const size_t n = program.registers.size();
  if (n > kStack) {
    heap_ = program.registers;
  } else if (n > 0) {
    std::memcpy(stack_, program.registers.data(), n * sizeof(float));
  }
}

CompileStatus compile_node(const NodeDesc& desc, ShaderProgram* program, std::string* error) {
  for (const NodeFamilyEntry& family : node_families()) {
    Instruction ins;
    const CompileStatus status = family.compile(desc, program, &ins, error);
    if (status == CompileStatus::kUnknownNode) continue;
    if (status == CompileStatus::kCompiled) program->code.push_back(ins);
    return status;
  }
  return CompileStatus::kUnknownNode;
}

void run_program(const ShaderProgram& program, const ShaderGlobals& globals, float* registers) {
  const auto& families = node_evaluators();
  const Instruction* code = program.code.data();
  const size_t n = program.code.size();
  for (size_t i = 0; i < n; ++i) {
    const Instruction& ins = code[i];
    families[static_cast<size_t>(ins.family)](ins, program, globals, registers);
  }
}

}  // namespace photon
