// Conformance of the kMath node family with Cycles 3.4: every case of test_scenes/nodes/math.json
// was rendered by Cycles (tools/node_refs.py) as the node's output on a plane; here each case's
// NodeDesc is compiled and evaluated at every pixel's Object coordinate (coords.exr) and compared
// with the Cycles image.
#include "photon/shading/math_nodes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "photon/shading/node_math.h"
#include "photon/testing/node_references.h"

namespace photon {
namespace math_nodes_test {
namespace {

// ---- The sockets of each node, in Blender 3.4's order (index "#i" in the manifest) ----
struct Socket {
  const char* identifier;
  int size;  // 1 float, 3 vector
  Vec3 fallback;
};
struct NodeSockets {
  std::vector<Socket> inputs, outputs;
};

const std::map<std::string, NodeSockets>& node_sockets() {
  static const std::map<std::string, NodeSockets> table = {
      {"ShaderNodeMath",
       {{{"Value", 1, Vec3(0.5f)}, {"Value_001", 1, Vec3(0.5f)}, {"Value_002", 1, Vec3(0.5f)}},
        {{"Value", 1, {}}}}},
      {"ShaderNodeVectorMath",
       {{{"Vector", 3, Vec3(0.0f)},
         {"Vector_001", 3, Vec3(0.0f)},
         {"Vector_002", 3, Vec3(0.0f)},
         {"Scale", 1, Vec3(1.0f)}},
        {{"Vector", 3, {}}, {"Value", 1, {}}}}},
      {"ShaderNodeMapRange",
       {{{"Value", 1, Vec3(1.0f)},
         {"From Min", 1, Vec3(0.0f)},
         {"From Max", 1, Vec3(1.0f)},
         {"To Min", 1, Vec3(0.0f)},
         {"To Max", 1, Vec3(1.0f)},
         {"Steps", 1, Vec3(4.0f)},
         {"Vector", 3, Vec3(0.0f)},
         {"From_Min_FLOAT3", 3, Vec3(0.0f)},
         {"From_Max_FLOAT3", 3, Vec3(1.0f)},
         {"To_Min_FLOAT3", 3, Vec3(0.0f)},
         {"To_Max_FLOAT3", 3, Vec3(1.0f)},
         {"Steps_FLOAT3", 3, Vec3(4.0f)}},
        {{"Result", 1, {}}, {"Vector", 3, {}}}}},
      {"ShaderNodeClamp",
       {{{"Value", 1, Vec3(1.0f)}, {"Min", 1, Vec3(0.0f)}, {"Max", 1, Vec3(1.0f)}},
        {{"Result", 1, {}}}}},
      {"ShaderNodeMapping",
       {{{"Vector", 3, Vec3(0.0f)},
         {"Location", 3, Vec3(0.0f)},
         {"Rotation", 3, Vec3(0.0f)},
         {"Scale", 3, Vec3(1.0f)}},
        {{"Vector", 3, {}}}}},
      {"ShaderNodeVectorRotate",
       {{{"Vector", 3, Vec3(0.0f)},
         {"Center", 3, Vec3(0.0f)},
         {"Axis", 3, Vec3(0.0f, 0.0f, 1.0f)},
         {"Angle", 1, Vec3(0.0f)},
         {"Rotation", 3, Vec3(0.0f)}},
        {{"Vector", 3, {}}}}},
      {"ShaderNodeVectorTransform", {{{"Vector", 3, Vec3(0.5f)}}, {{"Vector", 3, {}}}}},
      // "Normal_const" is the Normal output's default_value, sent by the add-on as an input.
      {"ShaderNodeNormal",
       {{{"Normal", 3, Vec3(0.0f, 0.0f, 1.0f)}, {"Normal_const", 3, Vec3(0.0f, 0.0f, 1.0f)}},
        {{"Normal", 3, {}}, {"Dot", 1, {}}}}},
  };
  return table;
}

int socket_index(const std::vector<Socket>& sockets, const std::string& key) {
  if (!key.empty() && key[0] == '#') return std::stoi(key.substr(1));
  for (size_t i = 0; i < sockets.size(); ++i)
    if (key == sockets[i].identifier) return static_cast<int>(i);
  return -1;
}

Vec3 json_vec(const Json& j) {
  if (j.kind == Json::kNumber) return Vec3(static_cast<float>(j.number));
  return {static_cast<float>(j.array.at(0).number), static_cast<float>(j.array.at(1).number),
          static_cast<float>(j.array.at(2).number)};
}

// Blender's object matrix for location, XYZ Euler rotation and scale: T * Rz Ry Rx * S.
Transform object_matrix(const Json& object) {
  Vec3 loc = object.has("location") ? json_vec(object.at("location")) : Vec3(0.0f);
  Vec3 rot = object.has("rotation") ? json_vec(object.at("rotation")) : Vec3(0.0f);
  Vec3 scale = object.has("scale") ? json_vec(object.at("scale")) : Vec3(1.0f);
  Transform m = euler_xyz_to_transform(rot);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) m.m[r][c] *= scale[c];
    m.m[r][3] = loc[r];
  }
  return m;
}

// Cycles' world-to-camera of node_refs.py's camera (at (0, 0, 10), looking down -Z): Cycles'
// camera space looks along +Z, so z is flipped: (x, y, 10 - z).
Transform refs_world_to_camera() {
  Transform t;
  t.m[2][2] = -1.0f;
  t.m[2][3] = 10.0f;
  return t;
}

struct CaseResult {
  int pixels = 0, bad = 0;
  float worst = 0.0f;
  std::string worst_text;
};

constexpr float kCoordOffset = 4.0f;
constexpr float kTolerance = 1e-4f;

CaseResult run_case(const Json& c, const std::filesystem::path& dir,
                    const RgbImage& shared_coords) {
  CaseResult result;
  const std::string name = c.at("name").string;
  const std::string type = c.at("node").string;
  const NodeSockets& sockets = node_sockets().at(type);

  NodeDesc desc;
  desc.type = type;
  if (c.has("properties")) {
    for (const auto& [key, v] : c.at("properties").object) {
      if (v.kind == Json::kString)
        desc.enums[key] = v.string;
      else if (v.kind == Json::kBool)
        desc.enums[key] = v.boolean ? "True" : "False";
      else
        desc.numbers[key] = v.number;
    }
  }
  // Registers: every input gets its default, then the manifest's values.
  ShaderProgram program;
  std::vector<int32_t> input_regs;
  for (const Socket& s : sockets.inputs) {
    input_regs.push_back(static_cast<int32_t>(program.registers.size()));
    desc.inputs[s.identifier] = input_regs.back();
    for (int i = 0; i < s.size; ++i) program.registers.push_back(s.fallback[i]);
  }
  auto set_input = [&](int index, Vec3 v) {
    for (int i = 0; i < sockets.inputs[index].size; ++i)
      program.registers[input_regs[index] + i] = v[i];
  };
  if (c.has("inputs"))
    for (const auto& [key, v] : c.at("inputs").object)
      set_input(socket_index(sockets.inputs, key), json_vec(v));
  if (c.has("output_values")) {  // the Normal node's direction
    for (const auto& [key, v] : c.at("output_values").object) {
      EXPECT_EQ(type, "ShaderNodeNormal");
      set_input(socket_index(sockets.inputs, "Normal_const"), json_vec(v));
    }
  }
  int linked = c.has("vector") && c.at("vector").kind == Json::kString
                   ? socket_index(sockets.inputs, c.at("vector").string)
                   : -1;
  int out_index = socket_index(sockets.outputs, c.has("output") ? c.at("output").string : "#0");
  if (out_index < 0) {  // by name
    for (size_t i = 0; i < sockets.outputs.size(); ++i)
      if (c.at("output").string == sockets.outputs[i].identifier) out_index = static_cast<int>(i);
  }
  const Socket& out_socket = sockets.outputs.at(out_index);
  int32_t out_reg = static_cast<int32_t>(program.registers.size());
  for (int i = 0; i < 3; ++i) program.registers.push_back(0.0f);
  desc.outputs[out_socket.identifier] = out_reg;

  Instruction ins;
  std::string error;
  EXPECT_EQ(compile_math_node(desc, &program, &ins, &error), CompileStatus::kCompiled)
      << name << ": " << error;

  ShaderGlobals globals;
  RgbImage own_coords;
  const RgbImage* coords = &shared_coords;
  if (c.has("object")) {
    EXPECT_TRUE(read_rgb_exr(dir / (name + "_coords.exr"), &own_coords)) << name;
    coords = &own_coords;
    invert_transform(object_matrix(c.at("object")), &globals.world_to_object);
  }
  globals.world_to_camera = refs_world_to_camera();

  RgbImage expected;
  EXPECT_TRUE(read_rgb_exr(dir / (name + ".exr"), &expected)) << name;
  if (expected.rgb.size() != coords->rgb.size()) {
    ADD_FAILURE() << name << ": image sizes differ";
    return result;
  }
  const float vector_scale =
      c.has("vector_scale") ? static_cast<float>(c.at("vector_scale").number) : 1.0f;
  const int count = expected.width * expected.height;
  std::vector<float> regs;
  for (int p = 0; p < count; p += node_ref_pixel_stride()) {
    Vec3 stored = coords->at(p);
    if (max_component(stored) < 1.0f) continue;  // the ray missed the plane
    Vec3 coord = stored - Vec3(kCoordOffset);
    ++result.pixels;
    regs = program.registers;
    if (linked >= 0) {
      Vec3 v = coord * vector_scale;
      // A vector linked to a float socket converts to the components' average (Cycles' VF).
      if (sockets.inputs[linked].size == 1) v = Vec3((v.x + v.y + v.z) * (1.0f / 3.0f));
      for (int i = 0; i < sockets.inputs[linked].size; ++i) regs[input_regs[linked] + i] = v[i];
    }
    eval_math_node(ins, program, globals, regs.data());
    Vec3 got = out_socket.size == 1 ? Vec3(regs[out_reg]) : load3(regs.data(), out_reg);
    Vec3 want = expected.at(p);
    for (int i = 0; i < 3; ++i) {
      float err = relative_error(got[i], want[i]);
      if (!(err <= kTolerance)) ++result.bad;
      if (!(err <= result.worst)) {
        result.worst = std::isnan(err) ? INFINITY : err;
        std::ostringstream text;
        text << "pixel " << p << " coord (" << coord.x << ", " << coord.y << ", " << coord.z
             << ") channel " << i << ": photon " << got[i] << ", cycles " << want[i];
        result.worst_text = text.str();
      }
    }
  }
  return result;
}

TEST(MathNodes, MatchCyclesReferences) {
  const std::filesystem::path root = node_refs_dir();
  const std::filesystem::path dir = root / "math";
  ASSERT_TRUE(std::filesystem::exists(root / "math.json")) << "no manifest under " << root;
  const Json manifest = read_json(root / "math.json");
  RgbImage coords;
  ASSERT_TRUE(read_rgb_exr(dir / "coords.exr", &coords));

  int cases = 0;
  for (const Json& c : manifest.at("cases").array) {
    CaseResult r = run_case(c, dir, coords);
    ++cases;
    EXPECT_GT(r.pixels, 1000 / node_ref_pixel_stride())
        << c.at("name").string << ": too few pixels hit the plane";
    EXPECT_EQ(r.bad, 0) << c.at("name").string << ": " << r.bad
                        << " channels beyond tolerance; worst " << r.worst << " at "
                        << r.worst_text;
    if (std::getenv("PHOTON_MATH_VERBOSE"))
      std::printf("%-44s %5d px  worst %.3g  %s\n", c.at("name").string.c_str(), r.pixels, r.worst,
                  r.worst_text.c_str());
  }
  EXPECT_GT(cases, 100);
}

TEST(MathNodes, UnknownNodeAndBadEnum) {
  ShaderProgram program;
  Instruction ins;
  std::string error;
  NodeDesc desc;
  desc.type = "ShaderNodeTexNoise";
  EXPECT_EQ(compile_math_node(desc, &program, &ins, &error), CompileStatus::kUnknownNode);
  desc.type = "ShaderNodeMath";
  desc.enums["operation"] = "CUBE_ROOT";  // in no Blender
  EXPECT_EQ(compile_math_node(desc, &program, &ins, &error), CompileStatus::kError);
  EXPECT_NE(error.find("CUBE_ROOT"), std::string::npos);
}

TEST(MathNodes, MissingInputsReadBlenderDefaults) {
  // Without registers for its inputs a Math ADD reads 0.5 + 0.5.
  ShaderProgram program;
  program.registers.assign(1, -7.0f);
  NodeDesc desc;
  desc.type = "ShaderNodeMath";
  desc.outputs["Value"] = 0;
  Instruction ins;
  std::string error;
  ASSERT_EQ(compile_math_node(desc, &program, &ins, &error), CompileStatus::kCompiled);
  std::vector<float> regs = program.registers;
  eval_math_node(ins, program, ShaderGlobals(), regs.data());
  EXPECT_EQ(regs[0], 1.0f);
}

}  // namespace
}  // namespace math_nodes_test
}  // namespace photon

