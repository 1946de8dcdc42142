// Checker, Gradient, Brick, Magic (and the Sky texture) against Cycles: each case of
// test_scenes/nodes/pattern.json is compiled from its NodeDesc and evaluated at every pixel's
// Object coordinate (coords.exr), then compared with the Cycles render of the same case.
#include "photon/shading/pattern_nodes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

#include "photon/testing/node_references.h"

namespace photon {
namespace pattern_nodes_test {
namespace {

namespace fs = std::filesystem;

constexpr float kCoordOffset = 4.0f;  // tools/node_refs.py's coords.exr offset

// A case's node, its registers (Vector at 0) and the register the shown output lands in.
struct Built {
  ShaderProgram program;
  Instruction ins;
  int32_t vector = -1, output = -1;
  bool output_is_float = false;
};

Built build_case(const Json& c) {
  Built b;
  NodeDesc desc;
  desc.type = c.find("node")->string;
  auto& regs = b.program.registers;
  if (const Json* props = c.find("properties")) {
    for (const auto& [key, v] : props->object) {
      if (v.kind == Json::kString)
        desc.enums[key] = v.string;
      else if (v.kind == Json::kBool)
        desc.enums[key] = v.boolean ? "True" : "False";
      else if (v.kind == Json::kNumber)
        desc.numbers[key] = v.number;
      else if (v.kind == Json::kArray)  // vector properties: "name[i]"
        for (size_t i = 0; i < v.array.size(); ++i)
          desc.numbers[key + "[" + std::to_string(i) + "]"] = v.array[i].number;
    }
  }
  // The point (or, for world cases, the direction) goes in the Vector input's register; an
  // unlinked Vector ("vector": null) is what the add-on sends as Generated / the ray direction.
  const Json* vec = c.find("vector");
  b.vector = static_cast<int32_t>(regs.size());
  desc.inputs[vec && vec->kind == Json::kString ? vec->string : "Vector"] = b.vector;
  regs.insert(regs.end(), 3, 0.0f);
  if (const Json* inputs = c.find("inputs")) {
    for (const auto& [key, v] : inputs->object) {
      desc.inputs[key] = static_cast<int32_t>(regs.size());
      if (v.kind == Json::kArray)
        for (int i = 0; i < 3; ++i) regs.push_back(static_cast<float>(v.array[i].number));
      else
        regs.push_back(static_cast<float>(v.number));
    }
  }
  const Json* out = c.find("output");
  const std::string output = out ? out->string : "Color";
  b.output_is_float = output == "Fac";
  b.output = static_cast<int32_t>(regs.size());
  desc.outputs[output] = b.output;
  regs.insert(regs.end(), 3, 0.0f);
  std::string error;
  EXPECT_EQ(compile_pattern_node(desc, &b.program, &b.ins, &error), CompileStatus::kCompiled)
      << error;
  return b;
}

struct CaseResult {
  int bad = 0;
  int quantized = 0;  // pixels within tolerance only inside the coordinate's rounding box
  float max_error = 0.0f;
  std::string worst;
};

// coords.exr stores float(co + 4): each coordinate is known to half an ulp of [4, 8), 2^-22.
constexpr float kCoordRounding = 1.0f / (1 << 22);

Vec3 eval_at(const Built& b, const Vec3& co, std::vector<float>& r) {
  r = b.program.registers;
  store3(r.data(), b.vector, co);
  ShaderGlobals g;
  g.generated = co;
  eval_pattern_node(b.ins, b.program, g, r.data());
  return b.output_is_float ? Vec3(r[b.output]) : load3(r.data(), b.output);
}

// Every pixel of one case: |photon - cycles| <= tol * max(1, |cycles|) at the stored coordinate,
// or else at some corner of the box the coordinate's rounding leaves (high-frequency textures
// and edges are that sensitive; such pixels are counted).
CaseResult compare_case(const Json& c, const RgbImage& coords, const RgbImage& ref, float tol) {
  const Built b = build_case(c);
  CaseResult res;
  std::vector<float> r;
  for (int i = 0; i < coords.width * coords.height; i += node_ref_pixel_stride()) {
    const Vec3 co = coords.at(i) - Vec3(kCoordOffset);
    const Vec3 got = eval_at(b, co, r);
    const Vec3 want = ref.at(i);
    bool pixel_ok = true;
    for (int k = 0; k < 3; ++k) {
      const float err = relative_error(got[k], want[k]);
      pixel_ok = pixel_ok && err <= tol;
      if (!(err <= res.max_error)) {
        res.max_error = err;
        std::ostringstream os;
        os << "pixel " << i << " co (" << co.x << ", " << co.y << ", " << co.z << ") ch " << k
           << " photon " << got[k] << " cycles " << want[k];
        res.worst = os.str();
      }
    }
    if (pixel_ok) continue;
    Vec3 lo = got, hi = got;
    for (int corner = 0; corner < 8; ++corner) {
      Vec3 d;
      for (int k = 0; k < 3; ++k) d[k] = (corner >> k & 1) ? kCoordRounding : -kCoordRounding;
      const Vec3 v = eval_at(b, co + d, r);
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], v[k]), hi[k] = std::max(hi[k], v[k]);
    }
    bool in_box = true;
    for (int k = 0; k < 3; ++k) {
      const float t = tolerance_at(tol, want[k]);
      in_box = in_box && want[k] >= lo[k] - t && want[k] <= hi[k] + t;
    }
    ++(in_box ? res.quantized : res.bad);
  }
  return res;
}

// Runs the manifest's surface cases (world == false) or its world cases (each with its own
// <name>.coords.exr of ray directions); returns how many ran.
int run_cases(bool world, float tol) {
  const fs::path dir = node_refs_dir();
  EXPECT_FALSE(dir.empty()) << "test_scenes/nodes not found above " << fs::current_path();
  const Json manifest = read_json(dir / "pattern.json");
  RgbImage plane_coords;
  read_rgb_exr(dir / "pattern" / "coords.exr", &plane_coords);
  EXPECT_GT(plane_coords.width, 0);
  int cases = 0;
  for (const Json& c : manifest.find("cases")->array) {
    const Json* w = c.find("world");
    if ((w != nullptr && w->boolean) != world) continue;
    const std::string name = c.find("name")->string;
    RgbImage coords = plane_coords, ref;
    if (world) read_rgb_exr(dir / "pattern" / (name + ".coords.exr"), &coords);
    read_rgb_exr(dir / "pattern" / (name + ".exr"), &ref);
    EXPECT_EQ(ref.width, coords.width) << name;
    if (ref.width != coords.width || ref.height != coords.height) continue;
    const CaseResult res = compare_case(c, coords, ref, tol);
    EXPECT_EQ(res.bad, 0) << name << ": max error " << res.max_error << " at " << res.worst;
    if (res.quantized > 0 || res.max_error > 1e-5f)
      std::printf("%s: max error %g, %d pixels matched within the coordinate rounding box\n",
                  name.c_str(), res.max_error, res.quantized);
    ++cases;
  }
  return cases;
}

TEST(PatternNodes, MatchCyclesReferences) {
  EXPECT_GE(run_cases(false, 1e-4f), 40);
}

TEST(PatternSky, MatchCyclesReferences) {
  EXPECT_GE(run_cases(true, 1e-4f), 8);
}

TEST(PatternNodes, CheckerKeepsIntegerCoordinatesOffEdges) {
  // Without Cycles' nudge, (1, 0, 0) would sit on a cell edge and floor to cell 1.
  EXPECT_EQ(checker_texture(Vec3(1.0f, 0.0f, 0.0f)), checker_texture(Vec3(0.5f, 0.5f, 0.5f)));
  EXPECT_NE(checker_texture(Vec3(1.5f, 0.5f, 0.5f)), checker_texture(Vec3(0.5f, 0.5f, 0.5f)));
}

TEST(PatternNodes, DegenerateInputsStayDefined) {
  // A zero row height or brick width (a linked input can be anything) and huge or NaN points
  // must not reach an out-of-range float-to-int conversion (checked under UBSan).
  const Vec2 zero_row =
      brick_texture(Vec3(0.3f, 0.2f, 0.0f), 0.02f, 0.1f, 0.0f, 0.5f, 0.0f, 0.5f, 2, 1.0f, 2);
  const Vec2 zero_width =
      brick_texture(Vec3(0.3f, 0.2f, 0.0f), 0.02f, 0.1f, 0.0f, 0.0f, 0.25f, 0.5f, 2, 1.0f, 2);
  EXPECT_TRUE(zero_row.x >= 0.0f && zero_row.x <= 1.0f);
  EXPECT_TRUE(zero_width.x >= 0.0f && zero_width.x <= 1.0f);
  const float huge = checker_texture(Vec3(3e9f, -3e9f, std::nanf("")));
  EXPECT_TRUE(huge == 0.0f || huge == 1.0f);
}

TEST(PatternNodes, MissingInputsTakeBlenderDefaultsAndBadEnumsFail) {
  NodeDesc desc;
  desc.type = "ShaderNodeTexBrick";
  desc.outputs["Fac"] = 0;
  ShaderProgram program;
  program.registers.assign(1, 0.0f);
  Instruction ins;
  std::string error;
  ASSERT_EQ(compile_pattern_node(desc, &program, &ins, &error), CompileStatus::kCompiled);
  std::vector<float> r = program.registers;
  ShaderGlobals g;
  g.generated = Vec3(0.31f, 0.52f, 0.0f);
  eval_pattern_node(ins, program, g, r.data());
  const Vec2 want =
      brick_texture(g.generated * 5.0f, 0.02f, 0.1f, 0.0f, 0.5f, 0.25f, 0.5f, 2, 1.0f, 2);
  EXPECT_EQ(r[0], want.y);

  NodeDesc gradient;
  gradient.type = "ShaderNodeTexGradient";
  gradient.enums["gradient_type"] = "CONICAL";
  EXPECT_EQ(compile_pattern_node(gradient, &program, &ins, &error), CompileStatus::kError);
  EXPECT_NE(error.find("CONICAL"), std::string::npos);

  NodeDesc other;
  other.type = "ShaderNodeMath";
  EXPECT_EQ(compile_pattern_node(other, &program, &ins, &error), CompileStatus::kUnknownNode);
}

}  // namespace
}  // namespace pattern_nodes_test
}  // namespace photon

