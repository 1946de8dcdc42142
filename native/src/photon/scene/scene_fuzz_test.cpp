// Seeded random scenes through the scene API the add-on uses (clean_mesh, gather_loop_mesh,
// snap_normals, sanitize_material, RenderSession, bake_points): meshes with NaN, infinite,
// huge or degenerate vertices and out-of-range indices, lights of every type with absurd
// parameters, random closures and texture indices, missing and corrupt image files, absurd
// cameras and settings; SPPM and VCM with absurd radii, iterations and budgets, and spectral
// mode over absurd Abbe numbers and lamp temperatures. Every input must be accepted or rejected
// with an exception or a warning; the render must finish with finite pixels (and no negative
// ones from SPPM, VCM or spectral mode) and the bake with finite radiance. Run
// under AddressSanitizer + UBSan (tools/sanitizer_tests.sh) this also catches memory errors and
// undefined behaviour.
//
// PHOTON_FUZZ_SECONDS bounds the random run (default 3 s); PHOTON_FUZZ_SEED picks its first seed
// (default 1). Seeds that once failed are listed in tests/fuzz/scene_fuzz_seeds.txt and replayed
// on every run.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "photon/scene/mesh_import.h"
#include "photon/scene/scene.h"
#include "photon/session/bake.h"
#include "photon/session/image_io.h"
#include "photon/session/render_session.h"

#ifndef PHOTON_FUZZ_SEEDS
#error "PHOTON_FUZZ_SEEDS must name the regression seed file"
#endif

namespace photon {
namespace scene_fuzz_test {
namespace {

namespace fs = std::filesystem;
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// SplitMix64 (Steele, Lea, Flood 2014): fixed output on every platform, unlike std::
// distributions, so a seed names the same scene everywhere.
class Random {
 public:
  explicit Random(uint64_t seed) : state_(seed) {}
  uint64_t next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  uint32_t below(uint32_t n) { return n ? static_cast<uint32_t>(next() % n) : 0; }
  bool chance(uint32_t percent) { return below(100) < percent; }
  float uniform(float lo, float hi) {
    return lo + (hi - lo) * static_cast<float>(next() >> 40) * 0x1p-24f;
  }
  // Mostly ordinary values in [lo, hi]; sometimes NaN, infinities, zero, huge, tiny, denormal.
  float weird(float lo, float hi, uint32_t weird_percent = 15) {
    if (!chance(weird_percent)) return uniform(lo, hi);
    static constexpr float kSpecial[] = {kNaN,  kInf,   -kInf,  0.0f,   -0.0f,
                                         1e30f, -1e30f, 1e-30f, 1e-40f, 3.4e38f,
                                         -1.0f, 1e6f,   -1e6f,  1e-7f,  65536.0f};
    return kSpecial[below(std::size(kSpecial))];
  }
  int pick(std::initializer_list<int> values) { return values.begin()[below(values.size())]; }

