#include "photon/scene/shader_program.h"

namespace photon {

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

}  // namespace photon
