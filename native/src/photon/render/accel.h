// Embree 3 acceleration structure over a Scene: one BVH per mesh, instanced into a top-level
// scene, so N instances of a mesh cost one BVH.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "photon/base/math.h"
#include "photon/base/ray_offset.h"
#include "photon/render/blas_cache.h"
#include "photon/render/embree.h"
#include "photon/scene/scene.h"

namespace photon {

struct Hit {
  Vec3 p;          // world-space hit point (ray origin + t * direction)
  Vec3 ng_object;  // Embree's unnormalised geometric normal, in the mesh's object space
  float t = 0.0f;
  float u = 0.0f, v = 0.0f;  // Embree barycentrics: p = (1-u-v) p0 + u p1 + v p2
  uint32_t instance = 0;
  uint32_t primitive = 0;
};

// Everything shading needs about a hit point, in world space.
struct SurfaceInteraction {
  Vec3 p;
  Vec3 ng;  // geometric normal, unit length, as wound by the mesh
  Vec3 ns;  // interpolated shading normal, on the same side as ng
  Vec2 uv;
  uint32_t material = 0;
  const Material* mat = nullptr;
  uint32_t instance = 0, primitive = 0;  // Embree instance and triangle (for UV tangents)
  Vec2 barycentric;                      // Embree's (u, v) on that triangle
  // What shader programs read about the object (null for points not made by an Accel).
  const Scene* scene = nullptr;
  const Instance* object = nullptr;
  const Mesh* mesh = nullptr;
};

// Mask bits the Accel adds to every instance that casts shadows (kVisibleShadow), by whether
// any of its materials may let light straight through (Material::may_be_transparent): shadow
// rays test the opaque ones with one any-hit query and walk through the others
// (render/shadow_ray.h). Rays that ask for kVisibleShadow see both kinds.
constexpr uint32_t kShadowOpaque = 1u << 5;
constexpr uint32_t kShadowTransparent = 1u << 6;

// What the BVH is built for. Embree's LOW quality (Morton build) takes about a third of the
// MEDIUM (binned SAH) build time but traces rays about half as fast: it pays only when a
// render traces few rays per triangle (see bvh_quality_for()).
enum class BvhQuality { kFastTrace, kFastBuild };

class Accel {
 public:
  // Builds the BVHs. `scene` must outlive the Accel. Warnings (Embree errors, skipped instances)
  // are appended to `warnings`. When `cancel` becomes true during the build, Embree abandons it
  // within a few ms and the Accel holds an empty scene instead (every ray misses); cancelled()
  // tells. The quality changes build and trace speed, not what a ray hits (robust mode: only
  // exact ties between triangles could resolve differently). With a `blas_cache` (Persistent
  // Data), mesh BVHs come from it and are built into it, on its device; it must outlive the Accel.
  Accel(const Scene& scene, std::vector<std::string>* warnings,
        const std::atomic<bool>* cancel = nullptr, BvhQuality quality = BvhQuality::kFastTrace,
        BlasCache* blas_cache = nullptr);
  ~Accel();
  Accel(const Accel&) = delete;
  Accel& operator=(const Accel&) = delete;

  bool intersect(const Ray& ray, uint32_t mask, Hit* hit) const;
  bool occluded(const Ray& ray, uint32_t mask) const;
  // Traces `count` coherent rays (neighbouring camera rays) as an Embree stream, which is
  // several times faster than one rtcIntersect1 per ray. found[i] tells whether hits[i] is set.
  void intersect_coherent(const Ray* rays, size_t count, uint32_t mask, Hit* hits,
                          bool* found) const;
  SurfaceInteraction interaction(const Hit& hit) const;
  // The material of triangle `primitive` of Embree instance `instance` (the default material
  // when the slot maps to none), and its scene material index (UINT32_MAX for the default).
  const Material& triangle_material(uint32_t instance, uint32_t primitive,
                                    uint32_t* index = nullptr) const;
  // World-space derivatives dp/du and dp/dv of the triangle's UV mapping (for tangent-space
  // normal maps). False without UVs or for a degenerate UV triangle.
  bool uv_tangents(uint32_t instance, uint32_t primitive, Vec3* dpdu, Vec3* dpdv) const;
  // Index into Scene::instances of Embree instance `instance` (instances whose transform was
  // unusable are skipped, so the two numberings can differ).
  uint32_t scene_instance(uint32_t instance) const { return instances_[instance].scene_index; }
  // The hit a ray would report at barycentrics (u, v) of triangle `triangle` (an index into the
  // mesh's cleaned triangles) of Scene::instances[scene_index], for shading a given surface
  // point (lighting bakes). False when the instance was skipped or the triangle is out of range.
  bool surface_hit(uint32_t scene_index, uint32_t triangle, float u, float v, Hit* hit) const;