 private:
  uint64_t state_;
};

// Image files every scene can point at: good, NaN-filled, corrupt, truncated, empty, a folder.
struct TextureFiles {
  fs::path dir;
  std::vector<std::string> paths;
};

const TextureFiles& texture_files() {
  static const TextureFiles files = [] {
    TextureFiles f;
    f.dir = fs::temp_directory_path() / ("photon_fuzz_" + std::to_string(::getpid()));
    fs::create_directories(f.dir / "cache");
    // Converted textures go to a private cache that the test removes at exit.
    ::setenv("PHOTON_TEXTURE_CACHE", (f.dir / "cache").c_str(), 1);
    std::string error;
    std::vector<float> good(4 * 4 * 4, 0.5f), bad(3 * 2 * 4, 1.0f);
    bad[0] = kNaN;
    bad[5] = kInf;
    bad[9] = -kInf;
    bad[10] = -5.0f;
    bad[14] = 1e30f;
    const std::string good_png = (f.dir / "good.png").string();
    const std::string bad_exr = (f.dir / "nan.exr").string();
    write_rgba_image(good_png, good, 4, 4, &error);
    write_rgba_image(bad_exr, bad, 3, 2, &error);
    {
      std::ofstream corrupt(f.dir / "corrupt.png", std::ios::binary);
      corrupt << "\x89PNG\r\n\x1a\n this is not a png at all";
    }
    {
      std::ifstream in(bad_exr, std::ios::binary);
      std::string bytes((std::istreambuf_iterator<char>(in)), {});
      std::ofstream cut(f.dir / "truncated.exr", std::ios::binary);
      cut << bytes.substr(0, bytes.size() / 2);
    }
    std::ofstream(f.dir / "empty.jpg").close();
    fs::create_directories(f.dir / "folder.png");
    f.paths = {good_png,
               bad_exr,
               (f.dir / "corrupt.png").string(),
               (f.dir / "truncated.exr").string(),
               (f.dir / "empty.jpg").string(),
               (f.dir / "folder.png").string(),
               (f.dir / "missing.png").string(),
               ""};
    std::atexit([] {
      std::error_code ec;
      fs::remove_all(texture_files().dir, ec);
    });
    return f;
  }();
  return files;
}

Vec3 weird_vec(Random& r, float lo, float hi, uint32_t weird_percent = 15) {
  return {r.weird(lo, hi, weird_percent), r.weird(lo, hi, weird_percent),
          r.weird(lo, hi, weird_percent)};
}

// Rotation-and-scale matrices mostly; sometimes singular, sheared or non-finite.
Transform weird_transform(Random& r) {
  float rows[12];
  const bool wild = r.chance(25);
  for (int i = 0; i < 12; ++i) {
    const bool diagonal = i == 0 || i == 5 || i == 10;
    const bool translation = i % 4 == 3;
    rows[i] = wild          ? r.weird(-3.0f, 3.0f, 30)
              : diagonal    ? r.uniform(0.5f, 2.0f)
              : translation ? r.uniform(-2.0f, 2.0f)
                            : r.uniform(-0.3f, 0.3f);
  }
  if (r.chance(5)) std::fill(rows, rows + 12, 0.0f);
  return Transform::from_rows(rows);
}

uint32_t weird_index(Random& r, size_t count) {
  if (r.chance(90)) return r.below(static_cast<uint32_t>(count));
  return static_cast<uint32_t>(r.pick({-1, -7, 0x7fffffff, 1000000})) + r.below(3);
}

// A mesh the way add_mesh or add_loop_mesh builds it, cleaned like finish_mesh.
Mesh random_mesh(Random& r, int index) {
  Mesh mesh;
  mesh.name = "mesh" + std::to_string(index);
  const uint32_t vertices = r.below(24);
  for (uint32_t i = 0; i < vertices; ++i) mesh.positions.push_back(weird_vec(r, -2.0f, 2.0f, 8));
  const uint32_t triangles = r.below(30);
  if (r.chance(50)) {
    // add_loop_mesh: loops reference vertices, corners reference loops.
    const uint32_t loops = r.below(40);
    std::vector<int32_t> loop_vertices(loops), corner_loops(3 * triangles);
    for (auto& v : loop_vertices) v = static_cast<int32_t>(weird_index(r, vertices));
    for (auto& c : corner_loops) c = static_cast<int32_t>(weird_index(r, loops));
    std::vector<float> vertex_normals(3 * vertices), loop_normals(3 * loops), uvs(2 * loops);
    for (float& v : vertex_normals) v = r.weird(-1.0f, 1.0f);
    for (float& v : loop_normals) v = r.weird(-1.0f, 1.0f);
    for (float& v : uvs) v = r.weird(-2.0f, 2.0f);
    LoopMeshView view;
    view.corner_loops = corner_loops.data();
    view.corner_count = corner_loops.size();
    view.loop_vertices = loop_vertices.data();
    view.loop_count = loops;
    if (r.chance(40)) view.vertex_normals = vertex_normals.data();
    if (r.chance(40)) view.loop_normals = loop_normals.data();
    if (r.chance(50)) view.loop_uvs = uvs.data();
    gather_loop_mesh(view, &mesh);
  } else {
    for (uint32_t i = 0; i < 3 * triangles; ++i) mesh.indices.push_back(weird_index(r, vertices));
    // Per-corner arrays of the right size mostly, of a wrong size sometimes.
    const uint32_t corners = r.chance(85) ? 3 * triangles : r.below(3 * triangles + 5);
    if (r.chance(50))
      for (uint32_t i = 0; i < corners; ++i) mesh.corner_normals.push_back(weird_vec(r, -1, 1));
    if (r.chance(50))
      for (uint32_t i = 0; i < corners; ++i)
        mesh.corner_uvs.push_back({r.weird(-2.0f, 2.0f), r.weird(-2.0f, 2.0f)});
  }
  if (r.chance(50)) {
    const size_t slots = r.chance(85) ? mesh.triangle_count() : r.below(10);
    for (size_t i = 0; i < slots; ++i)
      mesh.material_slots.push_back(r.pick({-1, 0, 1, 2, 5, 1 << 30}));
  }
  clean_mesh(&mesh);
  snap_normals(&mesh);
  return mesh;
}

Input random_input(Random& r, float lo, float hi, size_t textures) {
  Input in = Input::constant(weird_vec(r, lo, hi, 20));
  if (r.chance(50)) in = Input::constant(in.value.x);
  if (r.chance(20)) {
    in.texture = r.chance(70) ? static_cast<int32_t>(r.below(static_cast<uint32_t>(textures) + 1))
                              : r.pick({-1, -2, 1 << 30});
    in.channel = r.chance(50) ? TextureChannel::kColor : TextureChannel::kAlpha;
  }
  return in;
}

// A material as parse_material builds it: raw values, then the shared sanitize_material.
Material random_material(Random& r, int index, size_t textures) {
  Material m;
  m.name = "material" + std::to_string(index);
  const uint32_t closures = r.below(4);
  for (uint32_t i = 0; i < closures; ++i) {
    Closure c;
    c.type = static_cast<ClosureType>(r.below(8));
    c.sharp = r.chance(30);
    for (size_t p = 0; p < c.params.size(); ++p)
      if (r.chance(50)) c.params[p] = random_input(r, -0.5f, 2.0f, textures);
    if (r.chance(20)) {
      c.normal.texture = r.chance(70) ? static_cast<int32_t>(r.below(textures + 1)) : -5;
      c.normal.strength = r.weird(0.0f, 3.0f, 30);
    }
    for (uint32_t w = r.below(3); w > 0; --w)
      c.weight.push_back({random_input(r, -0.5f, 1.5f, textures), r.chance(50)});
    m.closures.push_back(c);
  }
  sanitize_material(&m, textures);
  return m;
}

Light random_light(Random& r, int index) {
  Light l;
  l.name = "light" + std::to_string(index);
  l.type = static_cast<LightType>(r.below(4));
  l.light_to_world = weird_transform(r);
  l.color = weird_vec(r, 0.0f, 1.0f);
  l.power = r.weird(0.0f, 200.0f, 25);
  l.radius = r.weird(0.0f, 0.5f);
  l.spot_size = r.weird(0.0f, 3.2f);
  l.spot_blend = r.weird(0.0f, 1.0f);
  l.sun_angle = r.weird(0.0f, 3.2f);
  l.shape = r.chance(50) ? AreaShape::kRectangle : AreaShape::kEllipse;
  l.size_x = r.weird(0.0f, 2.0f);
  l.size_y = r.weird(0.0f, 2.0f);
  l.visibility = static_cast<uint32_t>(r.next());
  return l;
}

void random_camera(Random& r, Camera* c) {
  c->projection = r.chance(70) ? Projection::kPerspective : Projection::kOrthographic;
  Transform xf;
  xf.m[2][3] = 5.0f;  // in front of the origin, looking down -Z at it
  c->set_camera_to_world(r.chance(70) ? xf : weird_transform(r));
  const float half = r.weird(0.1f, 3.0f);
  c->window_min_x = r.chance(80) ? -half : r.weird(-2.0f, 2.0f, 40);
  c->window_max_x = r.chance(80) ? half : r.weird(-2.0f, 2.0f, 40);
  c->window_min_y = r.chance(80) ? -half : r.weird(-2.0f, 2.0f, 40);
  c->window_max_y = r.chance(80) ? half : r.weird(-2.0f, 2.0f, 40);
  c->clip_start = r.weird(0.0f, 1.0f);
  c->clip_end = r.weird(1.0f, 1000.0f);
  c->aperture_radius = r.chance(70) ? 0.0f : r.weird(0.0f, 0.5f);
  c->focus_distance = r.weird(0.0f, 10.0f);
}

std::shared_ptr<Scene> random_scene(Random& r) {
  auto scene = std::make_shared<Scene>();
  const auto& files = texture_files();
  for (uint32_t i = r.below(4); i > 0; --i) {
    ImageTexture t;
    t.path = files.paths[r.below(static_cast<uint32_t>(files.paths.size()))];
    t.srgb = r.chance(50);
    t.extension = static_cast<TextureExtension>(r.below(3));
    t.interpolation = static_cast<TextureInterpolation>(r.below(3));
    scene->textures.push_back(t);
  }
  for (int i = 0, n = static_cast<int>(r.below(4)); i < n; ++i)
    scene->meshes.push_back(random_mesh(r, i));
  for (int i = 0, n = static_cast<int>(r.below(5)); i < n; ++i) {
    Instance inst;
    inst.name = "instance" + std::to_string(i);
    inst.mesh = weird_index(r, std::max<size_t>(scene->meshes.size(), 1));
    inst.object_to_world = weird_transform(r);
    for (uint32_t s = r.below(4); s > 0; --s)
      inst.slot_materials.push_back(r.pick({-1, 0, 1, 3, 1 << 30}));
    inst.visibility = r.chance(70) ? kVisibleAll : static_cast<uint32_t>(r.next()) & kVisibleAll;
    scene->instances.push_back(inst);
  }
  for (int i = 0, n = static_cast<int>(r.below(4)); i < n; ++i)
    scene->materials.push_back(random_material(r, i, scene->textures.size()));
  for (int i = 0, n = static_cast<int>(r.below(4)); i < n; ++i)
    scene->lights.push_back(random_light(r, i));
  random_camera(r, &scene->camera);
  scene->world.color = r.chance(50) ? Vec3(0.0f) : weird_vec(r, 0.0f, 1.0f);
  return scene;
}

// Absurd values where the renderer clamps them; costly settings (resolution, samples, photons,
// rays) stay small or absurdly low so a case takes well under a second.
RenderSettings random_settings(Random& r, IntegratorType integrator) {
  RenderSettings s;
  s.integrator = integrator;
  s.full_width = r.pick({-5, 0, 1, 2, 5, 12});
  s.full_height = r.pick({-5, 0, 1, 3, 8});
  s.x0 = r.pick({-3, 0, 0, 1, 100});
  s.y0 = r.pick({-3, 0, 0, 2, 100});
  s.x1 = r.pick({-1, 0, 4, 12, 1 << 30});
  s.y1 = r.pick({-1, 0, 3, 8, 1 << 30});
  s.samples = r.pick({-4, 0, 1, 2, 3});
  s.max_depth = r.pick({-1, 0, 1, 3, 8, 1 << 30});
  s.seed = r.next();
  s.threads = r.pick({-2, 0, 1, 2, 3});
  s.tile_size = r.pick({-1, 0, 1, 3, 8, 1 << 30});
  s.transparent_background = r.chance(50);
  s.light_passes = r.chance(50);
  s.photons = static_cast<uint64_t>(r.pick({0, 1, 7, 500, 3000}));
  s.caustic_photons = static_cast<uint64_t>(r.pick({0, 1, 300, 2000}));
  s.gather_count = r.pick({-5, 0, 1, 10, 50, 1 << 30});
  s.gather_radius = r.weird(0.0f, 1.0f, 40);
  s.caustic_gather_count = r.pick({-5, 0, 1, 20, 1 << 30});
  s.final_gather_rays = r.pick({-1, 0, 1, 2, 4});
  s.photon_time = r.chance(80) ? 0.0f : r.pick({-1, 0}) + (r.chance(50) ? kNaN : 0.02f);
  s.irradiance_cache = r.chance(50);
  // Automatic, absurd or huge: a small patch size on a huge scene asks for the 4M-element cap
  // (accepted with a warning, but gigabytes under ASan).
  s.radiosity_patch_size = r.chance(50) ? 0.0f : r.weird(1e30f, 1e30f, 70);
  s.radiosity_rays = static_cast<uint64_t>(r.pick({0, 1, 1000, 20000}));
  s.radiosity_threshold = r.weird(0.0f, 0.1f, 40);
  s.radiosity_iterations = r.pick({-1, 0, 1, 3});
  return s;
}

std::string describe(const Scene& scene) {
  size_t triangles = 0;
  for (const Mesh& m : scene.meshes) triangles += m.triangle_count();
  std::ostringstream o;
  o << scene.meshes.size() << " meshes (" << triangles << " triangles), " << scene.instances.size()
    << " instances, " << scene.materials.size() << " materials, " << scene.textures.size()
    << " textures, " << scene.lights.size() << " lights";
  return o.str();
}

// PHOTON_FUZZ_VERBOSE=1 prints each render's time and statistics.
bool verbose() {
  static const bool on = std::getenv("PHOTON_FUZZ_VERBOSE") != nullptr;
  return on;
}

constexpr const char* kIntegratorNames[] = {"RAY_TRACE", "PHOTON_MAP", "RADIOSITY", "SPPM", "VCM"};

// Renders `scene` with `settings` and checks what every render must give whatever the input:
// no failure, no cancel, an image of the clamped size, finite pixels and passes. Returns the
// image.
std::vector<float> render_and_check(const std::shared_ptr<Scene>& scene,
                                    const RenderSettings& settings) {
  const IntegratorType type = settings.integrator;
  const auto t0 = std::chrono::steady_clock::now();
  RenderSession session(scene, settings);
  session.start();
  std::vector<float> passes;
  const auto keep_passes = [&passes](const Tile& t) {
    for (const PassImage& pass : t.passes)
      passes.insert(passes.end(), pass.pixels.begin(), pass.pixels.end());
  };
  while (!session.finished()) {
    for (Tile& t : session.take_tiles(0.05)) keep_passes(t);
  }
  session.wait();
  for (Tile& t : session.take_tiles(0.0)) keep_passes(t);
  for (const std::string& w : session.warnings())
    EXPECT_EQ(w.rfind("Render failed", 0), std::string::npos) << w;
  EXPECT_FALSE(session.cancelled());
  const std::vector<float> image = session.image();
  const RenderSettings clamped = sanitized_settings(settings);
  EXPECT_EQ(image.size(),
            static_cast<size_t>(clamped.x1 - clamped.x0) * (clamped.y1 - clamped.y0) * 4);
  size_t bad = 0;
  for (float v : image) bad += !std::isfinite(v);
  for (float v : passes) bad += !std::isfinite(v);
  EXPECT_EQ(bad, 0u) << "non-finite pixel values";
  if (verbose()) {
    std::fprintf(stderr, "  %s %.2f s:", kIntegratorNames[static_cast<int>(type)],
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    const PrepareStats& prepared = session.stats().integrator;
    if (prepared.photon_map)
      std::fprintf(stderr, " photons_stored=%llu",
                   static_cast<unsigned long long>(prepared.photon_map->global_photons_stored));
    if (prepared.radiosity)
      std::fprintf(stderr, " radiosity_patches=%llu",
                   static_cast<unsigned long long>(prepared.radiosity->patches));
    std::fprintf(stderr, "\n");
  }
  return image;
}

// SPPM and VCM with absurd radii and budgets, and spectral mode over absurd Abbe numbers and
// lamp temperatures (an 800 K lamp has no colour inside Rec.709), on a copy of the seed's scene.
// Drawn from a generator of their own, so the draws above (and the stored seeds' cases) are
// unchanged.
void progressive_and_spectral_case(uint64_t seed, const Scene& base) {
  Random r(seed * 0x9E3779B97F4A7C15ull + 0x5EC7);
  auto scene = std::make_shared<Scene>(base);
  for (Material& m : scene->materials)
    for (Closure& c : m.closures) c.abbe = r.weird(0.0f, 80.0f, 40);
  for (Light& l : scene->lights) {
    l.spectrum = static_cast<LightSpectrum>(r.below(3));
    l.temperature = r.weird(800.0f, 12000.0f, 30);
  }
  for (IntegratorType type :
       {IntegratorType::kSppm, IntegratorType::kVcm, static_cast<IntegratorType>(r.below(3))}) {
    SCOPED_TRACE(std::string(kIntegratorNames[static_cast<int>(type)]) + " spectral/progressive");
    RenderSettings s = random_settings(r, type);
    s.spectral = r.chance(50);
    s.spectral_samples = r.pick({-1, 0, 1, 4, 9});
    s.sppm_iterations = s.vcm_iterations = r.pick({-1, 0, 1, 2});
    s.sppm_photons_per_iteration = s.vcm_light_paths = static_cast<uint64_t>(r.pick({0, 1, 300}));
    // Automatic, or from 1e-12 to 1e9 evenly in the exponent, or NaN, infinite, denormal...
    const float radius =
        r.pick({0, 1, 2, 3, 4}) == 0
            ? 0.0f
            : (r.chance(30) ? r.weird(0.0f, 1.0f, 100) : std::pow(10.0f, r.uniform(-12.0f, 9.0f)));
    s.sppm_initial_radius = s.vcm_initial_radius = r.chance(90) ? radius : -radius;
    s.sppm_alpha = s.vcm_alpha = r.weird(0.0f, 1.0f, 30);
    s.vcm_mode = static_cast<VcmMode>(r.below(3));
    const std::vector<float> image = render_and_check(scene, s);
    // Light outside the Rec.709 gamut resolves into it; the filters have no negative lobes.
    size_t negative = 0;
    for (float v : image) negative += v < 0.0f;
    EXPECT_EQ(negative, 0u) << "negative pixel values, spectral " << s.spectral;
  }
}

// One seed: a scene rendered by each integrator, then a bake of a few points. Failures are
// reported as gtest failures naming the seed.
void run_case(uint64_t seed) {
  Random r(seed);
  const auto t_scene = std::chrono::steady_clock::now();
  std::shared_ptr<Scene> scene = random_scene(r);
  // Area-light spreads from a generator of their own, so the stored seeds' scenes are unchanged
  // otherwise: half of the lights keep the whole hemisphere.
  Random spreads(seed * 0x9E3779B97F4A7C15ull + 0x5B2E);
  for (Light& l : scene->lights)
    if (spreads.chance(50)) l.spread = spreads.weird(0.0f, 3.2f, 30);
  if (verbose())
    std::fprintf(stderr, "  scene %.2f s\n",
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t_scene).count());
  SCOPED_TRACE("seed " + std::to_string(seed) + ": " + describe(*scene));
  for (IntegratorType type :
       {IntegratorType::kRayTrace, IntegratorType::kPhotonMap, IntegratorType::kRadiosity}) {
    SCOPED_TRACE(kIntegratorNames[static_cast<int>(type)]);
    render_and_check(scene, random_settings(r, type));
  }

  // A bake of a few points, valid and invalid, with each integrator that can bake.
  std::vector<BakePoint> points(r.below(6));
  for (BakePoint& p : points) {
    p.instance = weird_index(r, std::max<size_t>(scene->instances.size(), 1));
    p.triangle = weird_index(r, 8);
    p.u = r.weird(0.0f, 0.5f);
    p.v = r.weird(0.0f, 0.5f);
  }
  const IntegratorType bake_type =
      r.chance(50) ? IntegratorType::kPhotonMap : IntegratorType::kRadiosity;
  SCOPED_TRACE(std::string("bake with ") + kIntegratorNames[static_cast<int>(bake_type)]);
  BakeOptions options;
  options.brighter_side = r.chance(50);
  const auto t0 = std::chrono::steady_clock::now();
  const BakeResult result =
      bake_points(*scene, random_settings(r, bake_type), options, points, PrepareControl{});
  // A non-empty result.error is a rejection (the binding raises it as RuntimeError).
  if (verbose())
    std::fprintf(stderr, "  bake of %zu points %.2f s\n", points.size(),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  ASSERT_EQ(result.radiance.size(), points.size());
  ASSERT_EQ(result.status.size(), points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    EXPECT_TRUE(is_finite(result.radiance[i])) << "point " << i;
    EXPECT_TRUE(is_finite(result.position[i])) << "point " << i;
    EXPECT_TRUE(is_finite(result.normal[i])) << "point " << i;
  }

  progressive_and_spectral_case(seed, *scene);
}

uint64_t env_u64(const char* name, uint64_t fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::strtoull(v, nullptr, 10) : fallback;
}

std::vector<uint64_t> regression_seeds() {
  std::vector<uint64_t> seeds;
  std::ifstream in(PHOTON_FUZZ_SEEDS);
  EXPECT_TRUE(in.good()) << "cannot read " << PHOTON_FUZZ_SEEDS;
  std::string line;
  while (std::getline(in, line)) {
    line = line.substr(0, line.find('#'));
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    seeds.push_back(std::stoull(line));
  }
  return seeds;
}

TEST(SceneFuzz, RegressionSeedsStillPass) {
  const std::vector<uint64_t> seeds = regression_seeds();
  EXPECT_FALSE(seeds.empty());
  for (uint64_t seed : seeds) {
    run_case(seed);
    if (::testing::Test::HasFailure()) return;
  }
}

TEST(SceneFuzz, RandomScenesRenderAndBakeSafely) {
  const double budget = static_cast<double>(env_u64("PHOTON_FUZZ_SECONDS", 3));
  const uint64_t first = env_u64("PHOTON_FUZZ_SEED", 1);
  const auto t0 = std::chrono::steady_clock::now();
  uint64_t seed = first;
  for (;; ++seed) {
    // Printed before the case runs: a crash (or a sanitizer abort) leaves its seed in the log.
    std::fprintf(stderr, "scene fuzz: seed %llu\n", static_cast<unsigned long long>(seed));
    run_case(seed);
    if (::testing::Test::HasFailure()) {
      ADD_FAILURE() << "seed " << seed
                    << " failed: add it to tests/fuzz/scene_fuzz_seeds.txt once fixed";
      return;
    }
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() >= budget)
      break;
  }
  std::printf("scene fuzz: seeds %llu..%llu passed in %.0f s\n",
              static_cast<unsigned long long>(first), static_cast<unsigned long long>(seed),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
}

}  // namespace
}  // namespace scene_fuzz_test
}  // namespace photon
