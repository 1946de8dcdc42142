// Photon storage and k-nearest-neighbour lookup (Jensen 2001, "Realistic Image Synthesis Using
// Photon Mapping", ch. 6): a compact 20-byte photon record and a balanced kd-tree stored
// implicitly in the photon array (the median of every range is its node), so the tree costs no
// memory beyond the photons themselves.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "photon/math.h"

namespace photon {

// How the photon's path reached its surface, used to keep estimates from counting light twice.
enum PhotonFlags : uint8_t {
  kPhotonDirect = 1u << 0,    // first hit after leaving the light
  kPhotonCaustic = 1u << 1,   // light -> specular+ -> this diffuse surface
  kPhotonIndirect = 1u << 2,  // at least one diffuse bounce before this surface
  kPhotonAny = 0x7u,
};

// 20 bytes, as Jensen's: position 12, power as Ward's shared-exponent RGBE 4, incoming direction
// quantised to (theta, phi) 2, path flags 1, kd-tree split axis 1.
struct Photon {
  float position[3];
  uint8_t power_rgbe[4];
  uint8_t theta, phi;
  uint8_t flags;
  uint8_t axis;

  Vec3 pos() const { return {position[0], position[1], position[2]}; }
  Vec3 power() const;
  Vec3 direction() const;  // direction of travel, unit length
  static Photon make(const Vec3& p, const Vec3& direction, const Vec3& power, uint8_t flags);
};
static_assert(sizeof(Photon) == 20, "the photon record is 20 bytes");

// Ward's RGBE with rounding to nearest (Graphics Gems II, "Real Pixels").
void encode_rgbe(const Vec3& c, uint8_t out[4]);
Vec3 decode_rgbe(const uint8_t in[4]);

struct PhotonNeighbor {
  uint32_t index;
  float distance_squared;
};

class PhotonMap {
 public:
  PhotonMap() = default;
  // Takes the photons and balances the tree (parallel, deterministic for a given input order).
  // When `cancel` is set during the build the map is left empty (within ~a millisecond).
  explicit PhotonMap(std::vector<Photon> photons, const std::atomic<bool>* cancel = nullptr);

  size_t size() const { return photons_.size(); }
  bool empty() const { return photons_.empty(); }
  const Photon& operator[](size_t i) const { return photons_[i]; }
  size_t memory_bytes() const { return photons_.capacity() * sizeof(Photon); }

  // The `k` nearest photons to `p` within `max_radius` whose flags intersect `flag_mask`,
  // written to `out` (cleared first) as a max-heap on distance: out->front() is the farthest.
  void k_nearest(const Vec3& p, size_t k, float max_radius, uint8_t flag_mask,
                 std::vector<PhotonNeighbor>* out) const;
  // Index of the nearest photon within max_radius, or -1.
  int64_t nearest(const Vec3& p, float max_radius, uint8_t flag_mask) const;

  // Reflected radiance of a Lambertian surface of albedo 1 at `p` with normal `n` (multiply by
  // the albedo): seed 000 eq. 2.7 with f_r = 1/pi, the k nearest photons in a disc of area
  // pi r^2, weighted by the cone filter w = 1 - d / (c r), normalised by 1 - 2 / (3c) (Jensen
  // 1996, c = 1.1). Photons arriving from behind the surface (dot(dir, n) >= 0) are skipped, so
  // light does not leak through thin walls. `scratch` avoids allocation per query.
  Vec3 radiance_estimate(const Vec3& p, const Vec3& n, size_t k, float max_radius,
                         uint8_t flag_mask, std::vector<PhotonNeighbor>* scratch) const;

  // Median distance from a stored photon to its k-th nearest photon (itself included), over up
  // to `samples` photons spread through the map: the radius of the disc a k-nearest estimate
  // covers at a typical photon. 0 when the map holds fewer than k photons of `flag_mask`.
  float median_kth_distance(size_t k, uint8_t flag_mask, size_t samples = 256) const;

 private:
  void build(size_t lo, size_t hi, int depth, const std::atomic<bool>* cancel);
  std::vector<Photon> photons_;
};

// Sum of the photons' power (used by tests and statistics).
Vec3 total_power(const std::vector<Photon>& photons, uint8_t flag_mask = kPhotonAny);

}  // namespace photon
