#include "photon/integrators/photon_map/photon_map.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "photon/base/cancel_poll.h"

namespace photon {
namespace {

// 256 quantised angles each way: a lookup table instead of sin/cos per decoded photon.
struct DirectionTable {
  float cos_theta[256], sin_theta[256], cos_phi[256], sin_phi[256];
  DirectionTable() {
    for (int i = 0; i < 256; ++i) {
      const float theta = (i + 0.5f) * (kPi / 256.0f);
      const float phi = (i + 0.5f) * (2.0f * kPi / 256.0f);
      cos_theta[i] = std::cos(theta);
      sin_theta[i] = std::sin(theta);
      cos_phi[i] = std::cos(phi);
      sin_phi[i] = std::sin(phi);
    }
  }
};
const DirectionTable& direction_table() {
  static const DirectionTable table;
  return table;
}

uint8_t quantise(float x, float scale) {
  const int q = static_cast<int>(x * scale);
  return static_cast<uint8_t>(std::clamp(q, 0, 255));
}

constexpr float kConeFilterC = 1.1f;  // Jensen's cone filter constant, c >= 1

// Octahedral normal map (Meyer et al. 2010, "On Floating-Point Normal Vectors"): the unit sphere
// folded onto the square [-1, 1]^2, quantised to 64 x 32 cells.
constexpr int kNormalUBits = 6, kNormalVBits = 5;
constexpr int kNormalULevels = (1 << kNormalUBits) - 1, kNormalVLevels = (1 << kNormalVBits) - 1;

Vec2 octahedral_encode(const Vec3& n) {
  const float l1 = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
  if (!(l1 > 0.0f) || !std::isfinite(l1)) return {0.0f, 0.0f};  // +z: unknown normal
  float u = n.x / l1, v = n.y / l1;
  if (n.z < 0.0f) {
    const float fu = (1.0f - std::abs(v)) * std::copysign(1.0f, u);
    const float fv = (1.0f - std::abs(u)) * std::copysign(1.0f, v);
    u = fu;
    v = fv;
  }
  return {u, v};
}

Vec3 octahedral_decode(float u, float v) {
  const float z = 1.0f - std::abs(u) - std::abs(v);
  if (z < 0.0f) {
    const float fu = (1.0f - std::abs(v)) * std::copysign(1.0f, u);
    const float fv = (1.0f - std::abs(u)) * std::copysign(1.0f, v);
    u = fu;
    v = fv;
  }
  return normalize(Vec3(u, v, z));
}

int quantise_signed(float x, int levels) {
  return std::clamp(static_cast<int>(std::lround((x * 0.5f + 0.5f) * levels)), 0, levels);
}

}  // namespace

void encode_rgbe(const Vec3& c, uint8_t out[4]) {
  const float m = std::max(max_component(c), 0.0f);
  if (!(m > 1e-32f) || !std::isfinite(m)) {
    out[0] = out[1] = out[2] = out[3] = 0;
    return;
  }
  int e;
  std::frexp(m, &e);  // m = f * 2^e, f in [0.5, 1)
  float scale = std::ldexp(1.0f, 8 - e);
  // Round to nearest; if the largest channel rounds up to 256, use the next exponent.
  if (m * scale + 0.5f >= 256.0f) {
    ++e;
    scale *= 0.5f;
  }
  auto channel = [&](float v) {
    return static_cast<uint8_t>(
        std::clamp(static_cast<int>(std::max(v, 0.0f) * scale + 0.5f), 0, 255));
  };
  out[0] = channel(c.x);
  out[1] = channel(c.y);
  out[2] = channel(c.z);
  out[3] = static_cast<uint8_t>(std::clamp(e + 128, 0, 255));
}

Vec3 decode_rgbe(const uint8_t in[4]) {
  if (in[3] == 0) return Vec3(0.0f);
  const float f = std::ldexp(1.0f, static_cast<int>(in[3]) - (128 + 8));
  return {in[0] * f, in[1] * f, in[2] * f};
}

Vec3 Photon::power() const {
  return decode_rgbe(power_rgbe);
}

Vec3 Photon::direction() const {
  const DirectionTable& t = direction_table();
  return {t.sin_theta[theta] * t.cos_phi[phi], t.sin_theta[theta] * t.sin_phi[phi],
          t.cos_theta[theta]};
}

Vec3 Photon::normal() const {
  const float u = (axis >> 2) * (2.0f / kNormalULevels) - 1.0f;
  const float v = (flags >> 3) * (2.0f / kNormalVLevels) - 1.0f;
  return octahedral_decode(u, v);
}

Photon Photon::make(const Vec3& p, const Vec3& direction, const Vec3& power, uint8_t flags,
                    const Vec3& normal) {
  Photon ph{};
  ph.position[0] = p.x;
  ph.position[1] = p.y;
  ph.position[2] = p.z;
  encode_rgbe(power, ph.power_rgbe);
  const float theta = std::acos(std::clamp(direction.z, -1.0f, 1.0f));
  float phi = std::atan2(direction.y, direction.x);
  if (phi < 0.0f) phi += 2.0f * kPi;
  ph.theta = quantise(theta, 256.0f / kPi);
  ph.phi = quantise(phi, 256.0f / (2.0f * kPi));
  const Vec2 uv = octahedral_encode(normal);
  ph.flags =
      static_cast<uint8_t>((flags & kPhotonAny) | quantise_signed(uv.y, kNormalVLevels) << 3);
  ph.axis = static_cast<uint8_t>(quantise_signed(uv.x, kNormalULevels) << 2);
  return ph;
}

namespace {

constexpr float kWavelengthSteps = 65535.0f / (spectral::kLambdaMax - spectral::kLambdaMin);

}  // namespace

Photon Photon::make_spectral(const Vec3& p, const Vec3& direction, float lambda, float power,
                             uint8_t flags, const Vec3& normal) {
  Photon ph = make(p, direction, Vec3(0.0f), flags, normal);
  const float code = std::clamp((lambda - spectral::kLambdaMin) * kWavelengthSteps, 0.0f, 65535.0f);
  const auto w = static_cast<uint16_t>(std::lround(std::isfinite(code) ? code : 0.0f));
  std::memcpy(ph.power_rgbe, &w, 2);
  ph.set_spectral_power(power);
  return ph;
}

float Photon::wavelength() const {
  uint16_t w;
  std::memcpy(&w, power_rgbe, 2);
  return spectral::kLambdaMin + static_cast<float>(w) / kWavelengthSteps;
}

float Photon::spectral_power() const {
  uint16_t q;
  std::memcpy(&q, power_rgbe + 2, 2);
  const uint32_t bits = static_cast<uint32_t>(q) << 15;
  float v;
  std::memcpy(&v, &bits, 4);
  return v;
}

void Photon::set_spectral_power(float power) {
  uint16_t q = 0;
  if (power > 0.0f && std::isfinite(power)) {
    uint32_t bits;
    std::memcpy(&bits, &power, 4);
    // Round to the nearest of the kept 16 bits; the largest finite floats saturate.
    bits = std::min<uint32_t>(bits + (1u << 14), 0x7F7FFFFFu);
    q = static_cast<uint16_t>(bits >> 15);
  }
  std::memcpy(power_rgbe + 2, &q, 2);
}

PhotonMap::PhotonMap(std::vector<Photon> photons, const std::atomic<bool>* cancel, bool spectral)
    : spectral_(spectral) {
  try {
    if (photons.capacity() != photons.size()) {
      // shrink_to_fit, in slices that poll for cancellation (a billion-photon copy takes seconds).
      std::vector<Photon> exact;
      exact.reserve(photons.size());
      constexpr size_t kSlice = size_t{1} << 20;
      for (size_t i = 0; i < photons.size(); i += kSlice) {
        if (cancel && cancel->load(std::memory_order_relaxed)) throw Cancelled();
        exact.insert(exact.end(), photons.begin() + i,
                     photons.begin() + std::min(photons.size(), i + kSlice));
      }
      photons.swap(exact);
    }
    tree_ = PointKdTree<Photon>(std::move(photons), cancel);
  } catch (const Cancelled&) {
    tree_ = PointKdTree<Photon>();
  }
}

bool PhotonMap::from_balanced(std::vector<Photon> photons, bool spectral, PhotonMap* out) {
  for (const Photon& p : photons)
    if (p.split_axis() > 2) return false;
  out->tree_ = PointKdTree<Photon>::from_balanced(std::move(photons));
  out->spectral_ = spectral;
  return true;
}

void PhotonMap::k_nearest(const Vec3& p, size_t k, float max_radius, uint8_t flag_mask,
                          std::vector<PhotonNeighbor>* out) const {
  tree_.k_nearest(
      p, k, max_radius, [flag_mask](const Photon& ph) { return (ph.flags & flag_mask) != 0; }, out);
}

int64_t PhotonMap::nearest(const Vec3& p, float max_radius, uint8_t flag_mask) const {
  std::vector<PhotonNeighbor> one;
  one.reserve(1);
  k_nearest(p, 1, max_radius, flag_mask, &one);
  return one.empty() ? -1 : static_cast<int64_t>(one[0].index);
}

Vec3 PhotonMap::power(const Photon& ph) const {
  return spectral_ ? spectral::wavelength_rec709(ph.wavelength()) * ph.spectral_power()
                   : ph.power();
}

Vec3 PhotonMap::radiance_estimate(const Vec3& p, const Vec3& n, size_t k, float max_radius,
                                  uint8_t flag_mask, std::vector<PhotonNeighbor>* scratch,
                                  bool at_photon) const {
  if (!spectral_)
    return estimate(p, n, k, max_radius, flag_mask, at_photon, scratch,
                    [](const Photon& ph) { return ph.power(); });
  return estimate(p, n, k, max_radius, flag_mask, at_photon, scratch, [](const Photon& ph) {
    return spectral::wavelength_rec709(ph.wavelength()) * ph.spectral_power();
  });
}

Vec3 PhotonMap::reflected_estimate(const Vec3& p, const Vec3& n, size_t k, float max_radius,
                                   uint8_t flag_mask, const Vec3& albedo,
                                   std::vector<PhotonNeighbor>* scratch) const {
  if (!spectral_) return radiance_estimate(p, n, k, max_radius, flag_mask, scratch) * albedo;
  const spectral::ReflectanceSpectrum reflectance(albedo);
  return estimate(p, n, k, max_radius, flag_mask, false, scratch, [&](const Photon& ph) {
    const float lambda = ph.wavelength();
    return spectral::wavelength_rec709(lambda) * (ph.spectral_power() * reflectance(lambda));
  });
}

template <class Value>
Vec3 PhotonMap::estimate(const Vec3& p, const Vec3& n, size_t k, float max_radius,
                         uint8_t flag_mask, bool on_surface_only,
                         std::vector<PhotonNeighbor>* scratch, Value&& value) const {
  if (on_surface_only)
    tree_.k_nearest(
        p, k, max_radius, [flag_mask](const Photon& ph) { return (ph.flags & flag_mask) != 0; },
        [&](const Photon& ph, float d2) { return photon_on_surface(ph, p, n, std::sqrt(d2)); },
        scratch);
  else
    k_nearest(p, k, max_radius, flag_mask, scratch);
  if (scratch->empty()) return Vec3(0.0f);
  // With fewer than k photons inside max_radius the disc is the whole search disc; otherwise it
  // is the disc through the farthest of the k (Jensen's expanding sphere).
  const float r2 =
      scratch->size() < k ? max_radius * max_radius : scratch->front().distance_squared;
  if (!(r2 > 0.0f)) return Vec3(0.0f);
  const float r = std::sqrt(r2);
  Vec3 sum(0.0f);
  for (const PhotonNeighbor& nb : *scratch) {
    const Photon& ph = tree_[nb.index];
    const float d = std::sqrt(nb.distance_squared);
    if (!photon_on_surface(ph, p, n, d)) continue;
    const float w = 1.0f - d / (kConeFilterC * r);
    sum += value(ph) * w;
  }
  const float norm = 1.0f - 2.0f / (3.0f * kConeFilterC);
  return sum * (kInvPi / (norm * kPi * r2));
}

bool photon_on_surface(const Photon& photon, const Vec3& p, const Vec3& n, float distance) {
  if (dot(photon.direction(), n) >= 0.0f) return false;
  return on_same_surface(p, n, photon.pos(), photon.normal(), distance);
}

bool on_same_surface(const Vec3& p, const Vec3& n, const Vec3& q, const Vec3& nq, float distance) {
  const float c = dot(nq, n);
  if (!(c >= kSurfaceMinCos)) return false;
  const float sin_half = std::sqrt(std::max(0.0f, 0.5f * (1.0f - c)));
  // An allowance relative to |p| keeps points on the plane itself when they are within float
  // round-off of p (relative, so that a scene a micrometre across is not one surface).
  const float height = std::abs(dot(q - p, n));
  return height <= (sin_half + kSurfaceSlope) * distance +
                       1e-6f * std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
}

float PhotonMap::median_kth_distance(size_t k, uint8_t flag_mask, size_t samples) const {
  if (tree_.empty() || k == 0 || samples == 0) return 0.0f;
  // The tree is stored in order (each range's median is its node), so evenly spaced indices
  // are spread over the photons' extent.
  const size_t step = std::max<size_t>(1, tree_.size() / samples);
  std::vector<float> distances;
  std::vector<PhotonNeighbor> scratch;
  for (size_t i = step / 2; i < tree_.size(); i += step) {
    if (!(tree_[i].path_flags() & flag_mask)) continue;
    k_nearest(tree_[i].pos(), k, INFINITY, flag_mask, &scratch);
    if (scratch.size() == k) distances.push_back(std::sqrt(scratch.front().distance_squared));
  }
  if (distances.empty()) return 0.0f;
  std::nth_element(distances.begin(), distances.begin() + distances.size() / 2, distances.end());
  return distances[distances.size() / 2];
}

Vec3 total_power(const std::vector<Photon>& photons, uint8_t flag_mask, bool spectral) {
  double s[3] = {0, 0, 0};
  for (const Photon& ph : photons) {
    if (!(ph.flags & flag_mask)) continue;
    const Vec3 p =
        spectral ? spectral::wavelength_rec709(ph.wavelength()) * ph.spectral_power() : ph.power();
    s[0] += p.x;
    s[1] += p.y;
    s[2] += p.z;
  }
  return {static_cast<float>(s[0]), static_cast<float>(s[1]), static_cast<float>(s[2])};
}

}  // namespace photon
