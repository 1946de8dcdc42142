// Bottom-level BVHs kept between renders (Blender's Render > Performance > Persistent Data):
// an animation whose meshes do not change builds each mesh's BVH once. Entries are found by
// content (vertex positions and triangle indices compared exactly, a hash only narrows the
// search), so a reused BVH is the one a fresh build would make from the same data, and a
// changed mesh can never be served a stale one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "photon/render/embree.h"
#include "photon/scene/scene.h"

namespace photon {

class BlasCache {
 public:
  BlasCache();
  ~BlasCache();
  BlasCache(const BlasCache&) = delete;
  BlasCache& operator=(const BlasCache&) = delete;

  // The Embree device every cached BVH, and the top level instancing them, lives on.
  RTCDevice device() const { return device_; }

  // A BVH over `mesh`'s positions and triangles, retained for the caller (rtcReleaseScene it).
  // An entry with identical data is returned as is (*reused = true); otherwise one is built
  // with `commit` (which may abandon the build: it returns false, and so does acquire, with
  // nothing cached). Thread-safe.
  bool acquire(const Mesh& mesh, const std::function<bool(RTCScene)>& commit, RTCScene* blas,
               bool* reused);

  // Starts a new frame: entries not acquired since the previous call are dropped, so the cache
  // holds at most the meshes of the last frame rendered (plus those of the current one).
  void begin_frame();

  size_t size() const;
  // Embree errors raised on the cache's device since the last call.
  std::vector<std::string> take_warnings();

 private:
  struct Entry {
    uint64_t hash = 0;
    size_t vertex_count = 0, triangle_count = 0;
    RTCScene scene = nullptr;
    bool used = false;  // acquired since the last begin_frame()
  };

  static void on_embree_error(void* user, RTCError code, const char* message);
  static bool same_data(const Entry& entry, const Mesh& mesh);

  RTCDevice device_ = nullptr;
  mutable std::mutex mutex_;  // entries_
  std::vector<Entry> entries_;
  std::mutex warnings_mutex_;  // apart: Embree reports errors while acquire() holds mutex_
  std::vector<std::string> warnings_;
};

// Hash of a mesh's positions and triangle indices (what its BVH is built from).
uint64_t mesh_geometry_hash(const Mesh& mesh);

}  // namespace photon
