// Conformance of the colour node family with Cycles 3.4: every case of
// test_scenes/nodes/color.json is compiled from its NodeDesc and evaluated at each pixel's
// Object coordinate (coords.exr), and compared with Cycles' render of the same node
// (test_scenes/nodes/color/<case>.exr, made by tools/node_refs.py).
#include "photon/shading/color_nodes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <set>

#include "photon/shading/color_math.h"
#include "photon/testing/node_references.h"

namespace photon {
namespace color_nodes_test {
namespace {

// ---- From a manifest case (Blender socket names) to a NodeDesc (socket identifiers) ----
const std::set<std::string> kVectorSockets = {
    "Factor_Vector", "A_Vector", "B_Vector", "A_Color", "B_Color", "Result_Vector",
    "Result_Color",  "Color1",   "Color2",   "Color",   "Image",   "Vector"};

bool is_vector_socket(const std::string& id) {
  return kVectorSockets.count(id) > 0;
}

std::string prop(const Json& c, const char* name, const char* fallback) {
  const Json* props = c.find("properties");
  const Json* v = props ? props->find(name) : nullptr;
  return v && v->kind == Json::kString ? v->string : fallback;
}

// The Mix node repeats names across data types ("A" is A_Float, A_Vector or A_Color).
std::string identifier(const Json& c, const std::string& name) {
  const std::string& node = c.find("node")->string;
  if (node != "ShaderNodeMix") return name;
  const std::string data_type = prop(c, "data_type", "FLOAT");
  const std::string suffix = data_type == "RGBA"     ? "_Color"
                             : data_type == "VECTOR" ? "_Vector"
                                                     : "_Float";
  if (name == "Factor") {
    const bool per_axis =
        data_type == "VECTOR" && prop(c, "factor_mode", "UNIFORM") == "NON_UNIFORM";
    return per_axis ? "Factor_Vector" : "Factor_Float";
  }
  return name + suffix;
}

struct Case {
  std::string name;
  NodeDesc desc;
  ShaderProgram program;
  Instruction ins;
  int32_t linked = -1;  // register fed the Object coordinate (-1: none)
  bool linked_vector = false;
  int32_t output = -1;
  bool output_vector = false;
};

int32_t add_registers(ShaderProgram* program, const std::vector<float>& values) {
  const auto first = static_cast<int32_t>(program->registers.size());
  program->registers.insert(program->registers.end(), values.begin(), values.end());
  return first;
}

std::string build_case(const Json& c, Case* out) {
  out->name = c.find("name")->string;
  NodeDesc& desc = out->desc;
  desc.type = c.find("node")->string;
  if (const Json* props = c.find("properties")) {
    for (const auto& [key, v] : props->object) {
      if (v.kind == Json::kString) desc.enums[key] = v.string;
      if (v.kind == Json::kBool) desc.enums[key] = v.boolean ? "True" : "False";
      if (v.kind == Json::kNumber) desc.numbers[key] = v.number;
    }
  }
  if (const Json* inputs = c.find("inputs")) {
    for (const auto& [name, v] : inputs->object) {
      const std::string id = identifier(c, name);
      std::vector<float> values;
      if (v.kind == Json::kNumber) {
        values.push_back(static_cast<float>(v.number));
      } else {
        for (size_t i = 0; i < 3; ++i) values.push_back(static_cast<float>(v.array[i].number));
      }
      desc.inputs[id] = add_registers(&out->program, values);
    }
  }
  const Json* vector = c.find("vector");
  if (vector && vector->kind == Json::kString) {
    const std::string id = identifier(c, vector->string);
    out->linked_vector = is_vector_socket(id);
    out->linked = add_registers(&out->program, {0.0f, 0.0f, 0.0f});
    desc.inputs[id] = out->linked;
  }
  const std::string output_id = identifier(c, c.find("output")->string);
  out->output_vector = is_vector_socket(output_id);
  out->output = add_registers(&out->program, {0.0f, 0.0f, 0.0f});
  desc.outputs[output_id] = out->output;
  if (const Json* table = c.find("table")) {
    for (const Json& v : table->array) desc.table.push_back(static_cast<float>(v.number));
  }
  std::string error;
  const CompileStatus status = compile_color_node(desc, &out->program, &out->ins, &error);
  if (status == CompileStatus::kUnknownNode) return "not a colour node";
  if (status == CompileStatus::kError) return error;
  return {};
}

// Evaluates a case where Cycles shaded pixel `p` (Object coordinate) and returns what the
// Emission shader shows (a float output is grey).
Vec3 evaluate(const Case& c, const Vec3& p) {
  std::vector<float> registers = c.program.registers;
  if (c.linked >= 0) {
    // Implicit socket conversion, as Cycles: vector to float is the component average.
    if (c.linked_vector) {
      store3(registers.data(), c.linked, p);
    } else {
      registers[c.linked] = (p.x + p.y + p.z) * (1.0f / 3.0f);
    }
  }
  eval_color_node(c.ins, c.program, ShaderGlobals{}, registers.data());
  return c.output_vector ? load3(registers.data(), c.output) : Vec3(registers[c.output]);
}

struct Manifest {
  std::filesystem::path dir;
  Json cases;
  RgbImage coords;
};

const Manifest& manifest() {
  static const std::unique_ptr<Manifest> loaded = [] {
    auto m = std::make_unique<Manifest>();
    const auto nodes = node_refs_dir();
    if (nodes.empty()) return m;
    m->dir = nodes / "color";
    m->cases = *read_json(nodes / "color.json").find("cases");
    read_rgb_exr(m->dir / "coords.exr", &m->coords);
    return m;
  }();
  return *loaded;
}

constexpr float kTolerance = 1e-4f;  // relative above 1, absolute below

TEST(ColorNodesConformance, EveryCaseMatchesCycles) {
  const Manifest& m = manifest();
  ASSERT_FALSE(m.dir.empty()) << "test_scenes/nodes/color.json not found above the build";
  ASSERT_GT(m.coords.width, 0) << "cannot read " << (m.dir / "coords.exr");
  ASSERT_GE(m.cases.array.size(), 150u);
  std::vector<std::pair<float, std::string>> worst;  // each case's worst error
  for (const Json& json : m.cases.array) {
    Case c;
    const std::string error = build_case(json, &c);
    SCOPED_TRACE(c.name);
    ASSERT_TRUE(error.empty()) << error;
    RgbImage ref;
    ASSERT_TRUE(read_rgb_exr(m.dir / (c.name + ".exr"), &ref));
    ASSERT_EQ(ref.rgb.size(), m.coords.rgb.size());
    float case_worst = 0.0f;
    int bad = 0, first_bad = -1;
    const size_t pixels = ref.rgb.size() / 3;
    for (size_t i = 0; i < pixels; i += node_ref_pixel_stride()) {
      const float* q = &m.coords.rgb[i * 3];
      const Vec3 p(q[0] - 4.0f, q[1] - 4.0f, q[2] - 4.0f);
      const Vec3 got = evaluate(c, p);
      for (int k = 0; k < 3; ++k) {
        const float want = ref.rgb[i * 3 + k];
        const float err = relative_error(got[k], want);
        const float e = std::isfinite(err) ? err : 1e30f;
        case_worst = std::max(case_worst, e);
        if (e > kTolerance) {
          if (bad++ == 0) first_bad = static_cast<int>(i * 3 + k);
        }
      }
    }
    if (bad > 0) {
      const int i = first_bad / 3;
      const float* q = &m.coords.rgb[i * 3];
      const Vec3 got = evaluate(c, Vec3(q[0] - 4.0f, q[1] - 4.0f, q[2] - 4.0f));
      ADD_FAILURE() << bad << " channel(s) beyond " << kTolerance << ", worst " << case_worst
                    << "; first at pixel " << i << " (P " << q[0] - 4.0f << ", " << q[1] - 4.0f
                    << ", " << q[2] - 4.0f << ") channel " << first_bad % 3 << ": Photon "
                    << got[first_bad % 3] << ", Cycles " << ref.rgb[first_bad];
    }
    worst.emplace_back(case_worst, c.name);
  }
  std::sort(worst.rbegin(), worst.rend());
  std::printf("[ColorNodes] %zu cases; largest relative-or-absolute errors:", worst.size());
  for (size_t i = 0; i < std::min<size_t>(6, worst.size()); ++i) {
    std::printf(" %s %.2g%s", worst[i].second.c_str(), worst[i].first, i < 5 ? "," : "\n");
  }
}

// Every blend mode, data type and colour space the nodes offer is in the manifest.
TEST(ColorNodesConformance, ManifestCoversEveryMode) {
  const Manifest& m = manifest();
  ASSERT_FALSE(m.dir.empty());
  std::set<std::string> seen;
  for (const Json& c : m.cases.array) {
    const std::string node = c.find("node")->string;
    seen.insert(node);
    if (const Json* props = c.find("properties")) {
      for (const auto& [key, v] : props->object) {
        if (v.kind == Json::kString) seen.insert(node + "." + key + "=" + v.string);
      }
    }
  }
  const char* blends[] = {"MIX",          "DARKEN",     "MULTIPLY", "BURN",    "LIGHTEN",
                          "SCREEN",       "DODGE",      "ADD",      "OVERLAY", "SOFT_LIGHT",
                          "LINEAR_LIGHT", "DIFFERENCE", "SUBTRACT", "DIVIDE",  "HUE",
                          "SATURATION",   "COLOR",      "VALUE"};
  for (const char* b : blends) {
    EXPECT_TRUE(seen.count(std::string("ShaderNodeMix.blend_type=") + b)) << b;
    EXPECT_TRUE(seen.count(std::string("ShaderNodeMixRGB.blend_type=") + b)) << b;
    BlendMode mode;
    EXPECT_TRUE(parse_blend_mode(b, &mode)) << b;
  }
  for (const char* t : {"FLOAT", "VECTOR", "RGBA"}) {
    EXPECT_TRUE(seen.count(std::string("ShaderNodeMix.data_type=") + t)) << t;
  }
  for (const char* s : {"RGB", "HSV", "HSL"}) {
    EXPECT_TRUE(seen.count(std::string("ShaderNodeSeparateColor.mode=") + s)) << s;
    EXPECT_TRUE(seen.count(std::string("ShaderNodeCombineColor.mode=") + s)) << s;
  }
}

// NaN and infinite inputs (a division by zero upstream) give some value, never undefined
// behaviour: every float-to-int conversion is range-checked first (the sanitizer build runs
// this), and a table lookup never leaves its table.
TEST(ColorNodes, NonFiniteInputsAreSafe) {
  const Manifest& m = manifest();
  ASSERT_FALSE(m.dir.empty());
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  int evaluated = 0;
  for (const Json& json : m.cases.array) {
    Case c;
    ASSERT_TRUE(build_case(json, &c).empty());
    if (c.linked < 0) {
      // Constant-input cases (Blackbody, Wavelength): make the constant non-finite.
      c.linked = c.ins.in[0];
      c.linked_vector = false;
    }
    for (float v : {nan, inf, -inf, 1e30f, -1e30f}) {
      for (const Vec3& p : {Vec3(v), Vec3(v, 0.5f, 0.25f), Vec3(0.5f, v, -v)}) {
        evaluate(c, p);
        ++evaluated;
      }
    }
  }
  EXPECT_GT(evaluated, 1000);
}

// Bad data from the add-on is a clear compile error, never an out-of-bounds read.
TEST(ColorNodes, MalformedTablesAndEnumsAreErrors) {
  ShaderProgram program;
  Instruction ins;
  std::string error;
  NodeDesc ramp;
  ramp.type = "ShaderNodeValToRGB";
  ramp.table = {1.0f, 0.0f, 0.0f, 0.0f, 1.0f};  // one sample: too short
  EXPECT_EQ(compile_color_node(ramp, &program, &ins, &error), CompileStatus::kError);
  EXPECT_NE(error.find("table"), std::string::npos) << error;
  NodeDesc curve;
  curve.type = "ShaderNodeRGBCurve";
  curve.table = {0.0f, 1.0f, 0.0f, 0.1f, 0.2f, 0.3f, 0.4f, 0.5f};  // 5 values: not RGB triples
  EXPECT_EQ(compile_color_node(curve, &program, &ins, &error), CompileStatus::kError);
  NodeDesc mix;
  mix.type = "ShaderNodeMix";
  mix.enums = {{"data_type", "RGBA"}, {"blend_type", "NOT_A_MODE"}};
  EXPECT_EQ(compile_color_node(mix, &program, &ins, &error), CompileStatus::kError);
  NodeDesc other;
  other.type = "ShaderNodeTexNoise";
  EXPECT_EQ(compile_color_node(other, &program, &ins, &error), CompileStatus::kUnknownNode);
}

// An input the add-on leaves out reads Blender's socket default instead of register -1.
TEST(ColorNodes, MissingInputsReadBlenderDefaults) {
  ShaderProgram program;
  Instruction ins;
  std::string error;
  NodeDesc gamma;
  gamma.type = "ShaderNodeGamma";
  gamma.outputs["Color"] = 0;
  program.registers = {0.0f, 0.0f, 0.0f};
  ASSERT_EQ(compile_color_node(gamma, &program, &ins, &error), CompileStatus::kCompiled);
  std::vector<float> r = program.registers;
  eval_color_node(ins, program, ShaderGlobals{}, r.data());
  EXPECT_EQ(r[0], 1.0f);  // Color (1, 1, 1) ^ Gamma 1
  EXPECT_EQ(r[2], 1.0f);
}

}  // namespace
}  // namespace color_nodes_test
}  // namespace photon
