// Attribute, Color Attribute and UV Map nodes against Cycles: test_scenes/nodes/attribute.json
// renders each case on a jittered triangle grid carrying UV maps and attributes of every
// supported type and domain (tools/node_refs.py writes the grid and its per-corner values to
// attribute/mesh.txt). Each pixel's Object coordinate (coords.exr) is located on the grid
// (triangle and Embree barycentrics), the node is compiled from the case's NodeDesc and
// evaluated there, and the result is compared with the Cycles render.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "photon/scene/mesh_attribute.h"
#include "photon/shading/attribute_nodes.h"
#include "photon/shading/program_eval.h"
#include "photon/testing/node_references.h"

namespace photon {
namespace attribute_nodes_cycles_test {
namespace {

namespace fs = std::filesystem;

constexpr float kCoordOffset = 4.0f;  // tools/node_refs.py's coords.exr offset

// attribute/mesh.txt: "vertices N", N lines x y z, "triangles T", T lines a b c, then per
// attribute "attribute NAME COMPONENTS [render_color]" and 3T lines of values.
Mesh read_grid(const fs::path& path) {
  std::ifstream in(path);
  Mesh mesh;
  std::string word;
  size_t count = 0;
  in >> word >> count;
  EXPECT_EQ(word, "vertices");
  mesh.positions.resize(count);
  for (Vec3& p : mesh.positions) in >> p.x >> p.y >> p.z;
  in >> word >> count;
  EXPECT_EQ(word, "triangles");
  mesh.indices.resize(3 * count);
  for (uint32_t& i : mesh.indices) in >> i;
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::istringstream header(line);
    std::string name, tag;
    uint32_t components = 0;
    header >> word >> name >> components >> tag;
    if (word != "attribute") continue;
    std::vector<float> values(3 * count * components);
    for (float& v : values) {
      double d;
      in >> d;
      v = static_cast<float>(d);
    }
    std::getline(in, line);
    std::string error;
    EXPECT_TRUE(add_mesh_attribute(&mesh, name, components, values.data(), values.size(), &error))
        << error;
    // The add-on exports the render colour attribute also under its reserved name.
    if (tag == "render_color")
      EXPECT_TRUE(add_mesh_attribute(&mesh, kRenderColorAttribute, components, values.data(),
                                     values.size(), &error));
  }
  return mesh;
}

// The triangle of the grid under (x, y) and its Embree barycentrics (the grid is a height
// field over x, y); the smallest barycentric weight says how near an edge the point is.
bool locate(const Mesh& mesh, float x, float y, uint32_t* tri, Vec2* bary, float* edge) {
  for (uint32_t t = 0; t < mesh.triangle_count(); ++t) {
    const Vec3& a = mesh.positions[mesh.indices[3 * t]];
    const Vec3& b = mesh.positions[mesh.indices[3 * t + 1]];
    const Vec3& c = mesh.positions[mesh.indices[3 * t + 2]];
    const double det = double(b.x - a.x) * (c.y - a.y) - double(c.x - a.x) * (b.y - a.y);
    const double u = (double(x - a.x) * (c.y - a.y) - double(c.x - a.x) * (y - a.y)) / det;
    const double v = (double(b.x - a.x) * (y - a.y) - double(x - a.x) * (b.y - a.y)) / det;
    const double w = 1.0 - u - v;
    if (u >= -1e-7 && v >= -1e-7 && w >= -1e-7) {
      *tri = t;
      *bary = Vec2(static_cast<float>(u), static_cast<float>(v));
      *edge = static_cast<float>(std::min(w, std::min(u, v)));
      return true;
    }
  }
  return false;
}

// The NodeDesc the add-on sends for a case (shader_program.py _attribute_name).
NodeDesc case_desc(const Json& c, int32_t output) {
  NodeDesc d;
  d.type = c.find("node")->string;
  auto prop = [&](const char* key) {
    const Json* props = c.find("properties");
    const Json* v = props ? props->find(key) : nullptr;
    return v ? v->string : std::string();
  };
  std::string name;
  if (d.type == "ShaderNodeAttribute") {
    const std::string type = prop("attribute_type");
    if (!type.empty()) d.enums["attribute_type"] = type;
    name = type.empty() || type == "GEOMETRY" ? prop("attribute_name") : "";
  } else if (d.type == "ShaderNodeVertexColor") {
    name = prop("layer_name").empty() ? kRenderColorAttribute : prop("layer_name");
  } else {
    name = prop("uv_map");
  }
  if (!name.empty()) d.enums["photon_attribute"] = name;
  d.outputs[c.find("output")->string] = output;
  return d;
}

TEST(AttributeNodes, MatchCyclesReferences) {
  const fs::path dir = node_refs_dir();
  ASSERT_FALSE(dir.empty()) << "test_scenes/nodes not found above " << fs::current_path();
  const Json manifest = read_json(dir / "attribute.json");
  const Mesh mesh = read_grid(dir / "attribute" / "mesh.txt");
  ASSERT_GT(mesh.triangle_count(), 0u);
  ASSERT_GE(mesh.attributes.size(), 15u);
  RgbImage coords;
  read_rgb_exr(dir / "attribute" / "coords.exr", &coords);
  ASSERT_GT(coords.width, 0);
  const float tol = 1e-4f;
  int cases = 0, edge_pixels = 0;
  float max_error = 0.0f;
  for (const Json& c : manifest.find("cases")->array) {
    const std::string name = c.find("name")->string;
    RgbImage ref;
    read_rgb_exr(dir / "attribute" / (name + ".exr"), &ref);
    ASSERT_EQ(ref.width, coords.width) << name;
    ShaderProgram program;
    program.registers.assign(5, 0.0f);
    const bool scalar = c.find("output")->string == "Fac" || c.find("output")->string == "Alpha";
    std::string error;
    ASSERT_EQ(compile_node(case_desc(c, 0), &program, &error), CompileStatus::kCompiled) << error;
    int bad = 0;
    float worst = 0.0f;
    for (int i = 0; i < coords.width * coords.height; i += node_ref_pixel_stride()) {
      const Vec3 co = coords.at(i) - Vec3(kCoordOffset);
      ShaderGlobals g;
      float edge = 0.0f;
      ASSERT_TRUE(locate(mesh, co.x, co.y, &g.primitive, &g.barycentric, &edge)) << name << i;
      g.mesh = &mesh;
      std::vector<float> r = program.registers;
      run_program(program, g, r.data());
      const Vec3 got = scalar ? Vec3(r[0]) : load3(r.data(), 0);
      const Vec3 want = ref.at(i);
      for (int k = 0; k < 3; ++k) {
        const float err = relative_error(got[k], want[k]);
        max_error = std::max(max_error, err);
        if (err <= tol) continue;
        // A pixel centre within float rounding of a triangle edge may hit the neighbour in
        // Cycles; face and corner values jump there.
        if (edge < 1e-5f) {
          ++edge_pixels;
          break;
        }
        ++bad;
        worst = std::max(worst, err);
        break;
      }
    }
    EXPECT_EQ(bad, 0) << name << ": worst error " << worst;
    ++cases;
  }
  EXPECT_GE(cases, 60);
  std::printf("attribute cases: %d, max error %g, pixels on a triangle edge that differ: %d\n",
              cases, max_error, edge_pixels);
}

}  // namespace
}  // namespace attribute_nodes_cycles_test
}  // namespace photon
