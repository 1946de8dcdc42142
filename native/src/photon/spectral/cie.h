// CIE 1931 2-degree standard observer: the colour matching functions x, y, z tabulated every
// 1 nm over 360..830 nm, and integrals of spectra against them.
#pragma once

#include "photon/base/math.h"

namespace photon::spectral {

constexpr float kLambdaMin = 360.0f;
constexpr float kLambdaMax = 830.0f;
// Samples of every 1 nm table in this folder: 360, 361, ..., 830 nm.
constexpr int kTableSamples = 471;

// The tables themselves (kTableSamples values each, index i is 360 + i nm).
const float* cie_x_table();
const float* cie_y_table();
const float* cie_z_table();

// x, y, z at `lambda` nm, linearly interpolated between the 1 nm samples, 0 outside 360..830.
Vec3 cie_xyz(float lambda);

// Sum of y over the 1 nm table (the integral of y in nm): the luminance of an equal-energy
// spectrum of value 1. XYZ of an emission spectrum S is sum(S * xyz) / cie_y_integral().
float cie_y_integral();

}  // namespace photon::spectral
