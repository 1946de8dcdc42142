#include "photon/render/shader_globals.h"

#include <algorithm>

#include "photon/render/accel.h"
#include "photon/scene/scene.h"
#include "photon/shading/input_nodes.h"

namespace photon {

ShaderGlobals surface_globals(const SurfaceInteraction& si, const Vec3& wo, const Accel* accel,
                              const TextureSet* textures, const ShadeRay& ray) {
  ShaderGlobals g;
  g.p = si.p;
  const bool front = dot(si.ng, wo) >= 0.0f;
  // Cycles' N and Ng face the incoming ray; Backfacing says whether they were flipped.
  g.backfacing = !front;
  g.n = front ? si.ns : -si.ns;
  g.ng = front ? si.ng : -si.ng;
  g.incoming = wo;
  g.uv = si.uv;
  g.textures = textures;
  if (accel) accel->uv_tangents(si.instance, si.primitive, &g.dpdu, &g.dpdv);
  g.ray_flags = ray.flags;
  g.ray_length = ray.length;
  g.ray_depth = ray.depth;
  g.diffuse_depth = ray.diffuse_depth;
  g.glossy_depth = ray.glossy_depth;
  g.transparent_depth = ray.transparent_depth;
  g.transmission_depth = ray.transmission_depth;
  if (si.object) {
    g.object_to_world = si.object->object_to_world;
    g.world_to_object = inverse_affine(g.object_to_world);
    g.object_location = g.object_to_world.column(3);
    g.object_color = si.object->color;
    g.object_alpha = si.object->alpha;
    g.object_random = si.object->random;
    g.object_pass_index = si.object->pass_index;
  }
  if (si.mesh) {
    g.mesh = si.mesh;
    g.primitive = si.primitive;
    g.barycentric = si.barycentric;
    // Generated: the object-space point in the mesh's texture space box, [0, 1]^3.
    const Vec3 size = si.mesh->texspace_size;
    const Vec3 safe{size.x != 0.0f ? size.x : 1.0f, size.y != 0.0f ? size.y : 1.0f,
                    size.z != 0.0f ? size.z : 1.0f};
    g.generated_scale = Vec3(0.5f) / safe;
    g.generated =
        (g.world_to_object.point(si.p) - (si.mesh->texspace_location - safe)) * g.generated_scale;
  }
  if (si.mat) g.material_pass_index = si.mat->pass_index;
  if (si.scene) {
    g.camera = &si.scene->camera;
    // Cycles' camera space looks down +Z: Blender's camera space with Z negated.
    g.world_to_camera = inverse_affine(si.scene->camera.camera_to_world);
    for (int c = 0; c < 4; ++c) g.world_to_camera.m[2][c] = -g.world_to_camera.m[2][c];
  }
  // Bump's finite-difference step: a small fraction of the distance the ray travelled (a
  // pixel's footprint is about a thousandth of it for common fields of view), never below a
  // small absolute floor.
  g.bump_step = std::max(1e-3f * ray.length, 1e-5f);
  return g;
}

}  // namespace photon
