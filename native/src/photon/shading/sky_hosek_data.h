// Hosek-Wilkie sky model coefficient tables (CIE XYZ); see sky_hosek_data.cpp.
#pragma once

namespace photon::hosek {

constexpr int kDatasetSize = 2 * 10 * 6 * 9;  // albedo x turbidity x control point x parameter
constexpr int kRadianceSize = 2 * 10 * 6;     // albedo x turbidity x control point
extern const double kDatasetX[kDatasetSize], kDatasetY[kDatasetSize], kDatasetZ[kDatasetSize];
extern const double kRadianceX[kRadianceSize], kRadianceY[kRadianceSize], kRadianceZ[kRadianceSize];

}  // namespace photon::hosek
