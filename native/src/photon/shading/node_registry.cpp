#include "photon/shading/node_registry.h"

#include "photon/shading/attribute_nodes.h"
#include "photon/shading/color_nodes.h"
#include "photon/shading/image_nodes.h"
#include "photon/shading/input_nodes.h"
#include "photon/shading/math_nodes.h"
#include "photon/shading/noise_nodes.h"
#include "photon/shading/normal_nodes.h"
#include "photon/shading/pattern_nodes.h"
#include "photon/shading/voronoi_nodes.h"

namespace photon {

const std::vector<NodeFamilyEntry>& node_families() {
  static const std::vector<NodeFamilyEntry> families = {
      // First: it claims UV Map nodes that name their map (input nodes read the active one).
      {NodeFamily::kAttribute, compile_attribute_node, eval_attribute_node},
      {NodeFamily::kInput, compile_input_node, eval_input_node},
      {NodeFamily::kConvert, compile_convert_node, eval_convert_node},
      {NodeFamily::kMath, compile_math_node, eval_math_node},
      {NodeFamily::kNoise, compile_noise_node, eval_noise_node},
      {NodeFamily::kColor, compile_color_node, eval_color_node},
      {NodeFamily::kPattern, compile_pattern_node, eval_pattern_node},
      {NodeFamily::kVoronoi, compile_voronoi_node, eval_voronoi_node},
      {NodeFamily::kImage, compile_image_node, eval_image_node},
      {NodeFamily::kNormal, compile_normal_node, eval_normal_node},
  };
  return families;
}

namespace {
void eval_nothing(const Instruction&, const ShaderProgram&, const ShaderGlobals&, float*) {}
}  // namespace

const std::array<EvalNodeFn, static_cast<size_t>(NodeFamily::kCount)>& node_evaluators() {
  static const auto table = [] {
    std::array<EvalNodeFn, static_cast<size_t>(NodeFamily::kCount)> t;
    t.fill(eval_nothing);
    for (const NodeFamilyEntry& f : node_families()) t[static_cast<size_t>(f.family)] = f.eval;
    return t;
  }();
  return table;
}

void run_block(const ShaderProgram& program, size_t begin, size_t end, const ShaderGlobals& globals,
               float* registers) {
  const auto& families = node_evaluators();
  for (size_t i = begin; i < end; ++i) {
    const Instruction& ins = program.code[i];
    families[static_cast<size_t>(ins.family)](ins, program, globals, registers);
  }
}

}  // namespace photon
