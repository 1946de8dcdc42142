#include "photon/render/accel.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

namespace photon {
namespace {

Vec3 mat3_mul(const float m[3][3], const Vec3& v) {
  return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
          m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
          m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

void init_ray(const Ray& ray, uint32_t mask, RTCRay* r) {
  r->org_x = ray.origin.x;
  r->org_y = ray.origin.y;
  r->org_z = ray.origin.z;
  r->dir_x = ray.direction.x;
  r->dir_y = ray.direction.y;
  r->dir_z = ray.direction.z;
  r->tnear = ray.tmin;
  r->tfar = ray.tmax;
  r->time = 0.0f;
  r->mask = mask;
  r->id = 0;
  r->flags = 0;
}

// Embree 3 asserts on rays its RayK::valid() rejects (any origin or direction coordinate beyond
// FLT_LARGE = 1.844e18 or NaN, NaN tnear / tfar) and on a negative tnear, and Debian builds it
// with assertions on: an absurd camera or scene would abort Blender. Such rays are not traced;
// they hit nothing.
bool traceable(const Ray& ray) {
  constexpr float kLarge = 1.844e18f;
  auto small = [](const Vec3& v) {
    return std::fabs(v.x) <= kLarge && std::fabs(v.y) <= kLarge && std::fabs(v.z) <= kLarge;
  };
  return small(ray.origin) && small(ray.direction) && ray.tmin >= 0.0f && !std::isnan(ray.tmax);
}

void fill_hit(const RTCRayHit& rh, const Ray& ray, Hit* hit) {
  hit->t = rh.ray.tfar;
  hit->p = ray.origin + ray.direction * rh.ray.tfar;
  hit->ng_object = Vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
  hit->u = rh.hit.u;
  hit->v = rh.hit.v;
  hit->instance = rh.hit.instID[0];
  hit->primitive = rh.hit.primID;
}

}  // namespace

void Accel::on_embree_error(void* user, RTCError code, const char* message) {
  auto* self = static_cast<Accel*>(user);
  if (code == RTC_ERROR_CANCELLED) return;  // a build abandoned on cancel is no error
  std::lock_guard<std::mutex> lock(self->warnings_mutex_);
  if (self->warnings_)
    self->warnings_->push_back("Embree error " + std::to_string(static_cast<int>(code)) + ": " +
                               (message ? message : ""));
}

bool Accel::on_build_progress(void* cancel, double) {
  return !static_cast<const std::atomic<bool>*>(cancel)->load(std::memory_order_relaxed);
}

bool Accel::commit(RTCScene scene) {
  if (cancel_) {
    if (cancel_->load(std::memory_order_relaxed)) return false;
    rtcSetSceneProgressMonitorFunction(scene, &Accel::on_build_progress,
                                       const_cast<std::atomic<bool>*>(cancel_));
  }
  rtcCommitScene(scene);
  return !(cancel_ && cancel_->load(std::memory_order_relaxed));
}

void Accel::clear_after_cancel() {
  cancelled_ = true;
  if (top_) rtcReleaseScene(top_);
  for (RTCScene& s : mesh_scenes_)
    if (s) rtcReleaseScene(s), s = nullptr;
  instances_.clear();
  embree_instance_.assign(scene_.instances.size(), UINT32_MAX);
  blas_count_ = blas_reused_ = triangle_count_ = 0;
  transparent_shadows_ = false;
  top_ = rtcNewScene(device_);
  rtcCommitScene(top_);  // empty: instant, and every query on it misses
}

Accel::Accel(const Scene& scene, std::vector<std::string>* warnings,
             const std::atomic<bool>* cancel, BvhQuality quality, BlasCache* blas_cache)
    : scene_(scene), warnings_(warnings), cancel_(cancel) {
  if (blas_cache) {
    // Instanced BVHs must live on the top level's device; the cache reports its own errors.
    device_ = blas_cache->device();
    rtcRetainDevice(device_);
  } else {
    device_ = rtcNewDevice(nullptr);
    rtcSetDeviceErrorFunction(device_, &Accel::on_embree_error, this);
  }

  // Bottom level: one scene per mesh that has triangles and is used by an instance. The meshes
  // are built concurrently (Embree allows rtcCommitScene on different scenes from TBB worker
  // threads, each build nesting its own parallel loops), so a scene of many small meshes keeps
  // every thread busy instead of building them one after another.
  std::vector<uint8_t> used(scene.meshes.size(), 0);
  for (const Instance& inst : scene.instances)
    if (inst.mesh < used.size()) used[inst.mesh] = 1;
  std::vector<size_t> to_build;
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    if (used[m] && scene.meshes[m].triangle_count() > 0) to_build.push_back(m);
  mesh_scenes_.assign(scene.meshes.size(), nullptr);
  const RTCBuildQuality rtc_quality =
      quality == BvhQuality::kFastBuild ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_MEDIUM;
  if (blas_cache) {
    // Persistent Data: the cache builds what it lacks, one mesh at a time under its lock, into
    // buffers of its own (the BVHs outlive this frame's meshes).
    for (size_t m : to_build) {
      bool reused = false;
      if (!blas_cache->acquire(
              scene.meshes[m], [this](RTCScene s) { return commit(s); }, &mesh_scenes_[m],
              &reused)) {
        clear_after_cancel();
        return;
      }
      blas_reused_ += reused ? 1 : 0;
    }
  }
  std::atomic<bool> abandoned{false};
  tbb::parallel_for(size_t{0}, blas_cache ? size_t{0} : to_build.size(), [&](size_t i) {
    if (abandoned.load(std::memory_order_relaxed)) return;
    const size_t m = to_build[i];
    const Mesh& mesh = scene.meshes[m];
    RTCGeometry geom = embree::new_triangle_geometry(device_);
    rtcSetGeometryBuildQuality(geom, rtc_quality);
    // Embree reads vertices with 16-byte loads, so the last one needs 4 readable bytes after it.
    // Meshes imported with spare capacity (Scene's add_mesh reserves one vertex more) are
    // shared as they are; others are copied into a padded buffer owned by Embree.
    if (mesh.positions.capacity() > mesh.positions.size()) {
      rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                 mesh.positions.data(), 0, sizeof(Vec3), mesh.positions.size());
    } else {
      auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
          geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sizeof(Vec3), mesh.positions.size()));
      if (vertices)
        std::memcpy(vertices, mesh.positions.data(), mesh.positions.size() * sizeof(Vec3));
    }
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                               mesh.indices.data(), 0, 3 * sizeof(uint32_t), mesh.triangle_count());
    rtcCommitGeometry(geom);
    RTCScene blas = rtcNewScene(device_);
    // Robust triangle tests: with them a ray hits the same triangle at the same t whatever the
    // BVH's shape (only exact ties can resolve differently), so the build quality is free to
    // change.
    rtcSetSceneFlags(blas, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(blas, rtc_quality);
    rtcAttachGeometryByID(blas, geom, 0);
    rtcReleaseGeometry(geom);
    mesh_scenes_[m] = blas;
    if (!commit(blas)) abandoned = true;
  });
  if (abandoned) {
    clear_after_cancel();
    return;
  }
  blas_count_ = to_build.size();
  for (size_t m : to_build) triangle_count_ += scene.meshes[m].triangle_count();

  // Top level: one instance geometry per Instance; geometry id = index into instances_.
  top_ = rtcNewScene(device_);
  rtcSetSceneFlags(top_, RTC_SCENE_FLAG_ROBUST);
  size_t skipped = 0;
  // Objects too small for floats where they stand (kObjectFarFromOriginRatio): how many, and
  // the one farthest beyond precision.
  size_t coarse_objects = 0;
  float coarse_ratio = 0.0f, coarse_size = 0.0f, coarse_distance = 0.0f;
  std::string coarse_name;
  embree_instance_.assign(scene.instances.size(), UINT32_MAX);
  for (size_t index = 0; index < scene.instances.size(); ++index) {
    const Instance& inst = scene.instances[index];
    if (inst.mesh >= mesh_scenes_.size() || !mesh_scenes_[inst.mesh]) continue;
    InstanceData data;
    data.mesh = &scene.meshes[inst.mesh];
    data.scene_index = static_cast<uint32_t>(index);
    data.slot_materials = inst.slot_materials.data();
    data.slot_count = static_cast<uint32_t>(inst.slot_materials.size());
    const Transform& to_world = inst.object_to_world;
    if (!to_world.is_finite() || !to_world.normal_matrix(data.normal_matrix)) {
      ++skipped;
      continue;
    }
    RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(geom, mesh_scenes_[inst.mesh]);
    float xf[12];  // 3x4 column major
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 3; ++r) xf[c * 3 + r] = to_world.m[r][c];
    rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xf);
    data.mask = instance_mask(data);
    transparent_shadows_ = transparent_shadows_ || (data.mask & kShadowTransparent);
    rtcSetGeometryMask(geom, data.mask);
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(top_, geom, static_cast<unsigned>(instances_.size()));
    rtcReleaseGeometry(geom);
    embree_instance_[index] = static_cast<uint32_t>(instances_.size());
    instances_.push_back(data);

    // The instance's world box: its mesh's box centre transformed, half size by |rotation|.
    RTCBounds local;
    rtcGetSceneBounds(mesh_scenes_[inst.mesh], &local);
    const Vec3 centre(0.5f * (local.lower_x + local.upper_x),
                      0.5f * (local.lower_y + local.upper_y),
                      0.5f * (local.lower_z + local.upper_z));
    const Vec3 half(0.5f * (local.upper_x - local.lower_x), 0.5f * (local.upper_y - local.lower_y),
                    0.5f * (local.upper_z - local.lower_z));
    Vec3 world_lo, world_hi;
    for (int r = 0; r < 3; ++r) {
      const float c = to_world.m[r][0] * centre.x + to_world.m[r][1] * centre.y +
                      to_world.m[r][2] * centre.z + to_world.m[r][3];
      const float h = std::abs(to_world.m[r][0]) * half.x + std::abs(to_world.m[r][1]) * half.y +
                      std::abs(to_world.m[r][2]) * half.z;
      (&world_lo.x)[r] = c - h;
      (&world_hi.x)[r] = c + h;
    }
    if (scene_beyond_float_precision(world_lo, world_hi, kObjectFarFromOriginRatio)) {
      const float size = length(world_hi - world_lo);
      const float distance = std::max(max_abs_component(world_lo), max_abs_component(world_hi));
      const float ratio = size > 0.0f ? distance / size : INFINITY;
      if (coarse_objects++ == 0 || ratio > coarse_ratio) {
        coarse_ratio = ratio;
        coarse_size = size;
        coarse_distance = distance;
        coarse_name = inst.name.empty() ? data.mesh->name : inst.name;
      }
    }
  }
  if (!commit(top_)) {
    clear_after_cancel();
    return;
  }
  if (skipped && warnings_)
    warnings_->push_back("Skipped " + std::to_string(skipped) +
                         " instance(s) with a non-finite or singular transform");
  if (blas_cache && warnings_)
    for (std::string& w : blas_cache->take_warnings()) warnings_->push_back(std::move(w));

  if (!instances_.empty()) {
    update_bounds();
    if (warnings_ && scene_beyond_float_precision(bounds_min_, bounds_max_)) {
      const double extent = length(bounds_max_ - bounds_min_);
      const double distance =
          std::max(max_abs_component(bounds_min_), max_abs_component(bounds_max_));
      char text[320];
      std::snprintf(text, sizeof text,
                    "The scene spans %.3g m but lies %.3g m from the origin: 32-bit floats "
                    "resolve only %.3g m there, so surfaces band and shadows and contact light "
                    "go wrong; move the scene near the origin",
                    extent, distance, distance * std::numeric_limits<float>::epsilon());
      warnings_->push_back(text);
    } else if (warnings_ && coarse_objects) {
      char text[480];
      std::snprintf(text, sizeof text,
                    "%zu object(s) are too small for 32-bit floats where they lie: '%.100s' spans "
                    "%.3g m but lies %.3g m from the origin, where floats resolve only %.3g m, "
                    "so it bands and its shadows and contact light go wrong (the scene spans "
                    "%.3g m); keep small detail nearer the origin or the scene smaller",
                    coarse_objects, coarse_name.c_str(), coarse_size, coarse_distance,
                    coarse_distance * std::numeric_limits<float>::epsilon(),
                    length(bounds_max_ - bounds_min_));
      warnings_->push_back(text);
    }
  }
}

