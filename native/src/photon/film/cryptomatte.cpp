#include "photon/film/cryptomatte.h"

#include <algorithm>
#include <cstring>

namespace photon {
namespace {

uint32_t float_bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

float bits_float(uint32_t u) {
  float f;
  std::memcpy(&f, &u, sizeof f);
  return f;
}

}  // namespace

CryptomatteRow::CryptomatteRow(size_t width, int depth)
    : depth_(std::max(depth, 0)), coverage_(width) {}

void CryptomatteRow::clear() {
  for (auto& pixel : coverage_) pixel.clear();
}

void CryptomatteRow::add(size_t pixel, float id, float weight) {
  if (pixel >= coverage_.size() || !(weight > 0.0f)) return;
  const uint32_t bits = float_bits(id);
  auto& entries = coverage_[pixel];
  for (auto& entry : entries) {
    if (entry.first == bits) {
      entry.second += weight;
      return;
    }
  }
  entries.emplace_back(bits, weight);
}

void CryptomatteRow::write(size_t pixel, int samples, float* out) const {
  const int layers = cryptomatte_layers(depth_);
  std::fill(out, out + 4 * layers, 0.0f);
  if (pixel >= coverage_.size() || samples <= 0) return;
  std::vector<std::pair<uint32_t, float>> ranked = coverage_[pixel];
  std::sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) {
    return a.second != b.second ? a.second > b.second : a.first < b.first;
  });
  const size_t kept = std::min(ranked.size(), static_cast<size_t>(depth_));
  for (size_t r = 0; r < kept; ++r) {
    out[2 * r] = bits_float(ranked[r].first);
    out[2 * r + 1] = ranked[r].second / static_cast<float>(samples);
  }
}

}  // namespace photon
