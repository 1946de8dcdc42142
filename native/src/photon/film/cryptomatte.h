// Cryptomatte coverage (Cryptomatte 1.2 specification, Friedman & Jones, Psyop 2015): for every
// pixel, the IDs its camera samples hit first and the share of the samples that hit each, ranked
// by share. The IDs are floats made by the add-on from names (MurmurHash3, see
// addon/photon/cryptomatte.py); here they are only compared bit for bit.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace photon {

// Cryptomatte passes hold two (ID, coverage) ranks per RGBA layer.
constexpr int kCryptomatteRanksPerLayer = 2;

// Layers of `depth` ranks (Blender's view_layer.pass_cryptomatte_depth, rounded up to a pair).
inline int cryptomatte_layers(int depth) {
  return (depth + kCryptomatteRanksPerLayer - 1) / kCryptomatteRanksPerLayer;
}

// The coverage of one row of pixels while its samples are traced.
class CryptomatteRow {
 public:
  CryptomatteRow(size_t width, int depth);

  void clear();
  // One sample of `pixel` hit something with `id`, counted with `weight` (1 for a sample
  // that reached it unobstructed). The background has no ID and is not added.
  void add(size_t pixel, float id, float weight);
  // The pixel's ranks, highest coverage first (equal coverage: lower ID bits first), as
  // cryptomatte_layers(depth) RGBA layers (ID, coverage, ID, coverage), the coverage divided
  // by `samples`; missing ranks are zero. `out` holds 4 * cryptomatte_layers(depth) floats.
  void write(size_t pixel, int samples, float* out) const;

 private:
  int depth_;
  // Per pixel, the IDs met so far (as bits) and their summed weights. The IDs a pixel sees
  // are few, so a short list searched in order is quicker than a map.
  std::vector<std::vector<std::pair<uint32_t, float>>> coverage_;
};

}  // namespace photon
