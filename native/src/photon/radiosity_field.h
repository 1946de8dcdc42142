// The radiosity solution as a function on the surfaces: per-element radiosity B = P / A (seed
// 002 sec. 1.2: B_i constant on patch i), and a continuous version for display, with B at every
// welded vertex the area-weighted average of the elements around it, interpolated linearly
// across each element (Gouraud shading of radiosity; Cohen & Wallace 1993, the chapter on
// rendering), so patch edges do not show.
#pragma once

#include <vector>

#include "photon/radiosity_mesh.h"
#include "photon/radiosity_solver.h"

namespace photon {

class RadiosityField {
 public:
  RadiosityField() = default;
  // `side_power`: 2 per element (front, back), as solve_radiosity returns it.
  RadiosityField(const RadiosityMesh& mesh, const std::vector<RadiosityPower>& side_power);

  bool empty() const { return element_.empty(); }
  // Radiosity (W/m^2 per channel, by light path) of one side of element e: 0 front, 1 back.
  const RadiosityPower& element_radiosity(uint32_t e, uint32_t side) const {
    return element_[2 * e + side];
  }
  // Gouraud-interpolated radiosity at a located point, on side `side` of its element.
  RadiosityPower radiosity_at(const RadiosityLocation& where, uint32_t side) const;

 private:
  std::vector<RadiosityPower> element_;  // 2 per element
  std::vector<RadiosityPower> vertex_;   // 2 per welded vertex
};

}  // namespace photon
