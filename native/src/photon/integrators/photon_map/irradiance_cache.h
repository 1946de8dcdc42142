// Irradiance caching (Ward, Rubinstein & Clear 1988, "A Ray Tracing Solution for Diffuse
// Interreflection"): the final-gather result, which varies slowly over diffuse surfaces, is
// computed carefully at sparse records and interpolated in between. This file holds the records
// and their lookup; irradiance_cache_build.h places them.
//
// A record i at x_i with normal n_i and radius R_i (the harmonic mean distance of its gather
// hits) predicts the value at x with normal n with Ward's error measure (1988, eq. 5 inverted)
//   eps_i(x, n) = |x - x_i| / R_i + sqrt(1 - n . n_i),   w_i = 1 / eps_i,
// and is used where w_i > 1 / a (eps_i < a) for the accuracy parameter a. The interpolation
// weight is w_i - 1/a rather than Ward's w_i: it falls to zero at the edge of a record's
// domain, so records appearing and disappearing leave no visible boundary (the same reason
// Tabellion & Lamorlette 2004 use a weight that vanishes at the edge). Records in front of x
// (Ward's d_i < 0 test) are skipped.
#pragma once

#include <cstdint>
#include <vector>

#include "photon/base/math.h"

namespace photon {

struct IrradianceRecord {
  Vec3 p;
  Vec3 n;               // unit shading normal on the side the gather rays left
  Vec3 value;           // reflected radiance for albedo 1 (multiply by the diffuse reflectance)
  float radius = 0.0f;  // Ward's R_i, world units
};

// Ward's eps_i(x, n); larger is worse. Infinity when the normals face apart.
float ward_error(const IrradianceRecord& record, const Vec3& p, const Vec3& n);

// True when `record` lies in front of the point (p, n) (Ward 1988's d_i test) by more than a
// small tolerance, so it saw a different neighbourhood and must not be used.
bool record_in_front(const IrradianceRecord& record, const Vec3& p, const Vec3& n);

class IrradianceCache {
 public:
  IrradianceCache() = default;
  // `accuracy` is Ward's a (> 0). The records keep their order; the lookup structure depends
  // only on the input, so results are deterministic.
  IrradianceCache(std::vector<IrradianceRecord> records, float accuracy);

  bool empty() const { return records_.empty(); }
  size_t size() const { return records_.size(); }
  float accuracy() const { return accuracy_; }
  const std::vector<IrradianceRecord>& records() const { return records_; }
  size_t memory_bytes() const;

  // Weighted average of the records with eps_i < a at (p, n); false when there is none.
  bool lookup(const Vec3& p, const Vec3& n, Vec3* value) const;
  // True when some record has eps_i < max_error at (p, n).
  bool covers(const Vec3& p, const Vec3& n, float max_error) const;

 private:
  // A bounding volume hierarchy over the records' spheres of influence (radius a R_i).
  struct Node {
    Vec3 lo, hi;
    uint32_t first = 0;  // leaf: first index into order_; inner: index of the right child
    uint32_t count = 0;  // leaf: number of records; 0 for an inner node (left child = this + 1)
  };
  template <typename Visit>
  void for_each_candidate(const Vec3& p, Visit&& visit) const;
  uint32_t build(uint32_t begin, uint32_t end);

  std::vector<IrradianceRecord> records_;
  std::vector<uint32_t> order_;
  std::vector<Node> nodes_;
  float accuracy_ = 0.25f;
};

}  // namespace photon