  size_t instance_count() const { return instances_.size(); }
  size_t blas_count() const { return blas_count_; }
  size_t blas_reused() const { return blas_reused_; }        // of blas_count(), found in the cache
  size_t triangle_count() const { return triangle_count_; }  // unique (not instanced) triangles
  bool cancelled() const { return cancelled_; }  // the build was abandoned: the scene is empty
  // Bounding box of all instanced geometry in world space (empty scene: min > max).
  Vec3 bounds_min() const { return bounds_min_; }
  Vec3 bounds_max() const { return bounds_max_; }
  // scene_length_scale() of the bounds: the length ray offsets and other small distances scale
  // with, so the renderer is invariant to the scene's scale.
  float length_scale() const { return length_scale_; }
  RTCScene top_level() const { return top_; }

  // Moves the instances Scene::instances[scene_indices[k]] to the transforms the scene now
  // holds (the caller changed their object_to_world): their Embree instance transforms and
  // normal matrices are set and only the top level is rebuilt; no mesh BVH is touched. Bounds
  // and length scale are recomputed as the constructor computes them, so the Accel then traces
  // exactly as one built from the moved scene. False, with nothing changed, when the move
  // changes which instances are traced (a transform that was or becomes non-finite or
  // singular, an instance without a BVH) or the build was cancelled: build a new Accel then.
  // No ray may be traced meanwhile.
  bool update_instance_transforms(const std::vector<uint32_t>& scene_indices);
  // Whether any instance that casts shadows has a material that may be transparent (then
  // shadow rays must look through surfaces, render/shadow_ray.h).
  bool has_transparent_shadows() const { return transparent_shadows_; }
  // Sets every instance's shadow bits again after the caller edited Scene::materials (a
  // material may have become transparent or opaque). No ray may be traced meanwhile.
  void update_shadow_masks();

 private:
  // What shading reads per hit, kept compact (one cache line) and free of pointer chains.
  struct InstanceData {
    float normal_matrix[3][3];
    uint32_t slot_count = 0;
    const int32_t* slot_materials = nullptr;
    const Mesh* mesh = nullptr;
    uint32_t scene_index = 0;
    uint32_t mask = 0;  // as set in Embree (instance_mask)
  };

  const Scene& scene_;
  RTCDevice device_ = nullptr;
  RTCScene top_ = nullptr;
  std::vector<RTCScene> mesh_scenes_;
  std::vector<InstanceData> instances_;    // indexed by Embree instance geometry id
  std::vector<uint32_t> embree_instance_;  // Scene::instances index -> Embree id (UINT32_MAX)
  size_t blas_count_ = 0;
  size_t blas_reused_ = 0;
  size_t triangle_count_ = 0;
  Vec3 bounds_min_{INFINITY, INFINITY, INFINITY};
  Vec3 bounds_max_{-INFINITY, -INFINITY, -INFINITY};
  float length_scale_ = 1.0f;
  std::vector<std::string>* warnings_;
  std::mutex warnings_mutex_;
  const std::atomic<bool>* cancel_ = nullptr;
  bool cancelled_ = false;
  bool transparent_shadows_ = false;

  // The instance's Embree mask: its ray visibility and, when it casts shadows, its shadow bit.
  uint32_t instance_mask(const InstanceData& data) const;

  static void on_embree_error(void* user, RTCError code, const char* message);
  // Embree's build progress callback: false (stop) once the render is cancelled.
  static bool on_build_progress(void* cancel, double);
  // Commits `scene`, abandoning the build when cancelled; false when it was abandoned. Called
  // concurrently for different bottom-level scenes from TBB tasks.
  bool commit(RTCScene scene);
  // Releases every BVH and leaves an empty, committed top level.
  void clear_after_cancel();
  // Bounds and length scale of the committed top level (nothing instanced: left as they are).
  void update_bounds();
};

// A shadow ray between two surface points (p with normal ng, q with normal nq), both ends
// offset off their surfaces towards each other and the direction taken between the offset ends
// (pbrt-v4's SpawnRayTo for two interactions). Offsetting only the origin and keeping the
// direction p -> q moves the segment towards q's surface by the offset, so at short or
// grazing distances it ends inside q's own surface and the point occludes itself.
// `length_scale` is scene_length_scale() of the scene.
inline Ray shadow_ray_between(const Vec3& p, const Vec3& ng, const Vec3& q, const Vec3& nq,
                              float length_scale) {
  const Vec3 from = offset_ray_origin(p, ng, q - p, length_scale);
  const Vec3 to = offset_ray_origin(q, nq, p - q, length_scale);
  const Vec3 d = to - from;
  const float len = length(d);
  Ray ray;
  ray.origin = from;
  ray.direction = len > 0.0f ? d / len : normalize(q - p);
  ray.tmin = 0.0f;
  ray.tmax = len * (1.0f - 1e-4f);
  return ray;
}

}  // namespace photon
