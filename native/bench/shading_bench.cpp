// Shader-program cost: evaluations per second of a 20-node procedural material (coordinates,
// mapping, noise, voronoi, ramps, mixes, maths and a bump) against a constant material, through
// the whole shade_surface (the BSDF built from the closures included).
// Run: build/shading_bench
#include <benchmark/benchmark.h>

#include <memory>
#include <string>
#include <vector>

#include "photon/render/material_eval.h"
#include "photon/scene/camera.h"
#include "photon/session/scene_resources.h"
#include "photon/shading/program_eval.h"
#include "photon/testing/test_scenes.h"

using namespace photon;

namespace {

// A program builder for the benchmark: registers by hand, as the add-on allocates them.
struct Builder {
  ShaderProgram program;
  int32_t reg(std::vector<float> values) {
    const int32_t r = static_cast<int32_t>(program.registers.size());
    program.registers.insert(program.registers.end(), values.begin(), values.end());
    return r;
  }
  int32_t vec() { return reg({0, 0, 0}); }
  int32_t scalar() { return reg({0}); }
  void node(NodeDesc d) {
    std::string error;
    if (compile_node(d, &program, &error) != CompileStatus::kCompiled)
      throw std::runtime_error(d.type + ": " + error);
  }
};

std::vector<float> ramp_table(Vec3 a, Vec3 b) {
  std::vector<float> t{1.0f};
  for (int i = 0; i < 256; ++i) {
    const Vec3 c = lerp(a, b, i / 255.0f);
    t.insert(t.end(), {c.x, c.y, c.z, 1.0f});
  }
  return t;
}

// 20 nodes: Texture Coordinate, Mapping, Noise, ColorRamp, Voronoi, ColorRamp, Mix (multiply),
// Math x4, Wave, Mix, Vector Math, Separate Color, Gradient, Map Range, Checker, Mix, Bump.
Material procedural_material() {
  Builder b;
  const int32_t generated = b.vec(), object = b.vec();
  b.node({"ShaderNodeTexCoord", {}, {}, {}, {{"Generated", generated}, {"Object", object}}, {}});
  const int32_t mapped = b.vec();
  b.node({"ShaderNodeMapping",
          {{"vector_type", "POINT"}},
          {},
          {{"Vector", object},
           {"Location", b.reg({0.1f, 0.2f, 0.3f})},
           {"Rotation", b.reg({0.2f, 0.0f, 0.5f})},
           {"Scale", b.reg({2.0f, 2.0f, 2.0f})}},
          {{"Vector", mapped}},
          {}});
  const int32_t noise = b.scalar();
  b.node({"ShaderNodeTexNoise",
          {{"noise_dimensions", "3D"}},
          {},
          {{"Vector", mapped},
           {"Scale", b.reg({5})},
           {"Detail", b.reg({4})},
           {"Roughness", b.reg({0.5f})},
           {"Distortion", b.reg({0.3f})}},
          {{"Fac", noise}},
          {}});
  const int32_t ramp1 = b.vec();
  b.node({"ShaderNodeValToRGB",
          {},
          {},
          {{"Fac", noise}},
          {{"Color", ramp1}},
          ramp_table({0.2f, 0.1f, 0.05f}, {0.8f, 0.6f, 0.3f})});
  const int32_t cells = b.scalar();
  b.node({"ShaderNodeTexVoronoi",
          {{"voronoi_dimensions", "3D"}, {"feature", "F1"}, {"distance", "EUCLIDEAN"}},
          {},
          {{"Vector", mapped}, {"Scale", b.reg({8})}, {"Randomness", b.reg({1})}},
          {{"Distance", cells}},
          {}});
  const int32_t ramp2 = b.vec();
  b.node({"ShaderNodeValToRGB",
          {},
          {},
          {{"Fac", cells}},
          {{"Color", ramp2}},
          ramp_table({0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f})});
  const int32_t mixed = b.vec();
  b.node({"ShaderNodeMix",
          {{"data_type", "RGBA"}, {"blend_type", "MULTIPLY"}},
          {},
          {{"Factor_Float", b.reg({0.7f})}, {"A_Color", ramp1}, {"B_Color", ramp2}},
          {{"Result_Color", mixed}},
          {}});
  int32_t value = noise;
  for (const char* op : {"MULTIPLY", "ADD", "SINE", "ABSOLUTE"}) {
    const int32_t out = b.scalar();
    b.node({"ShaderNodeMath",
            {{"operation", op}},
            {},
            {{"Value", value}, {"Value_001", b.reg({1.7f})}},
            {{"Value", out}},
            {}});
    value = out;
  }
  const int32_t wave = b.scalar();
  b.node({"ShaderNodeTexWave",
          {{"wave_type", "RINGS"}},
          {},
          {{"Vector", mapped},
           {"Scale", b.reg({3})},
           {"Distortion", b.reg({2})},
           {"Detail", b.reg({2})}},
          {{"Fac", wave}},
          {}});
  const int32_t mixed2 = b.vec();
  b.node({"ShaderNodeMix",
          {{"data_type", "RGBA"}, {"blend_type", "OVERLAY"}},
          {},
          {{"Factor_Float", value}, {"A_Color", mixed}, {"B_Color", ramp1}},
          {{"Result_Color", mixed2}},
          {}});
  const int32_t offset = b.vec();
  b.node({"ShaderNodeVectorMath",
          {{"operation", "ADD"}},
          {},
          {{"Vector", generated}, {"Vector_001", mixed2}},
          {{"Vector", offset}},
          {}});
  const int32_t red = b.scalar();
  b.node(
      {"ShaderNodeSeparateColor", {{"mode", "RGB"}}, {}, {{"Color", offset}}, {{"Red", red}}, {}});
  const int32_t gradient = b.scalar();
  b.node({"ShaderNodeTexGradient",
          {{"gradient_type", "SPHERICAL"}},
          {},
          {{"Vector", offset}},
          {{"Fac", gradient}},
          {}});
  const int32_t ranged = b.scalar();
  b.node({"ShaderNodeMapRange",
          {{"data_type", "FLOAT"}, {"interpolation_type", "SMOOTHSTEP"}},
          {},
          {{"Value", gradient},
           {"From Min", b.reg({0})},
           {"From Max", b.reg({1})},
           {"To Min", b.reg({0.2f})},
           {"To Max", b.reg({0.9f})}},
          {{"Result", ranged}},
          {}});
  const int32_t checker = b.vec();
  b.node({"ShaderNodeTexChecker",
          {},
          {},
          {{"Vector", mapped},
           {"Color1", b.reg({0.9f, 0.9f, 0.9f})},
           {"Color2", b.reg({0.1f, 0.1f, 0.1f})},
           {"Scale", b.reg({4})}},
          {{"Color", checker}},
          {}});
  const int32_t albedo = b.vec();
  b.node({"ShaderNodeMix",
          {{"data_type", "RGBA"}, {"blend_type", "MIX"}},
          {},
          {{"Factor_Float", ranged}, {"A_Color", mixed2}, {"B_Color", checker}},
          {{"Result_Color", albedo}},
          {}});
  b.node({"PhotonBlockBegin", {}, {}, {}, {}, {}});
  const int32_t height = b.scalar();
  b.node({"ShaderNodeTexNoise",
          {{"noise_dimensions", "3D"}},
          {},
          {{"Scale", b.reg({12})}, {"Detail", b.reg({2})}},
          {{"Fac", height}},
          {}});
  const int32_t bumped = b.vec();
  b.node({"ShaderNodeBump",
          {{"invert", "False"}},
          {{"block", 1}},
          {{"Strength", b.reg({0.5f})}, {"Distance", b.reg({0.1f})}, {"Height", height}},
          {{"Normal", bumped}},
          {}});
  b.program.registers.resize(b.program.registers.size() + 2, 0.0f);

  Material m = Material::diffuse(Vec3(0.8f), "procedural");
  m.closures[0].type = ClosureType::kPrincipled;
  m.closures[0].params = Closure::default_params();
  m.closures[0][Param::kColor].reg = albedo;
  m.closures[0][Param::kRoughness].reg = ranged;
  m.closures[0].normal_reg = bumped;
  m.program = std::move(b.program);
  return m;
}

Material constant_material() {
  Material m = Material::diffuse(Vec3(0.8f), "constant");
  m.closures[0].type = ClosureType::kPrincipled;
  m.closures[0].params = Closure::default_params();
  m.closures[0][Param::kColor] = Input::constant(Vec3(0.6f, 0.4f, 0.2f));
  return m;
}

struct Fixture {
  Scene scene = make_cornell_box();
  std::vector<std::string> warnings;
  RenderSettings settings;
  std::unique_ptr<SceneResources> resources;
  std::vector<SurfaceInteraction> hits;

