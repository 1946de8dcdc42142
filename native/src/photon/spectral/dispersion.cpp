#include "photon/spectral/dispersion.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace photon::spectral {

float physical_abbe(float abbe) {
  if (!(abbe > 0.0f) || !std::isfinite(abbe)) return 0.0f;
  return std::clamp(abbe, kMinAbbe, kMaxAbbe);
}

CauchyDispersion CauchyDispersion::from_abbe(float n_d, float abbe) {
  CauchyDispersion d;
  if (!std::isfinite(n_d)) return d;
  d.a = n_d;
  abbe = physical_abbe(abbe);
  if (abbe == 0.0f) return d;
  // n_F - n_C = B (1/F^2 - 1/C^2) = (n_d - 1) / V, then A from n(d) = n_d.
  const double f = kLambdaF, c = kLambdaC, dl = kLambdaD;
  d.b = (static_cast<double>(n_d) - 1.0) / (abbe * (1.0 / (f * f) - 1.0 / (c * c)));
  d.a = n_d - d.b / (dl * dl);
  return d;
}

double prism_deviation(double n, double apex, double incidence) {
  const double r1 = std::asin(std::sin(incidence) / n);
  const double s2 = n * std::sin(apex - r1);
  if (std::fabs(s2) > 1.0) return std::numeric_limits<double>::quiet_NaN();
  return incidence + std::asin(s2) - apex;
}

double prism_min_deviation(double n, double apex) {
  const double s = n * std::sin(0.5 * apex);
  if (std::fabs(s) > 1.0) return std::numeric_limits<double>::quiet_NaN();
  return 2.0 * std::asin(s) - apex;
}

}  // namespace photon::spectral
