#include "photon/render/blas_cache.h"

#include <cstring>
#include <string_view>

namespace photon {
namespace {

RTCScene new_blas(RTCDevice device, const Mesh& mesh) {
  RTCGeometry geom = embree::new_triangle_geometry(device);
  // Both buffers are copies owned by Embree: the cached BVH outlives the Scene it came from.
  // Embree reads vertices with 16-byte loads; its own buffers are padded for that.
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sizeof(Vec3), mesh.positions.size()));
  if (vertices) std::memcpy(vertices, mesh.positions.data(), mesh.positions.size() * sizeof(Vec3));
  auto* indices = static_cast<uint32_t*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                              3 * sizeof(uint32_t), mesh.triangle_count()));
  if (indices) std::memcpy(indices, mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t));
  rtcCommitGeometry(geom);
  RTCScene blas = rtcNewScene(device);
  rtcSetSceneFlags(blas, RTC_SCENE_FLAG_ROBUST);  // as Accel's own BVHs
  rtcAttachGeometryByID(blas, geom, 0);
  rtcReleaseGeometry(geom);
  return blas;
}

}  // namespace

uint64_t mesh_geometry_hash(const Mesh& mesh) {
  const std::string_view p(reinterpret_cast<const char*>(mesh.positions.data()),
                           mesh.positions.size() * sizeof(Vec3));
  const std::string_view i(reinterpret_cast<const char*>(mesh.indices.data()),
                           mesh.indices.size() * sizeof(uint32_t));
  const uint64_t a = std::hash<std::string_view>{}(p);
  const uint64_t b = std::hash<std::string_view>{}(i);
  return a ^ (b + 0x9e3779b97f4a7c15ull + (a << 6) + (a >> 2));
}

BlasCache::BlasCache() {
  device_ = rtcNewDevice(nullptr);
  rtcSetDeviceErrorFunction(device_, &BlasCache::on_embree_error, this);
}

BlasCache::~BlasCache() {
  for (Entry& e : entries_) rtcReleaseScene(e.scene);
  rtcReleaseDevice(device_);
}

void BlasCache::on_embree_error(void* user, RTCError code, const char* message) {
  if (code == RTC_ERROR_CANCELLED) return;  // a build abandoned on cancel is no error
  auto* self = static_cast<BlasCache*>(user);
  std::lock_guard<std::mutex> lock(self->warnings_mutex_);
  self->warnings_.push_back("Embree error " + std::to_string(static_cast<int>(code)) + ": " +
                            (message ? message : ""));
}

bool BlasCache::same_data(const Entry& entry, const Mesh& mesh) {
  if (entry.vertex_count != mesh.positions.size() || entry.triangle_count != mesh.triangle_count())
    return false;
  RTCGeometry geom = rtcGetGeometry(entry.scene, 0);
  const void* vertices = rtcGetGeometryBufferData(geom, RTC_BUFFER_TYPE_VERTEX, 0);
  const void* indices = rtcGetGeometryBufferData(geom, RTC_BUFFER_TYPE_INDEX, 0);
  return vertices && indices &&
         std::memcmp(vertices, mesh.positions.data(), mesh.positions.size() * sizeof(Vec3)) == 0 &&
         std::memcmp(indices, mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t)) == 0;
}

bool BlasCache::acquire(const Mesh& mesh, const std::function<bool(RTCScene)>& commit,
                        RTCScene* blas, bool* reused) {
  const uint64_t hash = mesh_geometry_hash(mesh);
  std::lock_guard<std::mutex> lock(mutex_);
  for (Entry& e : entries_)
    if (e.hash == hash && same_data(e, mesh)) {
      e.used = true;
      rtcRetainScene(e.scene);
      *blas = e.scene;
      *reused = true;
      return true;
    }
  *reused = false;
  RTCScene scene = new_blas(device_, mesh);
  const bool built = commit(scene);
  // The progress monitor points at the caller's cancel flag, which dies with its render.
  rtcSetSceneProgressMonitorFunction(scene, nullptr, nullptr);
  if (!built) {
    rtcReleaseScene(scene);
    return false;
  }
  Entry e;
  e.hash = hash;
  e.vertex_count = mesh.positions.size();
  e.triangle_count = mesh.triangle_count();
  e.scene = scene;
  e.used = true;
  entries_.push_back(e);
  rtcRetainScene(scene);
  *blas = scene;
  return true;
}

void BlasCache::begin_frame() {
  std::lock_guard<std::mutex> lock(mutex_);
  size_t kept = 0;
  for (Entry& e : entries_) {
    if (!e.used) {
      rtcReleaseScene(e.scene);  // renders still holding it keep their own reference
      continue;
    }
    e.used = false;
    entries_[kept++] = e;
  }
  entries_.resize(kept);
}

size_t BlasCache::size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return entries_.size();
}

std::vector<std::string> BlasCache::take_warnings() {
  std::lock_guard<std::mutex> lock(warnings_mutex_);
  std::vector<std::string> out;
  out.swap(warnings_);
  return out;
}

}  // namespace photon