namespace photon {
namespace math_nodes_test {
namespace {

TEST(MathNodes, WorldShaderHasNoObjectSpace) {
  // Cycles skips the object transforms where there is no object (sd->object == OBJECT_NONE).
  ShaderGlobals g;
  g.world_to_object = Transform::translation(Vec3(1.0f, 2.0f, 3.0f));
  Vec3 p(0.25f, -0.5f, 2.0f);
  Vec3 moved = vector_transform(VectorTransformType::kPoint, VectorTransformSpace::kWorld,
                                VectorTransformSpace::kObject, p, g);
  EXPECT_FLOAT_EQ(moved.x, 1.25f);
  g.is_background = true;
  Vec3 kept = vector_transform(VectorTransformType::kPoint, VectorTransformSpace::kWorld,
                               VectorTransformSpace::kObject, p, g);
  EXPECT_FLOAT_EQ(kept.x, p.x);
  EXPECT_FLOAT_EQ(kept.z, p.z);
}

TEST(MathNodes, GuardsKeepResultsFinite) {
  // A NaN operand clamps to the lower bound as in Cycles' ternary clamp (use_clamp).
  EXPECT_EQ(cy_clamp(NAN, 0.0f, 1.0f), 0.0f);
  // Exponents beyond int range: Cycles' (int) cast gives INT_MIN, so a negative base yields 0.
  EXPECT_EQ(safe_powf(-2.0f, 1e20f), 0.0f);
  EXPECT_EQ(safe_powf(-2.0f, NAN), 0.0f);
  EXPECT_EQ(safe_powf(-2.0f, 3.0f), -8.0f);
  // Zero-length normals in Reflect/Refract stay finite (Cycles would produce NaN).
  VectorMathResult r = eval_vector_math(VectorMathOp::kReflect, Vec3(1.0f, 2.0f, 3.0f), Vec3(0.0f),
                                        Vec3(0.0f), 1.0f);
  EXPECT_TRUE(is_finite(r.vector));
  r = eval_vector_math(VectorMathOp::kRefract, Vec3(1.0f, 2.0f, 3.0f), Vec3(0.0f), Vec3(0.0f),
                       1.5f);
  EXPECT_TRUE(is_finite(r.vector));
}

}  // namespace
}  // namespace math_nodes_test
}  // namespace photon
