// Photon storage and k-nearest-neighbour lookup (Jensen 2001, "Realistic Image Synthesis Using
// Photon Mapping", ch. 6): a compact 20-byte photon record in a balanced kd-tree stored
// implicitly in the photon array (base/point_kdtree.h), its split axis packed into the record,
// so the tree costs no memory beyond the photons themselves.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "photon/base/math.h"
#include "photon/base/point_kdtree.h"
#include "photon/spectral/rgb_uplift.h"

namespace photon {

// How the photon's path reached its surface, used to keep estimates from counting light twice.
enum PhotonFlags : uint8_t {
  kPhotonDirect = 1u << 0,    // first hit after leaving the light
  kPhotonCaustic = 1u << 1,   // light -> specular+ -> this diffuse surface
  kPhotonIndirect = 1u << 2,  // at least one diffuse bounce before this surface
  kPhotonAny = 0x7u,
};

// 20 bytes, as Jensen's: position 12, power as Ward's shared-exponent RGBE 4, incoming direction
// quantised to (theta, phi) 2, path flags 1, kd-tree split axis 1. The flags and the split axis
// use 5 bits between them; the other 11 hold the normal of the surface the photon lies on
// (octahedral map, 6 + 5 bits, within 6 degrees), so an estimate can leave out photons of
// another surface (Jensen 2001, sec. 7.1) at no cost in memory.
//
// A spectral map's photons carry one wavelength each in the same 4 bytes: the wavelength in
// 1/139 nm steps over 360..830 nm (uint16) and the power as a float's top 16 bits below the
// sign (8 exponent and 8 mantissa bits, rounded: 0.2% steps). The power is the spectral flux
// at the wavelength over the wavelength's sampling density (spectral_path.h, wavelength_rgb).
struct Photon {
  float position[3];
  uint8_t power_rgbe[4];  // RGB maps: RGBE; spectral maps: wavelength, power
  uint8_t theta, phi;
  uint8_t flags;  // low 3 bits: PhotonFlags; high 5 bits: normal, octahedral v
  uint8_t axis;   // low 2 bits: kd-tree split axis; high 6 bits: normal, octahedral u

  Vec3 pos() const { return {position[0], position[1], position[2]}; }
  Vec3 power() const;
  Vec3 direction() const;  // direction of travel, unit length
  Vec3 normal() const;     // unit normal of the surface on the side the photon arrived from
  uint8_t path_flags() const { return flags & kPhotonAny; }
  int split_axis() const { return axis & 3; }
  // `normal`: the surface's geometric normal on the side the photon arrived from.
  static Photon make(const Vec3& p, const Vec3& direction, const Vec3& power, uint8_t flags,
                     const Vec3& normal);

  // A spectral map's photon.
  static Photon make_spectral(const Vec3& p, const Vec3& direction, float lambda, float power,
                              uint8_t flags, const Vec3& normal);
  float wavelength() const;
  float spectral_power() const;
  void set_spectral_power(float power);
};
static_assert(sizeof(Photon) == 20, "the photon record is 20 bytes");

// Ward's RGBE with rounding to nearest (Graphics Gems II, "Real Pixels").
void encode_rgbe(const Vec3& c, uint8_t out[4]);
Vec3 decode_rgbe(const uint8_t in[4]);

// The photon map's tree keeps each photon's split axis in the record's two low axis bits.
template <>
struct PointKdNode<Photon> {
  static float coordinate(const Photon& p, int axis) { return p.position[axis]; }
  static Vec3 position(const Photon& p) { return p.pos(); }
  static constexpr bool kAxisInNode = true;
  static int axis(const Photon& p) { return p.split_axis(); }
  static void set_axis(Photon& p, int axis) {
    p.axis = static_cast<uint8_t>((p.axis & ~3u) | static_cast<unsigned>(axis));
  }
};

using PhotonNeighbor = KdNeighbor;

class PhotonMap {
 public:
  PhotonMap() = default;
  // Takes the photons and balances the tree (parallel, deterministic for a given input order).
  // When `cancel` is set during the build the map is left empty (within ~a millisecond).
  // `spectral`: the photons were made with Photon::make_spectral.
  explicit PhotonMap(std::vector<Photon> photons, const std::atomic<bool>* cancel = nullptr,
                     bool spectral = false);
  // A map of photons already in a PhotonMap's balanced order with their split axes (a saved
  // map's photons(), prepared_state_io.h): kept as they are. False (and `out` untouched) when a
  // split axis is not 0, 1 or 2.
  static bool from_balanced(std::vector<Photon> photons, bool spectral, PhotonMap* out);

  bool spectral() const { return spectral_; }
  // A photon's power in linear Rec.709 (a spectral photon's share of the XYZ estimate).
  Vec3 power(const Photon& ph) const;

