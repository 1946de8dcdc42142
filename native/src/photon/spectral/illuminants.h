// Emission spectra: Planck's blackbody law and the CIE standard illuminants.
#pragma once

#include "photon/base/math.h"
#include "photon/spectral/colorimetry.h"

namespace photon::spectral {

// Planck's law: spectral radiance of a blackbody at `kelvin`, at `lambda` nm, in
// W / (m^2 sr m). 0 for a non-positive or non-finite temperature.
float blackbody(float lambda, float kelvin);
// The same divided by its value at the peak wavelength (Wien: 2.897771955e-3 m K / T), so the
// largest value over all wavelengths is 1.
float blackbody_normalized(float lambda, float kelvin);
// Linear Rec.709 colour of the normalised blackbody at `kelvin`, scaled to luminance 1 (the
// chromaticity Blender's Blackbody node gives, without its brightness).
Vec3 blackbody_rec709_chroma(float kelvin);

enum class Illuminant {
  kD65,  // CIE standard illuminant D65 (daylight, 6504 K)
  kA,    // CIE standard illuminant A (incandescent): Planck at 2856 K
  kF2,   // CIE F2 cool white fluorescent
  kF7,   // CIE F7 broadband daylight fluorescent
  kF11,  // CIE F11 narrow tri-band fluorescent
};

// The illuminant on the 1 nm table, scaled to luminance 1 (emission_to_xyz(s).y == 1).
const TabulatedSpectrum& illuminant_spectrum(Illuminant which);

}  // namespace photon::spectral
