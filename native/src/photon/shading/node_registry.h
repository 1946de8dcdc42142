// The node families a shader program is made of: their compile and evaluate functions, in one
// table (node_registry.cpp) so a new family is one line there.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "photon/shading/program.h"

namespace photon {

using CompileNodeFn = CompileStatus (*)(const NodeDesc&, ShaderProgram*, Instruction*,
                                        std::string*);
using EvalNodeFn = void (*)(const Instruction&, const ShaderProgram&, const ShaderGlobals&, float*);

struct NodeFamilyEntry {
  NodeFamily family;
  CompileNodeFn compile;
  EvalNodeFn eval;
};

const std::vector<NodeFamilyEntry>& node_families();
// Evaluators indexed by NodeFamily (families not linked in evaluate to nothing).
const std::array<EvalNodeFn, static_cast<size_t>(NodeFamily::kCount)>& node_evaluators();

// The evaluator of a Bump instruction re-runs the code of its height block (program_eval.cpp).
void run_block(const ShaderProgram& program, size_t begin, size_t end, const ShaderGlobals& globals,
               float* registers);

}  // namespace photon