  size_t size() const { return tree_.size(); }
  bool empty() const { return tree_.empty(); }
  const Photon& operator[](size_t i) const { return tree_[i]; }
  size_t memory_bytes() const { return tree_.memory_bytes(); }
  // The photons in balanced order (the implicit kd-tree).
  const std::vector<Photon>& photons() const { return tree_.nodes(); }

  // The `k` nearest photons to `p` within `max_radius` whose flags intersect `flag_mask`,
  // written to `out` (cleared first) as a max-heap on distance: out->front() is the farthest.
  void k_nearest(const Vec3& p, size_t k, float max_radius, uint8_t flag_mask,
                 std::vector<PhotonNeighbor>* out) const;
  // Index of the nearest photon within max_radius, or -1.
  int64_t nearest(const Vec3& p, float max_radius, uint8_t flag_mask) const;

  // Reflected radiance of a Lambertian surface of albedo 1 at `p` with normal `n` (multiply by
  // the albedo): Jensen 2001 sec. 7.1 with f_r = 1/pi, the k nearest photons in a disc of area
  // pi r^2, weighted by the cone filter w = 1 - d / (c r), normalised by 1 - 2 / (3c) (Jensen
  // 1996, c = 1.1). Only photons that lie on the queried surface count, so light does not leak
  // through walls (photon_on_surface). `scratch` avoids allocation per query.
  // `at_photon`: p is a stored photon itself (radiance precomputed at photon positions), which
  // the estimate always counts. The disc is then that of the k nearest photons of this surface
  // alone: a disc shrunk by photons of other surfaces (the lit inside of a closed mesh's face,
  // a wall beside a floor) counts that one photon over a tiny area (measured: a lamp sealed in
  // a closed cube brightened the floor under it by 25% through the cube's lit inner bottom
  // face). Elsewhere the plain k nearest set it, which is as exact and far cheaper where most
  // near photons belong to another surface.
  Vec3 radiance_estimate(const Vec3& p, const Vec3& n, size_t k, float max_radius,
                         uint8_t flag_mask, std::vector<PhotonNeighbor>* scratch,
                         bool at_photon = false) const;
  // The same estimate for a surface of diffuse reflectance `albedo` (the estimate times it): a
  // spectral map multiplies each photon by the reflectance at its own wavelength, so coloured
  // light on coloured surfaces is reflected as spectra are, not as RGB products.
  Vec3 reflected_estimate(const Vec3& p, const Vec3& n, size_t k, float max_radius,
                          uint8_t flag_mask, const Vec3& albedo,
                          std::vector<PhotonNeighbor>* scratch) const;

  // Median distance from a stored photon to its k-th nearest photon (itself included), over up
  // to `samples` photons spread through the map: the radius of the disc a k-nearest estimate
  // covers at a typical photon. 0 when the map holds fewer than k photons of `flag_mask`.
  float median_kth_distance(size_t k, uint8_t flag_mask, size_t samples = 256) const;

 private:
  // The cone-filtered sum of the k nearest photons' `value(photon)` as radiance (the shared part
  // of both estimates).
  template <class Value>
  Vec3 estimate(const Vec3& p, const Vec3& n, size_t k, float max_radius, uint8_t flag_mask,
                bool on_surface_only, std::vector<PhotonNeighbor>* scratch, Value&& value) const;
  PointKdTree<Photon> tree_;
  bool spectral_ = false;
};

// Whether a photon can belong to the surface through p with normal n (Jensen 2001, sec. 7.1:
// photons of other surfaces within the search sphere bias the estimate; behind a wall they
// leak light through it). It must
//  - have arrived from the side n faces (dot(direction, n) < 0): not the far side of a thin wall;
//  - lie on the same surface as p (on_same_surface).
bool photon_on_surface(const Photon& photon, const Vec3& p, const Vec3& n, float distance);

// Whether a point q with normal nq, `distance` from p, can lie on the same smooth surface as p
// with normal n:
//  - the normals agree, dot(nq, n) >= kSurfaceMinCos: not the inner face of an adjacent wall
//    at a corner or edge of a closed object;
//  - q is no farther off p's tangent plane than a surface bending from n to nq puts it (Jensen's
//    search sphere compressed into a disc along n): between p and q at distance d on a sphere
//    whose normals differ by theta, |(q - p) . n| = d sin(theta / 2), allowed up to
//    d (sin(theta / 2) + kSurfaceSlope). Not a parallel surface across a gap, such as the
//    inside of a box's bottom over the floor (theta = 0, height = the gap).
constexpr float kSurfaceMinCos = 0.25f;
constexpr float kSurfaceSlope = 0.1f;
bool on_same_surface(const Vec3& p, const Vec3& n, const Vec3& q, const Vec3& nq, float distance);

// Sum of the photons' power (used by tests and statistics), in linear Rec.709 for spectral ones.
Vec3 total_power(const std::vector<Photon>& photons, uint8_t flag_mask = kPhotonAny,
                 bool spectral = false);

}  // namespace photon
