#include "photon/integrators/photon_map/gather_guide.h"

#include <algorithm>

#include "photon/base/sampling.h"

namespace photon {

GuideHistogram build_guide(const PhotonMap& map, const std::vector<PhotonNeighbor>& neighbors,
                           const Frame& frame) {
  float weights[kGuideCells] = {};
  float largest = 0.0f;
  for (const PhotonNeighbor& nb : neighbors) {
    const Photon& ph = map[nb.index];
    if (!(ph.flags & kPhotonIndirect)) continue;  // final gathering collects only these
    const Vec3 incoming = frame.to_local(-ph.direction());
    if (incoming.z <= 0.0f) continue;
    const Vec2 u = invert_concentric_disk(Vec2(incoming.x, incoming.y));
    const int cx = std::min(static_cast<int>(u.x * kGuideResolution), kGuideResolution - 1);
    const int cy = std::min(static_cast<int>(u.y * kGuideResolution), kGuideResolution - 1);
    float& w = weights[cx * kGuideResolution + cy];
    w += luminance(map.power(ph));
    largest = std::max(largest, w);
  }
  GuideHistogram h;
  if (largest > 0.0f)
    for (int i = 0; i < kGuideCells; ++i)
      h.cells[i] = static_cast<uint8_t>(std::min(255.0f, std::ceil(weights[i] * 255.0f / largest)));
  return h;
}

GuidedSquare::GuidedSquare(const GuideHistogram& histogram) {
  float total = 0.0f;
  for (uint8_t c : histogram.cells) total += c;
  for (int i = 0; i < kGuideCells; ++i) {
    const float guided = total > 0.0f ? histogram.cells[i] / total : 1.0f / kGuideCells;
    cell_[i] = 0.5f / kGuideCells + 0.5f * guided;
  }
  column_cdf_[0] = 0.0f;
  for (int x = 0; x < kGuideResolution; ++x) {
    float column = 0.0f;
    for (int y = 0; y < kGuideResolution; ++y) column += cell_[x * kGuideResolution + y];
    column_cdf_[x + 1] = column_cdf_[x] + column;
  }
}

Vec2 GuidedSquare::sample(Vec2 u, float* density) const {
  // Column by the marginal, then row by the conditional; each remapped continuously, so a
  // stratified input stays stratified.
  const float total = column_cdf_[kGuideResolution];
  const float tx = u.x * total;
  int x = 0;
  while (x < kGuideResolution - 1 && tx >= column_cdf_[x + 1]) ++x;
  const float column = column_cdf_[x + 1] - column_cdf_[x];
  const float fx = std::clamp((tx - column_cdf_[x]) / column, 0.0f, 0.99999994f);
  const float ty = u.y * column;
  int y = 0;
  float below = 0.0f;
  while (y < kGuideResolution - 1 && ty >= below + cell_[x * kGuideResolution + y])
    below += cell_[x * kGuideResolution + y++];
  const float cell = cell_[x * kGuideResolution + y];
  const float fy = std::clamp((ty - below) / cell, 0.0f, 0.99999994f);
  *density = cell * kGuideCells / total;
  return {(x + fx) / kGuideResolution, (y + fy) / kGuideResolution};
}

}  // namespace photon
