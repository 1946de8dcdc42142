#include "photon/render/blas_cache.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "photon/render/accel.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace blas_cache_test {
namespace {

// Rays from inside the Cornell box in every direction, the same for every call.
std::vector<Ray> probe_rays(size_t count) {
  std::vector<Ray> rays;
  for (size_t i = 0; i < count; ++i) {
    const float a = 6.2831853f * static_cast<float>(i) / count;
    const float z = 1.0f - 2.0f * (static_cast<float>(i) + 0.5f) / count;
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    Ray ray;
    ray.origin = Vec3(0.1f, -0.2f, 1.0f);
    ray.direction = Vec3(r * std::cos(a * 37.0f), r * std::sin(a * 37.0f), z);
    rays.push_back(ray);
  }
  return rays;
}

// Every probe ray's hit, as raw bits (t, u, v, instance, primitive; zeros for a miss).
std::vector<uint32_t> hit_bits(const Accel& accel) {
  std::vector<uint32_t> bits;
  for (const Ray& ray : probe_rays(2000)) {
    Hit hit;
    const bool found = accel.intersect(ray, kVisibleAll, &hit);
    uint32_t t = 0, u = 0, v = 0;
    if (found) {
      std::memcpy(&t, &hit.t, 4);
      std::memcpy(&u, &hit.u, 4);
      std::memcpy(&v, &hit.v, 4);
    }
    bits.insert(bits.end(), {found ? 1u : 0u, t, u, v, hit.instance, hit.primitive});
  }
  return bits;
}

TEST(BlasCache, SecondAccelReusesEveryBvhAndTracesBitIdentically) {
  const Scene scene = make_cornell_box();
  std::vector<std::string> warnings;
  const Accel fresh(scene, &warnings);
  BlasCache cache;
  const Accel first(scene, &warnings, nullptr, BvhQuality::kFastTrace, &cache);
  EXPECT_EQ(first.blas_reused(), 0u);
  EXPECT_EQ(first.blas_count(), fresh.blas_count());
  EXPECT_EQ(cache.size(), fresh.blas_count());

  // The next frame: a new Scene with the same meshes, one instance moved.
  Scene next = make_cornell_box();
  next.instances.back().object_to_world.m[0][3] += 0.05f;
  cache.begin_frame();
  const Accel second(next, &warnings, nullptr, BvhQuality::kFastTrace, &cache);
  EXPECT_EQ(second.blas_reused(), second.blas_count());
  EXPECT_EQ(cache.size(), fresh.blas_count());
  EXPECT_TRUE(warnings.empty());

  EXPECT_EQ(hit_bits(first), hit_bits(fresh));
  const Accel next_fresh(next, &warnings);
  EXPECT_EQ(hit_bits(second), hit_bits(next_fresh));
  EXPECT_NE(hit_bits(second), hit_bits(first));  // the moved instance shows
}

TEST(BlasCache, ChangedMeshGetsItsOwnBvh) {
  const Scene scene = make_cornell_box();
  BlasCache cache;
  std::vector<std::string> warnings;
  { const Accel first(scene, &warnings, nullptr, BvhQuality::kFastTrace, &cache); }
  Scene edited = make_cornell_box();
  // The last bit of one vertex: content, not names or sizes, decides reuse.
  Mesh& mesh = edited.meshes.back();
  uint32_t x;
  std::memcpy(&x, &mesh.positions[0].x, 4);
  ++x;
  std::memcpy(&mesh.positions[0].x, &x, 4);
  cache.begin_frame();
  const Accel second(edited, &warnings, nullptr, BvhQuality::kFastTrace, &cache);
  EXPECT_EQ(second.blas_reused(), second.blas_count() - 1);
  const Accel edited_fresh(edited, &warnings);
  EXPECT_EQ(hit_bits(second), hit_bits(edited_fresh));
  // begin_frame drops what the last frame did not use: the old version of the edited mesh.
  EXPECT_EQ(cache.size(), second.blas_count() + 1);
  cache.begin_frame();
  EXPECT_EQ(cache.size(), second.blas_count());
  cache.begin_frame();
  EXPECT_EQ(cache.size(), 0u);
  // Accels keep their own references: the emptied cache does not pull BVHs from under them.
  EXPECT_EQ(hit_bits(second), hit_bits(edited_fresh));
}

TEST(BlasCache, CancelledBuildCachesNothing) {
  const Scene scene = make_cornell_box();
  BlasCache cache;
  std::vector<std::string> warnings;
  std::atomic<bool> cancel{true};
  const Accel cancelled(scene, &warnings, &cancel, BvhQuality::kFastTrace, &cache);
  EXPECT_TRUE(cancelled.cancelled());
  EXPECT_EQ(cache.size(), 0u);
  const Accel after(scene, &warnings, nullptr, BvhQuality::kFastTrace, &cache);
  EXPECT_EQ(after.blas_reused(), 0u);
  EXPECT_EQ(hit_bits(after), hit_bits(Accel(scene, &warnings)));
}

}  // namespace
}  // namespace blas_cache_test
}  // namespace photon
