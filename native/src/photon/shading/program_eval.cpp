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

bool validate_program(const ShaderProgram& program, std::string* error) {
  const int64_t count = static_cast<int64_t>(program.registers.size());
  // Any register may be read as a vector: three floats must fit.
  auto fits = [&](int32_t r) { return r < 0 || static_cast<int64_t>(r) + 3 <= count; };
  for (size_t i = 0; i < program.code.size(); ++i) {
    const Instruction& ins = program.code[i];
    if (static_cast<size_t>(ins.family) >= static_cast<size_t>(NodeFamily::kCount)) {
      *error = "instruction " + std::to_string(i) + " has an unknown node family";
      return false;
    }
    for (int32_t r : ins.in)
      if (!fits(r)) {
        *error = "instruction " + std::to_string(i) + " reads a register outside the program";
        return false;
      }
    for (int32_t r : ins.out)
      if (!fits(r)) {
        *error = "instruction " + std::to_string(i) + " writes a register outside the program";
        return false;
      }
    if (ins.data >= 0 && (ins.data_size < 0 || static_cast<int64_t>(ins.data) + ins.data_size >
                                                   static_cast<int64_t>(program.data.size()))) {
      *error = "instruction " + std::to_string(i) + " reads a table outside the program";
      return false;
    }
    if (ins.skip < 0 || static_cast<size_t>(ins.skip) > i) {
      *error = "instruction " + std::to_string(i) + " re-runs code outside the program";
      return false;
    }
  }
  return true;
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
