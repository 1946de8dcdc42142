#include "photon/testing/sds_scenes.h"

#include <cmath>
#include <utility>

#include "photon/testing/test_scenes.h"

namespace photon {
namespace {

int32_t add_material(Scene* scene, Material m) {
  scene->materials.push_back(std::move(m));
  return static_cast<int32_t>(scene->materials.size() - 1);
}

// The pool's water surface above its rest height: three crossing sine waves (slopes up to about
// 15 degrees, curved enough to focus near the floor). test_scenes/sds.py evaluates the same
// function.
struct Wave {
  float amplitude, kx, ky, phase;
};
constexpr Wave kWaves[] = {
    {0.004f, 22.0f, 8.0f, 0.3f}, {0.003f, -12.0f, 27.0f, 1.1f}, {0.0025f, 30.0f, -18.0f, 2.0f}};

float wave_height(float x, float y) {
  float h = 0.0f;
  for (const Wave& w : kWaves) h += w.amplitude * std::sin(w.kx * x + w.ky * y + w.phase);
  return h;
}

// The upward normal of z = rest + wave_height(x, y).
Vec3 wave_normal(float x, float y) {
  float dx = 0.0f, dy = 0.0f;
  for (const Wave& w : kWaves) {
    const float c = w.amplitude * std::cos(w.kx * x + w.ky * y + w.phase);
    dx += c * w.kx;
    dy += c * w.ky;
  }
  return normalize(Vec3(-dx, -dy, 1.0f));
}

}  // namespace

Mesh make_wavy_slab(float half, float bottom, float top, int cells) {
  Mesh m;
  m.name = "water";
  const int n = cells + 1;
  auto coord = [&](int i) { return -half + 2.0f * half * static_cast<float>(i) / cells; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const float x = coord(i), y = coord(j);
      m.positions.push_back({x, y, top + wave_height(x, y)});
    }
  auto top_index = [&](int i, int j) { return static_cast<uint32_t>(j * n + i); };
  auto add_triangle = [&](uint32_t a, uint32_t b, uint32_t c, bool smooth) {
    m.indices.insert(m.indices.end(), {a, b, c});
    for (uint32_t k : {a, b, c}) {
      const Vec3& p = m.positions[k];
      m.corner_normals.push_back(smooth ? wave_normal(p.x, p.y) : Vec3(0.0f));
    }
  };
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const uint32_t a = top_index(i, j), b = top_index(i + 1, j);
      const uint32_t c = top_index(i + 1, j + 1), d = top_index(i, j + 1);
      add_triangle(a, b, c, true);
      add_triangle(a, c, d, true);
    }
  // Flat faces: their corner normals are the face normal.
  auto add_flat = [&](uint32_t a, uint32_t b, uint32_t c) {
    const Vec3 nf =
        normalize(cross(m.positions[b] - m.positions[a], m.positions[c] - m.positions[a]));
    m.indices.insert(m.indices.end(), {a, b, c});
    for (int k = 0; k < 3; ++k) m.corner_normals.push_back(nf);
  };
  // Bottom: four corners, facing -z.
  const auto base = static_cast<uint32_t>(m.positions.size());
  m.positions.push_back({-half, -half, bottom});
  m.positions.push_back({half, -half, bottom});
  m.positions.push_back({half, half, bottom});
  m.positions.push_back({-half, half, bottom});
  add_flat(base, base + 2, base + 1);
  add_flat(base, base + 3, base + 2);
  // Sides: each edge of the top grid down to a bottom vertex under it.
  auto side = [&](auto top_at, Vec3 outward) {
    for (int k = 0; k < cells; ++k) {
      const uint32_t t0 = top_at(k), t1 = top_at(k + 1);
      const Vec3 p0 = m.positions[t0], p1 = m.positions[t1];
      const auto b0 = static_cast<uint32_t>(m.positions.size());
      m.positions.push_back({p0.x, p0.y, bottom});
      m.positions.push_back({p1.x, p1.y, bottom});
      // Wound so the face normal points `outward`.
      const Vec3 nf = cross(p1 - p0, Vec3(p0.x, p0.y, bottom) - p0);
      if (dot(nf, outward) > 0.0f) {
        add_flat(t0, t1, b0);
        add_flat(t1, b0 + 1, b0);
      } else {
        add_flat(t0, b0, t1);
        add_flat(t1, b0, b0 + 1);
      }
    }
  };
  side([&](int k) { return top_index(k, 0); }, Vec3(0, -1, 0));
  side([&](int k) { return top_index(cells, k); }, Vec3(1, 0, 0));
  side([&](int k) { return top_index(k, cells); }, Vec3(0, 1, 0));
  side([&](int k) { return top_index(0, k); }, Vec3(-1, 0, 0));
  return m;
}

namespace {

// A floor of tiles x tiles squares over [-half, half]^2 at z = 0 in two materials (slots 0
// and 1, slot 0 at the (-x, -y) corner), facing +z.
Mesh make_checker_floor(float half, int tiles) {
  Mesh m;
  m.name = "floor";
  const int n = tiles + 1;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      m.positions.push_back({-half + 2.0f * half * i / tiles, -half + 2.0f * half * j / tiles, 0});
  for (int j = 0; j < tiles; ++j)
    for (int i = 0; i < tiles; ++i) {
      const auto a = static_cast<uint32_t>(j * n + i);
      m.indices.insert(m.indices.end(), {a, a + 1, a + 1 + n, a, a + 1 + n, a + n});
      const int32_t slot = (i + j) % 2;
      m.material_slots.insert(m.material_slots.end(), {slot, slot});
    }
  return m;
}

// The mesh seen from the other side: every triangle wound the other way, normals negated.
Mesh turned_inside_out(Mesh m) {
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    std::swap(m.indices[3 * t + 1], m.indices[3 * t + 2]);
    if (!m.corner_normals.empty())
      std::swap(m.corner_normals[3 * t + 1], m.corner_normals[3 * t + 2]);
  }
  for (Vec3& n : m.corner_normals) n = -n;
  return m;
}

}  // namespace