void Accel::update_bounds() {
  if (instances_.empty()) return;
  RTCBounds b;
  rtcGetSceneBounds(top_, &b);
  bounds_min_ = Vec3(b.lower_x, b.lower_y, b.lower_z);
  bounds_max_ = Vec3(b.upper_x, b.upper_y, b.upper_z);
  length_scale_ = scene_length_scale(bounds_min_, bounds_max_);
}

bool Accel::update_instance_transforms(const std::vector<uint32_t>& scene_indices) {
  if (cancelled_) return false;
  // First check every move, so a refused one leaves the Accel as it was.
  std::vector<std::pair<uint32_t, InstanceData>> moved;
  moved.reserve(scene_indices.size());
  for (uint32_t index : scene_indices) {
    if (index >= scene_.instances.size() || index >= embree_instance_.size()) return false;
    const Instance& inst = scene_.instances[index];
    const bool traced_before = embree_instance_[index] != UINT32_MAX;
    const bool has_blas = inst.mesh < mesh_scenes_.size() && mesh_scenes_[inst.mesh];
    if (!has_blas) {
      if (traced_before) return false;
      continue;  // never traced, whatever its transform
    }
    InstanceData data;
    const bool usable =
        inst.object_to_world.is_finite() && inst.object_to_world.normal_matrix(data.normal_matrix);
    if (usable != traced_before) return false;
    if (usable) moved.emplace_back(embree_instance_[index], data);
  }
  for (const auto& [id, data] : moved) {
    InstanceData& inst = instances_[id];
    std::memcpy(inst.normal_matrix, data.normal_matrix, sizeof inst.normal_matrix);
    const Transform& to_world = scene_.instances[inst.scene_index].object_to_world;
    float xf[12];  // 3x4 column major, as the constructor sets it
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 3; ++r) xf[c * 3 + r] = to_world.m[r][c];
    RTCGeometry geom = rtcGetGeometry(top_, id);
    rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xf);
    rtcCommitGeometry(geom);
  }
  // Only the top level is rebuilt (over instance boxes: microseconds for a few thousand). The
  // build's cancel flag belonged to the render that built the Accel, which may be gone: this
  // short build is not cancellable.
  rtcSetSceneProgressMonitorFunction(top_, nullptr, nullptr);
  cancel_ = nullptr;
  rtcCommitScene(top_);
  update_bounds();
  return true;
}

