// Wavelength-dependent index of refraction from the two numbers a material gives: the index
// n_d at the helium d line and the Abbe number V (glass catalogues; Blender's IOR is taken as
// n_d). Cauchy's law n(lambda) = A + B / lambda^2 (Cauchy 1836; e.g. Born & Wolf, Principles of
// Optics, Sec. 2.3.4) fitted so that n(587.6) = n_d and (n_d - 1) / (n(486.1) - n(656.3)) = V.
#pragma once

namespace photon::spectral {

constexpr float kLambdaD = 587.56f;  // helium d line, nm
constexpr float kLambdaF = 486.13f;  // hydrogen F line, nm
constexpr float kLambdaC = 656.27f;  // hydrogen C line, nm

// The Abbe numbers of real transparent materials: rutile (TiO2, V about 9.8) disperses most of
// those used in optics and jewellery, fluorite (CaF2, about 95) among the least; Blender's
// slider stops at 200. Below about 0.76 Cauchy's law turns n(830 nm) - 1 against n_d - 1 (a glass
// whose red index is below 1), and near 0 it gives indices of hundreds: such numbers are
// clamped into this range (and the add-on says so).
constexpr float kMinAbbe = 9.0f;
constexpr float kMaxAbbe = 200.0f;

// V inside [kMinAbbe, kMaxAbbe]; 0 (no dispersion) for V <= 0 or not finite.
float physical_abbe(float abbe);

struct CauchyDispersion {
  double a = 1.0;  // A
  double b = 0.0;  // B, nm^2

  // V <= 0 or not finite (or n_d not finite) means no dispersion: n(lambda) = n_d. Other V
  // are taken through physical_abbe.
  static CauchyDispersion from_abbe(float n_d, float abbe);
  float ior(float lambda) const { return static_cast<float>(a + b / (double(lambda) * lambda)); }
};

// Deviation (radians) of a ray through a prism of apex angle `apex` and index `n`, entering at
// `incidence` (radians from the first face's normal): Snell's law at both faces,
// delta = incidence + exit - apex. NaN when the ray is totally reflected at the second face.
double prism_deviation(double n, double apex, double incidence);
// The minimum deviation 2 asin(n sin(apex / 2)) - apex, reached at the symmetric passage.
double prism_min_deviation(double n, double apex);

}  // namespace photon::spectral