void add_emissive_sphere(Scene* scene, const Vec3& center, float radius, float radiance) {
  const int32_t light = add_material(scene, Material::emission(Vec3(radiance), "light"));
  add_mesh_instance(scene, make_uv_sphere(center, radius, 24, 12), light);
}

Scene make_sds_glass_light() {
  Scene scene = make_cornell_box();
  // The five walls (the first five instances) without the blocks and the area light.
  scene.instances.resize(5);
  scene.meshes.resize(5);
  scene.lights.clear();
  // A thick glass shell: the light sits in air inside it, so every path from the light to a
  // wall crosses glass in pairs of interfaces (an emitter inside the glass itself would be
  // seen with radiance n^2 times the one its photons carry, as renderers that leave out the
  // radiance scaling of refraction, Cycles and Photon alike, transport it).
  const int32_t glass = add_material(&scene, Material::glass(1.5f, Vec3(1.0f), "glass"));
  const Vec3 center(0.0f, 0.1f, 0.7f);
  Mesh shell = make_uv_sphere(center, 0.4f, 64, 32);
  const Mesh cavity = turned_inside_out(make_uv_sphere(center, 0.25f, 64, 32));
  const auto offset = static_cast<uint32_t>(shell.positions.size());
  shell.positions.insert(shell.positions.end(), cavity.positions.begin(), cavity.positions.end());
  for (uint32_t i : cavity.indices) shell.indices.push_back(i + offset);
  shell.corner_normals.insert(shell.corner_normals.end(), cavity.corner_normals.begin(),
                              cavity.corner_normals.end());
  add_mesh_instance(&scene, std::move(shell), glass);
  // Above the cavity's centre, so the shell bends its light into caustics on the floor.
  add_emissive_sphere(&scene, {0.0f, 0.1f, 0.82f}, 0.06f, 60.0f);
  return scene;
}

Scene make_sds_mirror_caustic() {
  Scene scene;
  const int32_t white = add_material(&scene, Material::diffuse(Vec3(0.75f), "white"));
  const int32_t mirror = add_material(&scene, Material::mirror(Vec3(0.95f), "mirror"));
  const int32_t glass = add_material(&scene, Material::glass(1.5f, Vec3(1.0f), "glass"));
  add_mesh_instance(&scene, make_quad({-1.5f, -1.5f, 0}, {3, 0, 0}, {0, 3, 0}), white);
  // A wall behind the camera, which the mirror shows above the floor.
  add_mesh_instance(&scene, make_quad({-1.5f, -1.5f, 0}, {0, 0, 2}, {3, 0, 0}), white);
  // The mirror stands at y = 1 facing -y.
  add_mesh_instance(&scene, make_quad({-1.0f, 1.0f, 0.0f}, {2, 0, 0}, {0, 0, 1.6f}), mirror);
  // A ball of radius R and IOR n focuses at n R / (2 (n - 1)) = 0.375 from its centre: the
  // light 1 m above the ball is imaged about 0.6 m below the centre, on the floor.
  add_mesh_instance(&scene, make_uv_sphere({0.0f, -0.35f, 0.6f}, 0.25f, 64, 32), glass);
  add_emissive_sphere(&scene, {0.0f, -0.35f, 1.6f}, 0.04f, 500.0f);
  // The camera looks at the mirror over the ball (its outline stays below the frame), and the
  // mirror fills the frame.
  scene.camera = make_look_at_camera({0.0f, -1.1f, 1.35f}, {0.0f, 1.0f, 0.69f}, 0.45f, 1.0f);
  return scene;
}

Scene make_sds_pool() {
  Scene scene;
  const int32_t tile_a = add_material(&scene, Material::diffuse(Vec3(0.8f), "tile_white"));
  const int32_t tile_b =
      add_material(&scene, Material::diffuse(Vec3(0.1f, 0.3f, 0.6f), "tile_blue"));
  const int32_t water = add_material(&scene, Material::glass(1.33f, Vec3(1.0f), "water"));
  add_mesh_instance(&scene, make_checker_floor(1.0f, 8), tile_a);
  scene.instances.back().slot_materials = {tile_a, tile_b};
  add_mesh_instance(&scene, make_wavy_slab(1.0f, 0.02f, 0.45f, 128), water);
  // Behind the camera: the waves, tilted at most 15 degrees, reflect no glint of it into the
  // frame, so the floor's caustics are what the image is made of.
  add_emissive_sphere(&scene, {0.2f, -1.6f, 1.6f}, 0.08f, 300.0f);
  scene.camera = make_look_at_camera({0.0f, -0.9f, 2.2f}, {0.0f, 0.05f, 0.0f}, 0.6f, 1.0f);
  return scene;
}

const std::vector<std::string>& sds_scene_names() {
  static const std::vector<std::string> names = {"glass_light", "mirror_caustic", "pool"};
  return names;
}

bool make_sds_scene(const std::string& name, Scene* scene) {
  if (name == "glass_light") {
    *scene = make_sds_glass_light();
  } else if (name == "mirror_caustic") {
    *scene = make_sds_mirror_caustic();
  } else if (name == "pool") {
    *scene = make_sds_pool();
  } else {
    return false;
  }
  return true;
}

}  // namespace photon