uint32_t Accel::instance_mask(const InstanceData& data) const {
  const uint32_t visibility = scene_.instances[data.scene_index].visibility;
  if (!(visibility & kVisibleShadow)) return visibility;
  // Every material a triangle can name (slots outside the list fall back to the default
  // material, which is opaque).
  bool transparent = false;
  for (uint32_t slot = 0; slot < data.slot_count && !transparent; ++slot) {
    const int32_t m = data.slot_materials[slot];
    transparent = m >= 0 && static_cast<size_t>(m) < scene_.materials.size() &&
                  scene_.materials[m].may_be_transparent();
  }
  return visibility | (transparent ? kShadowTransparent : kShadowOpaque);
}

void Accel::update_shadow_masks() {
  if (cancelled_ || !top_) return;
  bool any = false, changed = false;
  for (size_t id = 0; id < instances_.size(); ++id) {
    InstanceData& data = instances_[id];
    const uint32_t mask = instance_mask(data);
    any = any || (mask & kShadowTransparent);
    if (mask == data.mask) continue;
    data.mask = mask;
    RTCGeometry geom = rtcGetGeometry(top_, static_cast<unsigned>(id));
    rtcSetGeometryMask(geom, mask);
    rtcCommitGeometry(geom);
    changed = true;
  }
  transparent_shadows_ = any;
  if (!changed) return;
  // As update_instance_transforms: a short top-level build that is not cancellable.
  rtcSetSceneProgressMonitorFunction(top_, nullptr, nullptr);
  cancel_ = nullptr;
  rtcCommitScene(top_);
}

