// The radiosity solution as a function on the surfaces: per-patch radiosity B = P / A (Cohen &
// Wallace 1993: B_i constant on patch i), and a continuous version for display, with B at every
// welded vertex the area-weighted average of the elements around it, interpolated linearly
// across each element (Gouraud shading of radiosity; Cohen & Wallace 1993, the chapter on
// rendering), so patch edges do not show. Vertices on clustered patches (many small triangles
// per patch) would show the clusters' voxel outlines that way, so there B is instead a kernel
// estimate from the patches nearby (tent kernel over patch centroids, weighted by area and by
// normal agreement): the clustering's piecewise constant B is reconstructed smoothly, in the
// spirit of the density estimation view of radiosity display (Shirley et al. 1995).
#pragma once

#include <vector>

#include "photon/integrators/radiosity/radiosity_mesh.h"
#include "photon/integrators/radiosity/radiosity_solver.h"

namespace photon {

class RadiosityField {
 public:
  RadiosityField() = default;
  // `side_power`: 2 per patch (front, back), as solve_radiosity returns it.
  RadiosityField(const RadiosityMesh& mesh, const std::vector<RadiosityPower>& side_power);

  bool empty() const { return patch_.empty(); }
  // Radiosity (W/m^2 per channel, by light path) of one side of element e (its patch's): 0
  // front, 1 back.
  const RadiosityPower& element_radiosity(uint32_t e, uint32_t side) const {
    return patch_[2 * element_patch_[e] + side];
  }
  const RadiosityPower& patch_radiosity(uint32_t p, uint32_t side) const {
    return patch_[2 * p + side];
  }
  // Gouraud-interpolated radiosity at a located point, on side `side` of its element.
  RadiosityPower radiosity_at(const RadiosityLocation& where, uint32_t side) const;

 private:
  std::vector<RadiosityPower> patch_;  // 2 per patch
  std::vector<uint32_t> element_patch_;
  std::vector<RadiosityPower> vertex_;  // 2 per welded vertex
};

}  // namespace photon
