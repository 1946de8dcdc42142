#include "photon/testing/test_scenes.h"

namespace photon {

uint32_t add_mesh_instance(Scene* scene, Mesh mesh, int32_t material, const Transform& xf) {
  clean_mesh(&mesh);
  scene->meshes.push_back(std::move(mesh));
  Instance inst;
  inst.mesh = static_cast<uint32_t>(scene->meshes.size() - 1);
  inst.object_to_world = xf;
  inst.slot_materials = {material};
  inst.name = scene->meshes.back().name;
  scene->instances.push_back(inst);
  return inst.mesh;
}

Mesh make_quad(const Vec3& corner, const Vec3& edge_u, const Vec3& edge_v) {
  Mesh m;
  m.name = "quad";
  m.positions = {corner, corner + edge_u, corner + edge_u + edge_v, corner + edge_v};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

Mesh make_textured_quad() {
  Mesh quad = make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0});
  for (size_t t = 0; t < quad.triangle_count(); ++t)
    for (int c = 0; c < 3; ++c) {
      const Vec3& p = quad.positions[quad.indices[3 * t + c]];
      quad.corner_uvs.push_back(Vec2(0.5f * (p.x + 1.0f), 0.5f * (p.y + 1.0f)));
    }
  return quad;
}

Mesh make_box(const Vec3& lo, const Vec3& hi) {
  Mesh m;
  m.name = "box";
  for (int i = 0; i < 8; ++i)
    m.positions.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  // Outward-facing (counter-clockwise seen from outside) faces.
  const uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    m.indices.insert(m.indices.end(), {f[0], f[1], f[2], f[0], f[2], f[3]});
  }
  return m;
}

Mesh make_uv_sphere(const Vec3& center, float radius, int segments, int rings) {
  Mesh m;
  m.name = "sphere";
  for (int r = 0; r <= rings; ++r) {
    const float theta = kPi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const float phi = 2.0f * kPi * s / segments;
      const Vec3 n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                   std::cos(theta));
      m.positions.push_back(center + n * radius);
    }
  }
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const uint32_t a = r * segments + s, b = r * segments + (s + 1) % segments;
      const uint32_t c = a + segments, d = b + segments;
      m.indices.insert(m.indices.end(), {a, c, d, a, d, b});
    }
  }
  // Smooth shading: corner normals point away from the centre.
  for (uint32_t idx : m.indices) m.corner_normals.push_back(normalize(m.positions[idx] - center));
  return m;
}

Camera make_look_at_camera(const Vec3& eye, const Vec3& target, float fov_y, float aspect) {
  Camera cam;
  const Vec3 forward = normalize(target - eye);
  const Vec3 right = normalize(cross(forward, Vec3(0.0f, 0.0f, 1.0f)));
  const Vec3 up = cross(right, forward);
  // Columns: camera +X = right, +Y = up, +Z = -forward, translation = eye.
  const Vec3 z = -forward;
  const float rows[12] = {right.x, up.x,  z.x,     eye.x, right.y, up.y,
                          z.y,     eye.y, right.z, up.z,  z.z,     eye.z};
  cam.camera_to_world = Transform::from_rows(rows);
  const float half_h = std::tan(fov_y * 0.5f);
  cam.window_min_y = -half_h;
  cam.window_max_y = half_h;
  cam.window_min_x = -half_h * aspect;
  cam.window_max_x = half_h * aspect;
  cam.clip_start = 0.01f;
  cam.clip_end = 1000.0f;
  return cam;
}

Scene make_cornell_box(float light_power) {
  Scene scene;
  auto material = [&](const char* name, Vec3 color) {
    scene.materials.push_back(Material::diffuse(color, name));
    return static_cast<int32_t>(scene.materials.size() - 1);
  };
  const int32_t white = material("white", Vec3(0.73f, 0.73f, 0.73f));
  const int32_t red = material("red", Vec3(0.65f, 0.05f, 0.05f));
  const int32_t green = material("green", Vec3(0.12f, 0.45f, 0.15f));

  // Room: x in [-1, 1], y in [-1, 1], z in [0, 2]; open towards -y where the camera is.
  add_mesh_instance(&scene, make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}), white);  // floor
  add_mesh_instance(&scene, make_quad({-1, -1, 2}, {0, 2, 0}, {2, 0, 0}), white);  // ceiling
  add_mesh_instance(&scene, make_quad({-1, 1, 0}, {2, 0, 0}, {0, 0, 2}), white);   // back
  add_mesh_instance(&scene, make_quad({-1, -1, 0}, {0, 2, 0}, {0, 0, 2}), red);    // left
  add_mesh_instance(&scene, make_quad({1, -1, 0}, {0, 0, 2}, {0, 2, 0}), green);   // right
  add_mesh_instance(&scene, make_box({-0.6f, -0.1f, 0.0f}, {-0.05f, 0.5f, 1.2f}), white);
  add_mesh_instance(&scene, make_box({0.1f, -0.6f, 0.0f}, {0.65f, -0.05f, 0.6f}), white);

  Light light;
  light.name = "ceiling_light";
  light.type = LightType::kArea;
  light.power = light_power;
  light.size_x = light.size_y = 0.5f;
  // Local -Z (the emission direction) must point down: the identity already does that.
  light.light_to_world = Transform::translation(Vec3(0.0f, 0.0f, 1.98f));
  scene.lights.push_back(light);

  scene.camera = make_look_at_camera({0.0f, -3.9f, 1.0f}, {0.0f, 0.0f, 1.0f}, 0.69f, 1.0f);
  return scene;
}

Scene make_caustic_box(float light_power) {
  Scene scene = make_cornell_box();
  // Keep the five walls (the first five instances), drop the two blocks and the area light.
  scene.instances.resize(5);
  scene.meshes.resize(5);
  scene.lights.clear();
  scene.materials.push_back(Material::glass(1.5f, Vec3(1.0f), "glass"));
  add_mesh_instance(&scene, make_uv_sphere({-0.45f, 0.2f, 0.35f}, 0.35f, 64, 32),
                    static_cast<int32_t>(scene.materials.size() - 1));
  scene.materials.push_back(Material::mirror(Vec3(0.95f), "mirror"));
  add_mesh_instance(&scene, make_uv_sphere({0.45f, -0.2f, 0.35f}, 0.35f, 64, 32),
                    static_cast<int32_t>(scene.materials.size() - 1));
  Light light;
  light.name = "sphere_light";
  light.type = LightType::kPoint;
  light.power = light_power;
  light.radius = 0.05f;
  light.light_to_world = Transform::translation(Vec3(0.0f, 0.0f, 1.8f));
  scene.lights.push_back(light);
  return scene;
}

}  // namespace photon