namespace photon {
namespace pattern_nodes_test {
namespace {

TEST(PatternSky, BadSettingsFailOrClampInsteadOfCrashing) {
  ShaderProgram program;
  program.registers.assign(6, 0.0f);
  Instruction ins;
  std::string error;
  NodeDesc sky;
  sky.type = "ShaderNodeTexSky";
  sky.inputs["Vector"] = 0;
  sky.outputs["Color"] = 3;
  sky.enums["sky_type"] = "PREETHAM";
  sky.numbers["sun_direction[0]"] = 0.0;
  sky.numbers["sun_direction[1]"] = 0.0;
  sky.numbers["sun_direction[2]"] = 0.0;
  EXPECT_EQ(compile_pattern_node(sky, &program, &ins, &error), CompileStatus::kError);
  EXPECT_NE(error.find("sun direction"), std::string::npos);

  sky.enums["sky_type"] = "SPECTRAL";
  EXPECT_EQ(compile_pattern_node(sky, &program, &ins, &error), CompileStatus::kError);
  EXPECT_NE(error.find("SPECTRAL"), std::string::npos);

  // Out-of-range and NaN settings are clamped or defaulted; a NaN direction gives black.
  sky.enums["sky_type"] = "HOSEK_WILKIE";
  sky.numbers["sun_direction[2]"] = 1.0;
  sky.numbers["turbidity"] = std::nan("");
  sky.numbers["ground_albedo"] = 7.0;
  ASSERT_EQ(compile_pattern_node(sky, &program, &ins, &error), CompileStatus::kCompiled) << error;
  std::vector<float> r = program.registers;
  store3(r.data(), 0, Vec3(0.0f, 0.6f, 0.8f));
  ShaderGlobals g;
  eval_pattern_node(ins, program, g, r.data());
  const Vec3 c = load3(r.data(), 3);
  EXPECT_TRUE(std::isfinite(c.x) && c.x > 0.0f && std::isfinite(c.z) && c.z > 0.0f);
  store3(r.data(), 0, Vec3(std::nan(""), 0.0f, 1.0f));
  eval_pattern_node(ins, program, g, r.data());
  EXPECT_EQ(load3(r.data(), 3).x, 0.0f);
}

}  // namespace
}  // namespace pattern_nodes_test
}  // namespace photon
