// Photon-guided final gathering (Jensen 1995, "Importance Driven Path Tracing using the Photon
// Map"): the directions of the photons that reached a point after a diffuse bounce show where
// its indirect light comes from. They are binned into an 8 x 8 histogram over the hemisphere
// (in the square of the concentric cosine mapping, where cosine sampling is uniform), and final
// gather rays are drawn from an equal mixture of that histogram and cosine sampling, so
// bright patches get more rays and no direction gets none.
#pragma once

#include <cstdint>
#include <vector>

#include "photon/integrators/photon_map/photon_map.h"

namespace photon {

constexpr int kGuideResolution = 8;
constexpr int kGuideCells = kGuideResolution * kGuideResolution;

// Cell weights quantised to bytes (the largest is 255); all zero: no guidance.
struct GuideHistogram {
  uint8_t cells[kGuideCells] = {};
};

// Bins the indirect photons among `neighbors` by incoming direction in `frame`, by luminance.
GuideHistogram build_guide(const PhotonMap& map, const std::vector<PhotonNeighbor>& neighbors,
                           const Frame& frame);

// The mixture 1/2 cosine + 1/2 histogram as a piecewise-constant density on the unit square.
class GuidedSquare {
 public:
  explicit GuidedSquare(const GuideHistogram& histogram);
  // Warps a uniform (stratified) point; `density` is the square density at the result
  // (1 everywhere for pure cosine sampling), so the direction pdf is density * cos / pi.
  Vec2 sample(Vec2 u, float* density) const;

 private:
  float cell_[kGuideCells];  // probability of each cell, [column][row]
  float column_cdf_[kGuideResolution + 1];
};

}  // namespace photon
