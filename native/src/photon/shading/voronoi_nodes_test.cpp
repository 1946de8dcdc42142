// The Voronoi Texture against Cycles: every case of test_scenes/nodes/voronoi.json (rendered by
// tools/node_refs.py with Cycles 3.4) is compiled from its NodeDesc and evaluated at each pixel's
// Object coordinate (coords.exr), then compared with Cycles' pixel.
#include "photon/shading/voronoi_nodes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "photon/shading/voronoi.h"
#include "photon/testing/node_references.h"

namespace photon {
namespace voronoi_nodes_test {
namespace {

// ---- References. ----
const std::filesystem::path kRefDir = node_refs_dir() / "voronoi";
constexpr float kCoordOffset = 4.0f;  // coords.exr stores Object coordinates + 4 (node_refs.py)

Json load_manifest() {
  return read_json(node_refs_dir() / "voronoi.json");
}

// ---- A one-node program laid out as the add-on lays it out: inputs, then outputs. ----
struct Socket {
  const char* name;
  int width;
  float fallback;  // Blender 3.4's default value
};
constexpr Socket kInputs[] = {{"Vector", 3, 0.0f},   {"W", 1, 0.0f},
                              {"Scale", 1, 5.0f},    {"Smoothness", 1, 1.0f},
                              {"Exponent", 1, 0.5f}, {"Randomness", 1, 1.0f}};
constexpr Socket kOutputs[] = {{"Distance", 1, 0.0f},
                               {"Color", 3, 0.0f},
                               {"Position", 3, 0.0f},
                               {"W", 1, 0.0f},
                               {"Radius", 1, 0.0f}};

struct Case {
  std::string name;
  NodeDesc desc;
  ShaderProgram program;
  std::string linked;  // the input fed the Object coordinate ("Vector", or "W" as their average)
  int32_t output = -1;
  int output_width = 1;
};

Case build_case(const Json& json) {
  Case c;
  c.name = json.find("name")->string;
  c.desc.type = json.find("node")->string;
  if (const Json* props = json.find("properties"))
    for (const auto& kv : props->object) c.desc.enums[kv.first] = kv.second.string;
  const Json* values = json.find("inputs");
  int32_t next = 0;
  for (const Socket& s : kInputs) {
    c.desc.inputs[s.name] = next;
    const Json* v = values ? values->find(s.name) : nullptr;
    for (int k = 0; k < s.width; ++k)
      c.program.registers.push_back(v ? static_cast<float>(v->number) : s.fallback);
    next += s.width;
  }
  const std::string output = json.find("output")->string;
  for (const Socket& s : kOutputs) {
    if (output != s.name) continue;
    c.desc.outputs[s.name] = next;
    c.output = next;
    c.output_width = s.width;
    for (int k = 0; k < s.width; ++k) c.program.registers.push_back(-7.0f);
    next += s.width;
  }
  c.linked = json.find("vector")->string;
  return c;
}

// Evaluates the case's one instruction at an Object coordinate; the output as Emission shows it.
Vec3 evaluate(const Case& c, const Instruction& ins, const Vec3& object) {
  std::vector<float> r = c.program.registers;
  const int32_t linked = c.desc.inputs.at(c.linked);
  if (c.linked == "Vector") {
    store3(r.data(), linked, object);
  } else {
    // Cycles' implicit vector-to-float conversion: the average of the components.
    store1(r.data(), linked, (object.x + object.y + object.z) * (1.0f / 3.0f));
  }
  eval_voronoi_node(ins, c.program, ShaderGlobals{}, r.data());
  return c.output_width == 3 ? load3(r.data(), c.output) : Vec3(r[c.output]);
}

// Relative-or-absolute error, per channel.
float error(const Vec3& a, const Vec3& b) {
  float e = 0.0f;
  for (int k = 0; k < 3; ++k) e = std::max(e, relative_error(a[k], b[k]));
  return e;
}

constexpr float kTolerance = 1e-4f;

// coords.exr holds coordinates + 4, rounded to floats of ulp 2.4e-7 or 4.8e-7 (node_refs.py): the
// point Cycles shaded lies within a rounding step of the one we evaluate. Where the output is
// sensitive at that scale (a cell border, where colour, position or F2's second point jump; a tie
// decided by rounding; or Minkowski with exponent < 1, whose |d|^e has an infinite slope where a
// feature point lies on an axis-aligned line through the shading point), that difference shows.
// Such a pixel is explained when the outputs over the box of +-1 rounding step around the
// coordinate vary by more than the tolerance and enclose Cycles' value.
bool explained_by_coordinate_rounding(const Case& c, const Instruction& ins, const Vec3& object,
                                      const Vec3& ref) {
  Vec3 ulp;
  for (int k = 0; k < 3; ++k) {
    const float stored = object[k] + kCoordOffset;
    ulp[k] = std::nextafter(stored, INFINITY) - stored;
  }
  // Samples every 1/8 step over +-1 step: where ties are decided by float rounding (Manhattan
  // distances to two points are equal over whole regions), the winner changes at that scale.
  constexpr int kSub = 8;
  Vec3 lo(INFINITY), hi(-INFINITY);
  for (int i = -kSub; i <= kSub; ++i)
    for (int j = -kSub; j <= kSub; ++j)
      for (int k = -kSub; k <= kSub; ++k) {
        const Vec3 p =
            object + Vec3(static_cast<float>(i), static_cast<float>(j), static_cast<float>(k)) *
                         ulp * (1.0f / kSub);
        const Vec3 v = evaluate(c, ins, p);
        lo = min(lo, v);
        hi = max(hi, v);
      }
  if (error(hi, lo) <= kTolerance) return false;  // not sensitive here: a real difference
  for (int k = 0; k < 3; ++k) {
    const float margin = tolerance_at(kTolerance, ref[k]);
    if (ref[k] < lo[k] - margin || ref[k] > hi[k] + margin) return false;
  }
  return true;
}

TEST(VoronoiNodes, MatchesCyclesOnEveryManifestCase) {
  const Json manifest = load_manifest();
  const Json* cases = manifest.find("cases");
  ASSERT_NE(cases, nullptr);
  ASSERT_GE(cases->array.size(), 300u);
  RgbImage coords;
  ASSERT_TRUE(read_rgb_exr(kRefDir / "coords.exr", &coords)) << kRefDir / "coords.exr";
  ASSERT_GT(coords.size(), 0u);

  size_t pixels = 0, sensitive_pixels = 0, above_1e6 = 0, above_1e5 = 0;
  float worst = 0.0f;
  std::string worst_case;
  for (const Json& json : cases->array) {
    Case c = build_case(json);
    SCOPED_TRACE(c.name);
    Instruction ins;
    std::string error_text;
    ASSERT_EQ(compile_voronoi_node(c.desc, &c.program, &ins, &error_text), CompileStatus::kCompiled)
        << error_text;
    EXPECT_EQ(ins.family, NodeFamily::kVoronoi);
    RgbImage ref;
    ASSERT_TRUE(read_rgb_exr(kRefDir / (c.name + ".exr"), &ref)) << "missing reference " << c.name;
    ASSERT_EQ(ref.size(), coords.size());
    float case_worst = 0.0f;
    std::vector<size_t> mismatches;
    for (size_t i = 0; i < coords.size(); i += node_ref_pixel_stride()) {
      const float e = error(evaluate(c, ins, coords.at(i) - Vec3(kCoordOffset)), ref.at(i));
      ++pixels;
      above_1e6 += e > 1e-6f;
      above_1e5 += e > 1e-5f;
      if (e <= kTolerance) {
        case_worst = std::max(case_worst, e);
        if (e > worst) worst = e, worst_case = c.name;
      } else {
        mismatches.push_back(i);
      }
    }
    if (case_worst > 1e-5f) std::printf("  %s: largest error %.3g\n", c.name.c_str(), case_worst);
    // Pixels that coordinate rounding can explain are rare (the band it can cross is ~1e-6 wide),
    // so more than a few mismatches fail at once.
    constexpr size_t kMaxSensitive = 4;
    size_t case_bad = 0, case_sensitive = 0;
    for (size_t i : mismatches) {
      const Vec3 object = coords.at(i) - Vec3(kCoordOffset);
      const Vec3 expected = ref.at(i);
      if (mismatches.size() <= kMaxSensitive &&
          explained_by_coordinate_rounding(c, ins, object, expected)) {
        ++case_sensitive;
        continue;
      }
      const Vec3 got = evaluate(c, ins, object);
      if (++case_bad <= 3)
        ADD_FAILURE() << "pixel " << i << " at (" << object.x << ", " << object.y << ", "
                      << object.z << "): got (" << got.x << ", " << got.y << ", " << got.z
                      << "), Cycles (" << expected.x << ", " << expected.y << ", " << expected.z
                      << ")";
    }
    EXPECT_EQ(case_bad, 0u) << "of " << mismatches.size() << " pixels beyond " << kTolerance;
    sensitive_pixels += case_sensitive;
  }
  std::printf(
      "voronoi: %zu cases, %zu pixels; largest error within tolerance %.3g (%s); "
      "%zu pixels explained by coordinate rounding; error > 1e-6 at %zu pixels, > 1e-5 at %zu\n",
      cases->array.size(), pixels, worst, worst_case.c_str(), sensitive_pixels, above_1e6,
      above_1e5);
}

// Every dimension x feature x metric Blender offers is in the manifest, with every output the mode
// shows, at Randomness 1 and 0.5 (and Minkowski exponents 0.5 and 3).
TEST(VoronoiNodes, ManifestCoversEveryModeAndOutput) {
  const Json manifest = load_manifest();
  std::set<std::string> seen;
  for (const Json& json : manifest.find("cases")->array) {
    const Json* props = json.find("properties");
    const Json* inputs = json.find("inputs");
    auto prop = [&](const char* k) {
      const Json* v = props->find(k);
      return v ? v->string : std::string("-");
    };
    auto input = [&](const char* k) {
      const Json* v = inputs->find(k);
      return v ? std::to_string(v->number) : std::string("-");
    };
    const std::string feature = prop("feature");
    const bool metric_used = prop("voronoi_dimensions") != "1D" &&
                             (feature == "F1" || feature == "F2" || feature == "SMOOTH_F1");
    const std::string metric = metric_used ? prop("distance") : "-";
    const std::string exponent = metric == "MINKOWSKI" ? input("Exponent") : "-";
    seen.insert(prop("voronoi_dimensions") + " " + feature + " " + metric + " " + exponent + " " +
                input("Randomness") + " " + json.find("output")->string);
  }
  const char* features[] = {"F1", "F2", "SMOOTH_F1", "DISTANCE_TO_EDGE", "N_SPHERE_RADIUS"};
  size_t expected = 0;
  for (int dims = 1; dims <= 4; ++dims)
    for (const char* feature : features)
      for (const char* rand : {"1.000000", "0.500000"}) {
        const std::string f = feature;
        std::vector<std::string> outputs;
        if (f == "DISTANCE_TO_EDGE")
          outputs = {"Distance"};
        else if (f == "N_SPHERE_RADIUS")
          outputs = {"Radius"};
        else {
          outputs = {"Distance", "Color"};
          if (dims > 1) outputs.push_back("Position");
          if (dims == 1 || dims == 4) outputs.push_back("W");
        }
        std::vector<std::string> metrics = {"- -"};
        if (dims > 1 && outputs.size() > 1)
          metrics = {"EUCLIDEAN -", "MANHATTAN -", "CHEBYCHEV -", "MINKOWSKI 0.500000",
                     "MINKOWSKI 3.000000"};
        for (const std::string& m : metrics)
          for (const std::string& out : outputs) {
            const std::string key =
                std::to_string(dims) + "D " + f + " " + m + " " + rand + " " + out;
            EXPECT_TRUE(seen.count(key)) << "no case for " << key;
            ++expected;
          }
      }
  EXPECT_EQ(expected, 334u);
}

NodeDesc voronoi_desc(const char* dims, const char* feature, const char* metric) {
  NodeDesc d;
  d.type = "ShaderNodeTexVoronoi";
  d.enums = {{"voronoi_dimensions", dims}, {"feature", feature}, {"distance", metric}};
  return d;
}

TEST(VoronoiNodes, CompileRejectsUnknownModesWithAClearError) {
  ShaderProgram program;
  Instruction ins;
  std::string error;
  NodeDesc other = voronoi_desc("3D", "F1", "EUCLIDEAN");
  other.type = "ShaderNodeTexNoise";
  EXPECT_EQ(compile_voronoi_node(other, &program, &ins, &error), CompileStatus::kUnknownNode);
  EXPECT_EQ(compile_voronoi_node(voronoi_desc("5D", "F1", "EUCLIDEAN"), &program, &ins, &error),
            CompileStatus::kError);
  EXPECT_NE(error.find("dimensions"), std::string::npos) << error;
  EXPECT_EQ(compile_voronoi_node(voronoi_desc("3D", "F3", "EUCLIDEAN"), &program, &ins, &error),
            CompileStatus::kError);
  EXPECT_NE(error.find("F3"), std::string::npos) << error;
  EXPECT_EQ(compile_voronoi_node(voronoi_desc("2D", "F1", "HAMMING"), &program, &ins, &error),
            CompileStatus::kError);
  EXPECT_NE(error.find("HAMMING"), std::string::npos) << error;
}

// Inputs the add-on did not send take Blender's defaults (Scale 5, Randomness 1, ...), and only
// the outputs it asked for are written.
TEST(VoronoiNodes, UnsentInputsTakeBlenderDefaults) {
  NodeDesc desc = voronoi_desc("3D", "F1", "EUCLIDEAN");
  desc.inputs = {{"Vector", 0}};
  desc.outputs = {{"Distance", 3}};
  ShaderProgram program;
  program.registers = {0.31f, -0.12f, 0.77f, -1.0f, 123.0f};
  Instruction ins;
  std::string error;
  ASSERT_EQ(compile_voronoi_node(desc, &program, &ins, &error), CompileStatus::kCompiled);
  std::vector<float> r = program.registers;
  eval_voronoi_node(ins, program, ShaderGlobals{}, r.data());
  voronoi::Params params;
  params.randomness = 1.0f;
  const voronoi::Result expected = voronoi::voronoi_3d(Vec3(0.31f, -0.12f, 0.77f) * 5.0f, params);
  EXPECT_EQ(r[3], expected.distance);
  EXPECT_EQ(r[4], 123.0f);
}

// Non-finite and huge coordinates give some value without crashing or looping.
TEST(VoronoiNodes, NonFiniteCoordinatesFinish) {
  const float bad[] = {NAN, INFINITY, -INFINITY, 3e38f, -3e38f};
  for (int dims = 1; dims <= 4; ++dims)
    for (int feature = 0; feature < 5; ++feature)
      for (float v : bad) {
        voronoi::Params params;
        params.feature = static_cast<voronoi::Feature>(feature);
        switch (dims) {
          case 1:
            voronoi::voronoi_1d(v, params);
            break;
          case 2:
            voronoi::voronoi_2d(v, 0.5f, params);
            break;
          case 3:
            voronoi::voronoi_3d(Vec3(0.5f, v, 0.5f), params);
            break;
          default:
            voronoi::voronoi_4d(Vec3(0.5f), v, params);
        }
      }
  SUCCEED();
}

}  // namespace
}  // namespace voronoi_nodes_test
}  // namespace photon