Accel::~Accel() {
  if (top_) rtcReleaseScene(top_);
  for (RTCScene s : mesh_scenes_)
    if (s) rtcReleaseScene(s);
  if (device_) rtcReleaseDevice(device_);
}

bool Accel::intersect(const Ray& ray, uint32_t mask, Hit* hit) const {
  if (!traceable(ray)) return false;
  RTCRayHit rh;
  init_ray(ray, mask, &rh.ray);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  embree::intersect1(top_, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  fill_hit(rh, ray, hit);
  return true;
}

void Accel::intersect_coherent(const Ray* rays, size_t count, uint32_t mask, Hit* hits,
                               bool* found) const {
  constexpr size_t kBatch = 64;
  // Aligned so Embree forms the same ray packets on every thread's stack: with a different
  // alignment it may trace a few rays singly, with last-bit differences in t (Embree #149).
  alignas(64) RTCRayHit batch[kBatch];
  for (size_t base = 0; base < count; base += kBatch) {
    const size_t n = std::min(kBatch, count - base);
    for (size_t i = 0; i < n; ++i) {
      if (traceable(rays[base + i])) {
        init_ray(rays[base + i], mask, &batch[i].ray);
      } else {
        // Valid for Embree but inactive (tnear > tfar): it reports no hit.
        init_ray(Ray{Vec3(0.0f), Vec3(0.0f, 0.0f, 1.0f), 1.0f, 0.0f}, mask, &batch[i].ray);
      }
      batch[i].hit.geomID = RTC_INVALID_GEOMETRY_ID;
      batch[i].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    }
    embree::intersect_coherent(top_, batch, static_cast<unsigned>(n));
    for (size_t i = 0; i < n; ++i) {
      found[base + i] = batch[i].hit.geomID != RTC_INVALID_GEOMETRY_ID;
      if (found[base + i]) fill_hit(batch[i], rays[base + i], &hits[base + i]);
    }
  }
}

bool Accel::occluded(const Ray& ray, uint32_t mask) const {
  if (!traceable(ray)) return true;  // no light along a ray that cannot be traced
  RTCRay r;
  init_ray(ray, mask, &r);
  embree::occluded1(top_, &r);
  return r.tfar < 0.0f;  // Embree sets tfar to -inf when something blocks the ray
}

bool Accel::surface_hit(uint32_t scene_index, uint32_t triangle, float u, float v, Hit* hit) const {
  if (scene_index >= embree_instance_.size() || embree_instance_[scene_index] == UINT32_MAX)
    return false;
  const uint32_t instance = embree_instance_[scene_index];
  const Mesh& mesh = *instances_[instance].mesh;
  if (triangle >= mesh.triangle_count() || !std::isfinite(u) || !std::isfinite(v)) return false;
  const uint32_t* idx = &mesh.indices[3 * static_cast<size_t>(triangle)];
  const Vec3 &p0 = mesh.positions[idx[0]], &p1 = mesh.positions[idx[1]],
             &p2 = mesh.positions[idx[2]];
  const Transform& to_world = scene_.instances[scene_index].object_to_world;
  hit->p = to_world.point(p0 * (1.0f - u - v) + p1 * u + p2 * v);
  hit->ng_object = cross(p1 - p0, p2 - p0);  // Embree's triangle Ng
  hit->t = 0.0f;
  hit->u = u;
  hit->v = v;
  hit->instance = instance;
  hit->primitive = triangle;
  return true;
}

SurfaceInteraction Accel::interaction(const Hit& hit) const {
  // Built from what Embree returned (point, geometric normal) so the common case touches no
  // vertex data; only smooth meshes read their corner normals.
  const InstanceData& inst = instances_[hit.instance];
  const Mesh& mesh = *inst.mesh;
  const size_t tri = hit.primitive;
  const float b0 = 1.0f - hit.u - hit.v;

  SurfaceInteraction si;
  si.p = hit.p;
  si.ng = normalize(mat3_mul(inst.normal_matrix, hit.ng_object));
  si.ns = si.ng;
  if (!mesh.corner_normals.empty()) {
    const Vec3* n = &mesh.corner_normals[3 * tri];
    Vec3 ns = mat3_mul(inst.normal_matrix, n[0] * b0 + n[1] * hit.u + n[2] * hit.v);
    if (length_squared(ns) > 0.0f && is_finite(ns)) {
      ns = normalize(ns);
      si.ns = dot(ns, si.ng) < 0.0f ? -ns : ns;
    }
  }
  if (!mesh.corner_uvs.empty()) {
    const Vec2* uv = &mesh.corner_uvs[3 * tri];
    si.uv = uv[0] * b0 + uv[1] * hit.u + uv[2] * hit.v;
  }
  si.mat = &triangle_material(hit.instance, hit.primitive, &si.material);
  si.instance = hit.instance;
  si.primitive = hit.primitive;
  si.barycentric = Vec2(hit.u, hit.v);
  si.scene = &scene_;
  si.object = &scene_.instances[inst.scene_index];
  si.mesh = &mesh;
  return si;
}

bool Accel::uv_tangents(uint32_t instance, uint32_t primitive, Vec3* dpdu, Vec3* dpdv) const {
  if (instance >= instances_.size()) return false;
  const InstanceData& inst = instances_[instance];
  const Mesh& mesh = *inst.mesh;
  if (mesh.corner_uvs.empty() || 3 * primitive + 2 >= mesh.indices.size()) return false;
  const uint32_t* idx = &mesh.indices[3 * primitive];
  const Vec2* uv = &mesh.corner_uvs[3 * primitive];
  const Vec3 dp1 = mesh.positions[idx[1]] - mesh.positions[idx[0]];
  const Vec3 dp2 = mesh.positions[idx[2]] - mesh.positions[idx[0]];
  const float du1 = uv[1].x - uv[0].x, dv1 = uv[1].y - uv[0].y;
  const float du2 = uv[2].x - uv[0].x, dv2 = uv[2].y - uv[0].y;
  const float det = du1 * dv2 - dv1 * du2;
  if (!(std::fabs(det) > 1e-12f)) return false;
  const Transform& xf = scene_.instances[inst.scene_index].object_to_world;
  *dpdu = xf.vector((dp1 * dv2 - dp2 * dv1) / det);
  *dpdv = xf.vector((dp2 * du1 - dp1 * du2) / det);
  return is_finite(*dpdu) && is_finite(*dpdv);
}

const Material& Accel::triangle_material(uint32_t instance, uint32_t primitive,
                                         uint32_t* index) const {
  const InstanceData& inst = instances_[instance];
  const Mesh& mesh = *inst.mesh;
  const int32_t slot = mesh.material_slots.empty() ? 0 : mesh.material_slots[primitive];
  const int32_t material =
      (slot >= 0 && static_cast<uint32_t>(slot) < inst.slot_count) ? inst.slot_materials[slot] : -1;
  if (material >= 0 && static_cast<size_t>(material) < scene_.materials.size()) {
    if (index) *index = static_cast<uint32_t>(material);
    return scene_.materials[material];
  }
  if (index) *index = UINT32_MAX;
  return Scene::default_material();
}

}  // namespace photon
