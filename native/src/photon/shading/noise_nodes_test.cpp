// The noise family against Cycles: every case of test_scenes/nodes/noise.json was rendered by
// Blender 3.4's Cycles (tools/node_refs.py) into test_scenes/nodes/noise/<case>.exr, the node's
// output at each pixel's hit point; coords.exr holds that hit point (+4). Each case is compiled
// from the same description and evaluated at every pixel's point.
#include "photon/shading/noise_nodes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "photon/shading/noise.h"
#include "photon/testing/node_references.h"

namespace photon {
namespace noise_nodes_test {
namespace {

namespace fs = std::filesystem;

constexpr float kCoordOffset = 4.0f;  // tools/node_refs.py adds it to keep coords.exr positive

// A case made runnable: the program, which registers the Object coordinate feeds, and where the
// shown output lands.
struct Case {
  std::string name;
  ShaderProgram program;
  int32_t vector_reg = -1;     // 3 registers, the hit point
  int32_t scalar_reg = -1;     // 1 register, the hit point's average (a vector linked to a float)
  int32_t generated_reg = -1;  // 3 registers, the Generated coordinate (an unlinked texture Vector)
  int32_t output_reg = -1;
  bool output_is_color = false;
  bool periodic = false;  // a saw wave: values wrap from 1 to 0
  // Nothing linked: every input is a constant the test knows exactly, so only float rounding
  // order may differ from Cycles.
  bool constant() const { return vector_reg < 0 && scalar_reg < 0 && generated_reg < 0; }
};

bool is_vector_socket(const std::string& name) {
  return name == "Vector";
}

Case build_case(const Json& c) {
  Case out;
  out.name = c.find("name")->string;
  NodeDesc desc;
  desc.type = c.find("node")->string;
  if (const Json* props = c.find("properties"))
    for (const auto& [k, v] : props->object) desc.enums[k] = v.string;
  auto& regs = out.program.registers;
  if (const Json* inputs = c.find("inputs")) {
    for (const auto& [k, v] : inputs->object) {
      desc.inputs[k] = static_cast<int32_t>(regs.size());
      if (v.kind == Json::kArray)
        for (const Json& x : v.array) regs.push_back(static_cast<float>(x.number));
      else
        regs.push_back(static_cast<float>(v.number));
    }
  }
  const Json* vector = c.find("vector");
  std::string linked = (vector == nullptr) ? "Vector" : vector->string;
  if (vector == nullptr || vector->kind == Json::kString) {
    int32_t reg = static_cast<int32_t>(regs.size());
    desc.inputs[linked] = reg;
    if (is_vector_socket(linked)) {
      out.vector_reg = reg;
      regs.insert(regs.end(), 3, 0.0f);
    } else {
      out.scalar_reg = reg;
      regs.push_back(0.0f);
    }
  }
  // Cycles gives an unlinked texture Vector the Generated coordinate, not the socket's value
  // (White Noise excepted); the add-on passes it in the Vector register.
  bool one_d = enum_value(desc, "noise_dimensions", "") == "1D" ||
               enum_value(desc, "musgrave_dimensions", "") == "1D";
  if (!is_vector_socket(linked) && desc.type != "ShaderNodeTexWhiteNoise" && !one_d) {
    out.generated_reg = static_cast<int32_t>(regs.size());
    desc.inputs["Vector"] = out.generated_reg;
    regs.insert(regs.end(), 3, 0.0f);
  }
  std::string output = c.find("output")->string;
  out.output_is_color = output == "Color";
  out.output_reg = static_cast<int32_t>(regs.size());
  desc.outputs[output] = out.output_reg;
  regs.insert(regs.end(), out.output_is_color ? 3 : 1, 0.0f);
  auto profile = desc.enums.find("wave_profile");
  out.periodic = profile != desc.enums.end() && profile->second == "SAW";

  Instruction ins;
  std::string error;
  EXPECT_EQ(compile_noise_node(desc, &out.program, &ins, &error), CompileStatus::kCompiled)
      << out.name << ": " << error;
  out.program.code.push_back(ins);
  return out;
}

Vec3 run(Case& c, const Vec3& p) {
  std::vector<float> r = c.program.registers;
  if (c.vector_reg >= 0) store3(r.data(), c.vector_reg, p);
  // Cycles' implicit vector-to-float conversion: the average of the components.
  if (c.scalar_reg >= 0) r[c.scalar_reg] = (p.x + p.y + p.z) * (1.0f / 3.0f);
  // Generated: the point in the plane's bounding box, x, y in [-1, 1], z in [-0.25, 0.75].
  if (c.generated_reg >= 0)
    store3(r.data(), c.generated_reg, Vec3((p.x + 1.0f) * 0.5f, (p.y + 1.0f) * 0.5f, p.z + 0.25f));
  ShaderGlobals globals;
  for (const Instruction& ins : c.program.code) eval_noise_node(ins, c.program, globals, r.data());
  return c.output_is_color ? load3(r.data(), c.output_reg) : Vec3(r[c.output_reg]);
}

float difference(const Case& c, float ours, float cycles) {
  float d = std::fabs(ours - cycles);
  if (c.periodic) d = std::min(d, std::fabs(1.0f - d));
  return d / std::max(1.0f, std::fabs(cycles));
}

struct Manifest {
  fs::path dir;
  std::vector<Json> cases;
  RgbImage coords;
};

const Manifest& manifest() {
  static const Manifest m = [] {
    Manifest m;
    const fs::path root = node_refs_dir();
    const Json j = read_json(root / "noise.json");
    if (const Json* cases = j.find("cases")) m.cases = cases->array;
    m.dir = root / "noise";
    read_rgb_exr(m.dir / "coords.exr", &m.coords);
    return m;
  }();
  return m;
}

bool is_white_noise_linked(const Json& c) {
  const Json* vector = c.find("vector");
  return c.find("node")->string == "ShaderNodeTexWhiteNoise" && vector != nullptr &&
         vector->kind == Json::kString;
}

// Every case whose value varies smoothly (or is constant) with the point: each pixel within 1e-4
// relative-or-absolute of Cycles.
TEST(NoiseNodes, MatchCyclesReferences) {
  const Manifest& m = manifest();
  ASSERT_GE(m.cases.size(), 90u) << "manifest not found under " << node_refs_dir();
  ASSERT_GT(m.coords.width, 0) << "coords.exr not readable";
  float worst_overall = 0.0f;
  int compared = 0;
  for (const Json& jc : m.cases) {
    if (is_white_noise_linked(jc)) continue;  // WhiteNoiseMatchesCyclesHashes
    Case c = build_case(jc);
    RgbImage ref;
    read_rgb_exr(m.dir / (c.name + ".exr"), &ref);
    ASSERT_EQ(ref.width * ref.height, m.coords.width * m.coords.height) << c.name;
    float worst = 0.0f;
    int worst_pixel = 0, bad = 0;
    for (int i = 0; i < ref.width * ref.height; i += node_ref_pixel_stride()) {
      Vec3 p = m.coords.at(i) - Vec3(kCoordOffset);
      Vec3 ours = run(c, p), cycles = ref.at(i);
      for (int k = 0; k < 3; ++k) {
        float d = difference(c, ours[k], cycles[k]);
        if (!(d <= (c.constant() ? 1e-6f : 1e-4f))) ++bad;
        if (!(d <= worst)) worst = d, worst_pixel = i;
      }
    }
    // coords.exr stores the point + 4 as float (up to 2.4e-7 off); high octaves magnify that.
    if (worst > 1e-5f || c.constant())
      std::printf("%s: worst difference %.3g\n", c.name.c_str(), worst);
    worst_overall = std::max(worst_overall, worst);
    ++compared;
    EXPECT_EQ(bad, 0) << c.name << ": worst difference " << worst << " at pixel " << worst_pixel
                      << " (ours " << run(c, m.coords.at(worst_pixel) - Vec3(kCoordOffset))[0]
                      << ", Cycles " << ref.at(worst_pixel)[0] << ")";
  }
  std::printf("noise family: %d cases, worst difference %.3g\n", compared, worst_overall);
}

// Bad input: unknown modes are compile errors naming the value; non-finite and absurd inputs
// evaluate to finite outputs without hanging (Detail is clamped to 15 octaves).
TEST(NoiseNodes, BadInputIsReportedOrClamped) {
  ShaderProgram program;
  Instruction ins;
  std::string error;
  NodeDesc other;
  other.type = "ShaderNodeTexChecker";
  EXPECT_EQ(compile_noise_node(other, &program, &ins, &error), CompileStatus::kUnknownNode);
  NodeDesc bad;
  bad.type = "ShaderNodeTexMusgrave";
  bad.enums["musgrave_type"] = "PERLIN";
  EXPECT_EQ(compile_noise_node(bad, &program, &ins, &error), CompileStatus::kError);
  EXPECT_NE(error.find("PERLIN"), std::string::npos) << error;
  bad.type = "ShaderNodeTexNoise";
  bad.enums = {{"noise_dimensions", "5D"}};
  EXPECT_EQ(compile_noise_node(bad, &program, &ins, &error), CompileStatus::kError);
  EXPECT_NE(error.find("5D"), std::string::npos) << error;

  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  struct Node {
    const char* type;
    std::map<std::string, std::string> enums;
  };
  std::vector<Node> nodes;
  for (const char* d : {"1D", "2D", "3D", "4D"}) {
    nodes.push_back({"ShaderNodeTexNoise", {{"noise_dimensions", d}}});
    nodes.push_back({"ShaderNodeTexWhiteNoise", {{"noise_dimensions", d}}});
    for (const char* t :
         {"MULTIFRACTAL", "RIDGED_MULTIFRACTAL", "HYBRID_MULTIFRACTAL", "FBM", "HETERO_TERRAIN"})
      nodes.push_back(
          {"ShaderNodeTexMusgrave", {{"musgrave_dimensions", d}, {"musgrave_type", t}}});
  }
  for (const char* t : {"BANDS", "RINGS"})
    for (const char* prof : {"SIN", "SAW", "TRI"})
      nodes.push_back({"ShaderNodeTexWave", {{"wave_type", t}, {"wave_profile", prof}}});
  for (const Node& node : nodes) {
    for (float bad_value : {nan, inf, -inf, 1e30f}) {
      ShaderProgram p;
      NodeDesc desc;
      desc.type = node.type;
      desc.enums = node.enums;
      desc.inputs["Vector"] = 0;
      p.registers = {bad_value, 0.5f, -bad_value};
      for (const char* in : {"W", "Scale", "Detail"}) {
        desc.inputs[in] = static_cast<int32_t>(p.registers.size());
        p.registers.push_back(bad_value);
      }
      for (const char* out : {"Fac", "Value", "Color"}) {
        desc.outputs[out] = static_cast<int32_t>(p.registers.size());
        p.registers.insert(p.registers.end(), 3, -1.0f);
      }
      Instruction i;
      ASSERT_EQ(compile_noise_node(desc, &p, &i, &error), CompileStatus::kCompiled) << error;
      ShaderGlobals globals;
      eval_noise_node(i, p, globals, p.registers.data());
      for (size_t k = 6; k < p.registers.size(); ++k)
        EXPECT_TRUE(std::isfinite(p.registers[k]))
            << node.type << " " << node.enums.begin()->second << " input " << bad_value;
    }
  }
}

// Floats within `radius` of x (the coordinate coords.exr rounded away), or none when too many.
std::vector<float> candidates(float x, float radius, size_t limit) {
  std::vector<float> out;
  float lo = x - radius, hi = x + radius;
  if (!((hi - lo) / std::max(std::fabs(std::nextafter(std::fabs(x), 0.0f) - std::fabs(x)), 1e-30f) <
        static_cast<float>(limit)))
    return out;
  for (float v = lo; v <= hi; v = std::nextafter(v, hi + 1.0f)) out.push_back(v);
  return out;
}

// White Noise hashes the exact bits of the hit point, which coords.exr (the point + 4, rounded to
// float) does not keep. So each pixel searches the floats its coordinate could have been for one
// whose hash gives Cycles' value bit for bit; a wrong hash or seed matches almost never.
TEST(NoiseNodes, WhiteNoiseMatchesCyclesHashes) {
  const Manifest& m = manifest();
  ASSERT_GT(m.coords.width, 0) << "coords.exr not readable";
  constexpr float kRadius = 2.5e-7f;  // half an ulp of floats in [4, 8)
  int cases = 0;
  for (const Json& jc : m.cases) {
    if (!is_white_noise_linked(jc)) continue;
    Case c = build_case(jc);
    RgbImage ref;
    read_rgb_exr(m.dir / (c.name + ".exr"), &ref);
    ASSERT_EQ(ref.width * ref.height, m.coords.width * m.coords.height) << c.name;
    int eligible = 0, matched = 0;
    for (int i = 0; i < ref.width * ref.height; i += node_ref_pixel_stride()) {
      Vec3 p = m.coords.at(i) - Vec3(kCoordOffset);
      Vec3 cycles = ref.at(i);
      std::vector<float> axes[3];
      bool ok = true;
      if (c.scalar_reg >= 0) {  // 1D: W is the average of the point, searched directly
        axes[0] = candidates((p.x + p.y + p.z) * (1.0f / 3.0f), 1.2f * kRadius, 64);
        axes[1] = axes[2] = {0.0f};
        ok = !axes[0].empty() && std::fabs(axes[0][0]) > 0.1f;
      } else {
        for (int k = 0; k < 3; ++k) {
          axes[k] = candidates(p[k], kRadius, 24);
          ok = ok && !axes[k].empty() && std::fabs(p[k]) > 0.2f;
        }
        if (jc.find("properties")->find("noise_dimensions")->string == "2D") axes[2] = {p.z};
      }
      if (!ok) continue;
      ++eligible;
      bool found = false;
      for (float x : axes[0])
        for (float y : axes[1])
          for (float z : axes[2]) {
            if (found) break;
            std::vector<float> r = c.program.registers;
            if (c.vector_reg >= 0) store3(r.data(), c.vector_reg, Vec3(x, y, z));
            if (c.scalar_reg >= 0) r[c.scalar_reg] = x;
            ShaderGlobals globals;
            eval_noise_node(c.program.code[0], c.program, globals, r.data());
            Vec3 ours = c.output_is_color ? load3(r.data(), c.output_reg) : Vec3(r[c.output_reg]);
            found = ours.x == cycles.x && ours.y == cycles.y && ours.z == cycles.z;
          }
      matched += found;
    }
    ++cases;
    std::printf("%s: %d of %d pixels hash to Cycles' value exactly\n", c.name.c_str(), matched,
                eligible);
    EXPECT_GE(eligible, 300 / node_ref_pixel_stride()) << c.name;
    EXPECT_GE(matched, eligible * 95 / 100) << c.name;
  }
  EXPECT_EQ(cases, 8);
}

}  // namespace
}  // namespace noise_nodes_test
}  // namespace photon
