// The optimiser behind RGB -> spectrum uplifting (Jakob & Hanika 2019, "A Low-Dimensional
// Function Space for Efficient Spectral Upsampling", Eurographics): for a target linear
// Rec.709 reflectance colour, the coefficients c of the spectrum
//   s(lambda) = S(c0 t^2 + c1 t + c2),  S(x) = 1/2 + x / (2 sqrt(1 + x^2)),
//   t = (lambda - 360 nm) / 470 nm,
// whose colour under D65 is closest to the target in CIELAB (Sec. 4: Gauss-Newton on the
// CIE76 difference), and the table of such coefficients over the RGB cube (Sec. 5). Used by
// the build-time generator (native/tools/uplift_table_gen.cpp) and by the tests.
#pragma once

#include <cstdint>
#include <vector>

#include "photon/base/math.h"

namespace photon::spectral {

// Spectrum colour (under D65) and its derivatives with respect to c, on the 1 nm table.
class UpliftFitter {
 public:
  UpliftFitter();

  // Refines `coeffs` (the starting point on entry) towards the spectrum of colour `rgb`;
  // returns the final CIE76 distance (Delta E*ab) to the target.
  double fit(const Vec3& rgb, double coeffs[3]) const;

  // Linear Rec.709 colour under D65 of the spectrum with `coeffs`, in double precision.
  void rgb_of(const double coeffs[3], double rgb[3]) const;

 private:
  void xyz_and_jacobian(const double c[3], double xyz[3], double jac[3][3]) const;
  void lab_of(const double xyz[3], double lab[3], double dlab[3][3]) const;

  std::vector<double> t_;     // normalised wavelength per 1 nm sample
  std::vector<double> w_[3];  // D65(lambda) * {x,y,z}(lambda) / sum(D65 y)
  double white_[3];           // XYZ of the perfect reflector under D65
  double xyz_to_rgb_[3][3];
  double rgb_to_xyz_[3][3];
};

// The table layout of RgbToSpectrumTable: z_nodes[res], then coeffs[3][res][res][res][3]
// (sheet = index of the largest component, z index, y index, x index, coefficient).
struct UpliftTableData {
  int32_t resolution = 0;
  std::vector<float> z_nodes;
  std::vector<float> coeffs;
};

// The darkest fitted brightness. Below it a sigmoid cannot reach dark saturated colours (its
// value far from the transition decays only as 1 / (4 x^2)): the fits there miss by up to
// 1e-2 in RGB. Colours darker than this blend the node at this brightness with black (node 0,
// the zero spectrum), i.e. they are that node's spectrum scaled down, which is exact.
constexpr double kUpliftDarkestFit = 0.1;

// z of node k: 0 for k = 0, then kUpliftDarkestFit + (1 - kUpliftDarkestFit) *
// smoothstep((k - 1) / (res - 2)), dense near 1 where the coefficients change fastest (near
// white) -- the paper (Sec. 5) uses smoothstep(smoothstep(k / (res - 1))) from 0.
float uplift_z_node(int k, int resolution);

// Fits every node of the table (the cells of one (sheet, x, y) column warm-started from their
// neighbour in z, as the paper does). Deterministic whatever `threads`.
UpliftTableData build_uplift_table(int resolution, int threads);

// Binary file: "PHUPLFT1", int32 resolution, z_nodes, coeffs (little-endian floats).
bool write_uplift_table(const UpliftTableData& table, const char* path);

}  // namespace photon::spectral
