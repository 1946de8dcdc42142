// Mesh attributes: adding them (through clean_mesh's dropped triangles), interpolating corner,
// point and face data at barycentrics, ShaderGlobals carrying the mesh point, and the
// Attribute / Color Attribute / UV Map nodes' outputs as Cycles 3.4 gives them (measured with
// Blender 3.4.1: a missing attribute reads 0 with Alpha 1 on the Attribute node, Alpha 0 on
// Color Attribute; Fac is a 2D attribute's x, else the average of three channels).
#include "photon/shading/attribute_nodes.h"

#include <gtest/gtest.h>

#include <cmath>

#include "photon/render/accel.h"
#include "photon/render/shader_globals.h"
#include "photon/scene/mesh_attribute.h"
#include "photon/shading/normal_nodes.h"
#include "photon/shading/program_eval.h"

namespace photon {
namespace attribute_nodes_test {
namespace {

// Two triangles of a unit square sharing the edge (1, 3): (0, 1, 3) and (1, 2, 3).
Mesh square() {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.indices = {0, 1, 3, 1, 2, 3};
  return m;
}

float at(const MeshAttribute& a, uint32_t tri, float u, float v, int c = 0) {
  float out[4] = {-7, -7, -7, -7};
  EXPECT_TRUE(interpolate_attribute(a, tri, u, v, out));
  return out[c];
}

TEST(MeshAttributeTest, CornerValuesInterpolateWithEmbreeBarycentrics) {
  Mesh m = square();
  const std::vector<float> v = {1, 2, 3, 10, 20, 30};  // per corner
  std::string error;
  ASSERT_TRUE(add_mesh_attribute(&m, "c", 1, v.data(), v.size(), &error)) << error;
  const MeshAttribute& a = m.attributes[0];
  EXPECT_FLOAT_EQ(at(a, 0, 0, 0), 1.0f);  // corner 0
  EXPECT_FLOAT_EQ(at(a, 0, 1, 0), 2.0f);  // corner 1 weighs u
  EXPECT_FLOAT_EQ(at(a, 0, 0, 1), 3.0f);  // corner 2 weighs v
  EXPECT_FLOAT_EQ(at(a, 1, 0.25f, 0.5f), 0.25f * 10 + 0.25f * 20 + 0.5f * 30);
  float out[4];
  EXPECT_FALSE(interpolate_attribute(a, 2, 0, 0, out));  // no third triangle
}

TEST(MeshAttributeTest, PointValuesAreContinuousAndFaceValuesConstant) {
  Mesh m = square();
  // A point attribute expanded to corners: each corner takes its vertex's value.
  const float vertex[4] = {0.1f, 0.7f, 0.4f, 0.9f};
  std::vector<float> point, face;
  for (uint32_t i : m.indices) point.push_back(vertex[i]);
  for (float f : {0.25f, 0.75f})
    for (int c = 0; c < 3; ++c) face.push_back(f);
  std::string error;
  ASSERT_TRUE(add_mesh_attribute(&m, "p", 1, point.data(), point.size(), &error));
  ASSERT_TRUE(add_mesh_attribute(&m, "f", 1, face.data(), face.size(), &error));
  // The shared edge's midpoint, (1, 3) in both triangles: the same value from either side.
  const MeshAttribute& p = m.attributes[0];
  EXPECT_NEAR(at(p, 0, 0.5f, 0.5f), 0.5f * (0.7f + 0.9f), 1e-6f);
  EXPECT_NEAR(at(p, 1, 0.0f, 0.5f), 0.5f * (0.7f + 0.9f), 1e-6f);
  const MeshAttribute& f = m.attributes[1];
  EXPECT_FLOAT_EQ(at(f, 0, 0.3f, 0.3f), 0.25f);
  EXPECT_FLOAT_EQ(at(f, 1, 0.3f, 0.3f), 0.75f);
}

TEST(MeshAttributeTest, FollowsTrianglesCleanMeshDropped) {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.indices = {0, 1, 3, 0, 0, 1, 1, 2, 3};  // the middle triangle is degenerate
  clean_mesh(&m);
  ASSERT_EQ(m.triangle_count(), 2u);
  std::vector<float> v;
  for (int t = 0; t < 3; ++t)
    for (int c = 0; c < 3; ++c) v.insert(v.end(), {float(t), float(c)});
  std::string error;
  ASSERT_TRUE(add_mesh_attribute(&m, "uv", 2, v.data(), v.size(), &error)) << error;
  EXPECT_FLOAT_EQ(at(m.attributes[0], 1, 0, 0, 0), 2.0f);  // kept triangle 1 was given as 2
  EXPECT_FLOAT_EQ(at(m.attributes[0], 1, 0, 1, 1), 2.0f);  // its corner 2
  // Values for fewer triangles than were given are refused, the mesh unchanged.
  EXPECT_FALSE(add_mesh_attribute(&m, "short", 2, v.data(), 12, &error));
  EXPECT_FALSE(add_mesh_attribute(&m, "odd", 2, v.data(), 17, &error));
  EXPECT_FALSE(add_mesh_attribute(&m, "wide", 5, v.data(), 15, &error));
  EXPECT_EQ(m.attributes.size(), 1u);
}

TEST(MeshAttributeTest, CleanMeshCompactsAttributesAndNonFiniteValuesBecomeZero) {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.indices = {0, 1, 3, 0, 0, 1, 1, 2, 3};
  const std::vector<float> v = {0, 0, NAN, 5, 5, 5, 6, INFINITY, 6};
  std::string error;
  ASSERT_TRUE(add_mesh_attribute(&m, "a", 1, v.data(), v.size(), &error)) << error;
  EXPECT_FLOAT_EQ(m.attributes[0].values[2], 0.0f);
  clean_mesh(&m);  // drops the middle triangle: its values go with it
  ASSERT_EQ(m.attributes[0].values.size(), 6u);
  EXPECT_FLOAT_EQ(m.attributes[0].values[3], 6.0f);
  EXPECT_FLOAT_EQ(m.attributes[0].values[4], 0.0f);
}

// A one-node program over an attribute node; returns its registers after evaluation.
struct NodeRun {
  ShaderProgram program;
  std::vector<float> registers;
};

NodeRun run_node(const std::string& type, const std::string& name, const Mesh* mesh, uint32_t tri,
                 Vec2 bary, std::map<std::string, std::string> enums = {}) {
  NodeRun run;
  NodeDesc d;
  d.type = type;
  d.enums = std::move(enums);
  if (!name.empty()) d.enums["photon_attribute"] = name;
  d.outputs = {{"Color", 0}, {"Vector", 3}, {"Fac", 6}, {"Alpha", 7}, {"UV", 8}};
  run.program.registers.assign(11, -1.0f);
  std::string error;
  EXPECT_EQ(compile_node(d, &run.program, &error), CompileStatus::kCompiled) << error;
  ShaderGlobals g;
  g.mesh = mesh;
  g.primitive = tri;
  g.barycentric = bary;
  run.registers = run.program.registers;
  run_program(run.program, g, run.registers.data());
  return run;
}

TEST(AttributeNodeTest, OutputsPerComponentCountAsCycles) {
  Mesh m = square();
  std::string error;
  std::vector<float> f1(6, 0.3f), f2, f3, f4;
  for (int i = 0; i < 6; ++i) {
    f2.insert(f2.end(), {0.2f, 0.6f});
    f3.insert(f3.end(), {0.1f, 0.5f, 0.9f});
    f4.insert(f4.end(), {0.5f, 0.25f, 0.75f, 0.4f});
  }
  ASSERT_TRUE(add_mesh_attribute(&m, "f", 1, f1.data(), f1.size(), &error));
  ASSERT_TRUE(add_mesh_attribute(&m, "uv2", 2, f2.data(), f2.size(), &error));
  ASSERT_TRUE(add_mesh_attribute(&m, "vec", 3, f3.data(), f3.size(), &error));
  ASSERT_TRUE(add_mesh_attribute(&m, "col", 4, f4.data(), f4.size(), &error));
  const Vec2 b{0.2f, 0.3f};
  auto r = run_node("ShaderNodeAttribute", "f", &m, 1, b).registers;
  EXPECT_NEAR(r[0], 0.3f, 1e-6f);
  EXPECT_NEAR(r[2], 0.3f, 1e-6f);
  EXPECT_NEAR(r[6], 0.3f, 1e-6f);
  EXPECT_FLOAT_EQ(r[7], 1.0f);
  r = run_node("ShaderNodeAttribute", "uv2", &m, 1, b).registers;
  EXPECT_NEAR(r[3], 0.2f, 1e-6f);
  EXPECT_NEAR(r[4], 0.6f, 1e-6f);
  EXPECT_FLOAT_EQ(r[5], 0.0f);
  EXPECT_NEAR(r[6], 0.2f, 1e-6f);  // Fac: x
  EXPECT_FLOAT_EQ(r[7], 1.0f);
  r = run_node("ShaderNodeAttribute", "vec", &m, 0, b).registers;
  EXPECT_NEAR(r[6], 0.5f, 1e-6f);  // Fac: the average
  EXPECT_FLOAT_EQ(r[7], 1.0f);
  r = run_node("ShaderNodeAttribute", "col", &m, 0, b).registers;
  EXPECT_NEAR(r[1], 0.25f, 1e-6f);
  EXPECT_NEAR(r[6], 0.5f, 1e-6f);
  EXPECT_NEAR(r[7], 0.4f, 1e-6f);
  r = run_node("ShaderNodeVertexColor", "col", &m, 0, b).registers;
  EXPECT_NEAR(r[2], 0.75f, 1e-6f);
  EXPECT_NEAR(r[7], 0.4f, 1e-6f);
  r = run_node("ShaderNodeUVMap", "uv2", &m, 0, b).registers;
  EXPECT_NEAR(r[8], 0.2f, 1e-6f);
  EXPECT_NEAR(r[9], 0.6f, 1e-6f);
  EXPECT_FLOAT_EQ(r[10], 0.0f);
}

TEST(AttributeNodeTest, MissingAttributesReadAsCyclesReadsThem) {
  Mesh m = square();
  const Vec2 b{0.2f, 0.3f};
  auto r = run_node("ShaderNodeAttribute", "nope", &m, 0, b).registers;
  EXPECT_FLOAT_EQ(r[0], 0.0f);
  EXPECT_FLOAT_EQ(r[6], 0.0f);
  EXPECT_FLOAT_EQ(r[7], 1.0f);
  r = run_node("ShaderNodeAttribute", "", &m, 0, b).registers;  // no name: missing too
  EXPECT_FLOAT_EQ(r[3], 0.0f);
  EXPECT_FLOAT_EQ(r[7], 1.0f);
  r = run_node("ShaderNodeVertexColor", "nope", &m, 0, b).registers;
  EXPECT_FLOAT_EQ(r[0], 0.0f);
  EXPECT_FLOAT_EQ(r[7], 0.0f);
  r = run_node("ShaderNodeUVMap", "nope", &m, 0, b).registers;
  EXPECT_FLOAT_EQ(r[8], 0.0f);
  EXPECT_FLOAT_EQ(r[9], 0.0f);
  r = run_node("ShaderNodeAttribute", "nope", nullptr, 0, b).registers;  // the world
  EXPECT_FLOAT_EQ(r[0], 0.0f);
  EXPECT_FLOAT_EQ(r[7], 1.0f);
  // Object attributes are not exported: everything 0, Alpha too, even when the mesh has one.
  std::vector<float> f1(6, 0.3f);
  std::string error;
  ASSERT_TRUE(add_mesh_attribute(&m, "f", 1, f1.data(), f1.size(), &error));
  r = run_node("ShaderNodeAttribute", "f", &m, 0, b, {{"attribute_type", "OBJECT"}}).registers;
  EXPECT_FLOAT_EQ(r[0], 0.0f);
  EXPECT_FLOAT_EQ(r[6], 0.0f);
  EXPECT_FLOAT_EQ(r[7], 0.0f);
}

TEST(AttributeNodeTest, UnnamedUvMapStaysWithTheActiveMapAndNamesShareSlots) {
  NodeDesc d;
  d.type = "ShaderNodeUVMap";
  d.outputs = {{"UV", 0}};
  ShaderProgram p;
  p.registers.assign(3, 0.0f);
  std::string error;
  ASSERT_EQ(compile_node(d, &p, &error), CompileStatus::kCompiled);
  EXPECT_EQ(p.code[0].family, NodeFamily::kInput);
  d.enums["photon_attribute"] = "second";
  ASSERT_EQ(compile_node(d, &p, &error), CompileStatus::kCompiled);
  ASSERT_EQ(compile_node(d, &p, &error), CompileStatus::kCompiled);
  EXPECT_EQ(p.code[1].family, NodeFamily::kAttribute);
  EXPECT_EQ(p.attributes.size(), 1u);  // one slot per name
  EXPECT_EQ(p.code[2].mode, p.code[1].mode);
}

// A tangent-space Normal Map's output with its UV map named `uv_map` (empty: the active map,
// whose tangents `g` carries).
Vec3 normal_map(const std::string& uv_map, const ShaderGlobals& g) {
  NodeDesc d;
  d.type = "ShaderNodeNormalMap";
  d.enums["space"] = "TANGENT";
  if (!uv_map.empty()) d.enums["photon_attribute"] = uv_map;
  d.inputs = {{"Strength", 0}, {"Color", 1}};
  d.outputs = {{"Normal", 4}};
  ShaderProgram p;
  p.registers = {1.0f, 0.9f, 0.5f, 0.7f, 0, 0, 0};
  std::string error;
  EXPECT_EQ(compile_node(d, &p, &error), CompileStatus::kCompiled) << error;
  std::vector<float> r = p.registers;
  run_program(p, g, r.data());
  return load3(r.data(), 4);
}

TEST(AttributeNodeTest, NormalMapReadsTangentsOfItsNamedUvMap) {
  Mesh m = square();
  // "rot": the square's UVs turned a quarter: u runs along +y, v along -x.
  std::vector<float> rot;
  for (uint32_t i : m.indices) rot.insert(rot.end(), {m.positions[i].y, 1.0f - m.positions[i].x});
  std::string error;
  ASSERT_TRUE(add_mesh_attribute(&m, "rot", 2, rot.data(), rot.size(), &error));
  ShaderGlobals g;
  g.mesh = &m;
  g.primitive = 1;
  g.n = g.ng = Vec3(0, 0, 1);
  g.dpdu = Vec3(0, 1, 0), g.dpdv = Vec3(-1, 0, 0);  // the same frame as the active map
  const Vec3 active = normal_map("", g);
  g.dpdu = Vec3(1, 0, 0), g.dpdv = Vec3(0, 1, 0);  // the active map now differs
  const Vec3 named = normal_map("rot", g);
  EXPECT_NEAR(named.x, active.x, 1e-6f);
  EXPECT_NEAR(named.y, active.y, 1e-6f);
  EXPECT_NEAR(named.z, active.z, 1e-6f);
  EXPECT_GT(std::fabs(named.x - normal_map("", g).x), 0.1f);  // not the active map's answer
  const Vec3 missing = normal_map("nope", g);                 // Cycles: the normal unperturbed
  EXPECT_FLOAT_EQ(missing.z, 1.0f);
}

TEST(AttributeNodeTest, BumpOffsetsMoveTheBarycentrics) {
  // Bump evaluates its height at points offset along the surface: attributes must move too.
  Mesh m = square();
  ShaderGlobals g;
  g.mesh = &m;
  g.primitive = 0;  // corners (0,0), (1,0), (0,1): u along x, v along y
  g.barycentric = Vec2(0.2f, 0.3f);
  const ShaderGlobals s = offset_globals(g, Vec3(0.1f, -0.05f, 0.0f));
  EXPECT_NEAR(s.barycentric.x, 0.3f, 1e-6f);
  EXPECT_NEAR(s.barycentric.y, 0.25f, 1e-6f);
}

TEST(AttributeNodeTest, SurfaceGlobalsCarryTheMeshPoint) {
  Mesh m = square();
  SurfaceInteraction si;
  si.mesh = &m;
  si.primitive = 1;
  si.barycentric = Vec2(0.25f, 0.5f);
  si.ng = si.ns = Vec3(0, 0, 1);
  const ShaderGlobals g = surface_globals(si, Vec3(0, 0, 1), nullptr, nullptr, ShadeRay{});
  EXPECT_EQ(g.mesh, &m);
  EXPECT_EQ(g.primitive, 1u);
  EXPECT_FLOAT_EQ(g.barycentric.x, 0.25f);
  EXPECT_FLOAT_EQ(g.barycentric.y, 0.5f);
}

}  // namespace
}  // namespace attribute_nodes_test
}  // namespace photon
