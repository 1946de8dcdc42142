// Scenes built in code, for unit tests, benchmarks and the CLI (no Blender needed).
#pragma once

#include "photon/scene/scene.h"

namespace photon {

// Adds a mesh and one instance of it with the given material; returns the mesh index.
uint32_t add_mesh_instance(Scene* scene, Mesh mesh, int32_t material,
                           const Transform& xf = Transform());

Mesh make_quad(const Vec3& corner, const Vec3& edge_u, const Vec3& edge_v);
// The square [-1, 1]^2 at z = 0 facing +z, with per-corner UVs spanning [0, 1]^2.
Mesh make_textured_quad();
Mesh make_box(const Vec3& min, const Vec3& max);
Mesh make_uv_sphere(const Vec3& center, float radius, int segments, int rings);

// A Cornell box 2 m wide centred on the origin (floor at z = 0, camera looking along +y),
// lit by a 0.5 m square area light of `light_power` watts under the ceiling.
Scene make_cornell_box(float light_power = 40.0f);

// The caustic box: the Cornell room (no blocks) with a glass ball (IOR 1.5) and a mirror ball,
// both of radius 0.35, lit by a small sphere light (point light, radius 0.05) at (0, 0, 1.8).
Scene make_caustic_box(float light_power = 60.0f);

// A camera at `eye` looking at `target` (world +Z up) with the given vertical field of view
// for an image of aspect width / height.
Camera make_look_at_camera(const Vec3& eye, const Vec3& target, float fov_y_radians, float aspect);

}  // namespace photon