  explicit Fixture(Material material) {
    for (Material& m : scene.materials) m = material;
    resources = std::make_unique<SceneResources>(scene, settings, &warnings);
    // Shading points where camera rays meet the box's walls and blocks.
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x) {
        Ray ray =
            generate_camera_ray(scene.camera, (x + 0.5f) / 32, (y + 0.5f) / 32, Vec2(0.5f, 0.5f));
        Hit hit;
        if (resources->accel().intersect(ray, kVisibleCamera, &hit))
          hits.push_back(resources->accel().interaction(hit));
      }
  }
};

void shade_all(benchmark::State& state, Material material) {
  Fixture f(std::move(material));
  const Accel& accel = f.resources->accel();
  const TextureSet* textures = &f.resources->textures();
  ShadeRay camera;
  camera.flags = kRayCamera;
  camera.length = 3.0f;
  for (auto _ : state)
    for (const SurfaceInteraction& si : f.hits) {
      ShadingPoint sp = shade_surface(si, -si.ng, accel, textures, camera);
      benchmark::DoNotOptimize(sp);
    }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(f.hits.size()));
}

void BM_Shade_ConstantMaterial(benchmark::State& state) {
  shade_all(state, constant_material());
}
void BM_Shade_Procedural20Nodes(benchmark::State& state) {
  shade_all(state, procedural_material());
}

void BM_Program_Procedural20Nodes(benchmark::State& state) {
  const Material m = procedural_material();
  ShaderGlobals g;
  g.bump_step = 1e-3f;
  uint64_t i = 0;
  for (auto _ : state) {
    g.p = Vec3(0.001f * (i % 1000), 0.37f, 0.002f * (i % 777));
    g.generated = g.p;
    ProgramRegisters registers(m.program);
    run_program(m.program, g, registers.data());
    benchmark::DoNotOptimize(registers.data()[0]);
    ++i;
  }
  state.SetItemsProcessed(state.iterations());
}

}  // namespace

BENCHMARK(BM_Shade_ConstantMaterial);
BENCHMARK(BM_Shade_Procedural20Nodes);
BENCHMARK(BM_Program_Procedural20Nodes);
BENCHMARK_MAIN();
