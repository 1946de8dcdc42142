#include "photon/spectral/rgb_uplift.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include "photon/spectral/illuminants.h"

// The table embedded by the generated source (native/tools/uplift_table_gen.cpp).
extern "C" const unsigned char photon_uplift_table_data[];
extern "C" const unsigned char photon_uplift_table_end[];

namespace photon::spectral {
namespace {

float clamp01(float v) {
  return v > 0.0f ? std::min(v, 1.0f) : 0.0f;
}  // NaN -> 0

const RgbToSpectrumTable& load_embedded() {
  static const RgbToSpectrumTable table = [] {
    const unsigned char* p = photon_uplift_table_data;
    const size_t size = static_cast<size_t>(photon_uplift_table_end - photon_uplift_table_data);
    int32_t res = 0;
    if (size < 12 || std::memcmp(p, "PHUPLFT1", 8) != 0)
      throw std::runtime_error("Photon: the embedded RGB->spectrum table is corrupt");
    std::memcpy(&res, p + 8, sizeof(res));
    const size_t floats = static_cast<size_t>(res) + 9 * static_cast<size_t>(res) * res * res;
    if (res < 2 || size != 12 + floats * sizeof(float))
      throw std::runtime_error("Photon: the embedded RGB->spectrum table has the wrong size");
    // 12-byte header after a 16-aligned start: the floats are 4-aligned.
    const float* f = reinterpret_cast<const float*>(p + 12);
    return RgbToSpectrumTable(res, f, f + res);
  }();
  return table;
}

}  // namespace

float SigmoidPolynomial::max_value() const {
  float m = std::max((*this)(kLambdaMin), (*this)(kLambdaMax));
  if (c0 != 0.0f) {
    const float t = -c1 / (2.0f * c0);
    if (t >= 0.0f && t <= 1.0f)
      m = std::max(m, (*this)(kLambdaMin + t * (kLambdaMax - kLambdaMin)));
  }
  return m;
}

const RgbToSpectrumTable& RgbToSpectrumTable::rec709() {
  return load_embedded();
}

bool RgbToSpectrumTable::locate(const Vec3& in, Cell* cell, SigmoidPolynomial* grey) const {
  const float rgb[3] = {clamp01(in.x), clamp01(in.y), clamp01(in.z)};
  if (rgb[0] == rgb[1] && rgb[1] == rgb[2]) {
    // S(c2) = v for c2 = (v - 1/2) / sqrt(v (1 - v)); v = 1 gives +inf, v = 0 gives -inf.
    const float v = rgb[0];
    *grey = SigmoidPolynomial();
    grey->c2 =
        v >= 1.0f ? INFINITY : (v <= 0.0f ? -INFINITY : (v - 0.5f) / std::sqrt(v * (1.0f - v)));
    return false;
  }
  const int sheet = rgb[0] > rgb[1] ? (rgb[0] > rgb[2] ? 0 : 2) : (rgb[1] > rgb[2] ? 1 : 2);
  const int res = resolution_;
  const float z = rgb[sheet];
  const float x = rgb[(sheet + 1) % 3] * static_cast<float>(res - 1) / z;
  const float y = rgb[(sheet + 2) % 3] * static_cast<float>(res - 1) / z;
  cell->sheet = sheet;
  cell->xi = std::min(static_cast<int>(x), res - 2);
  cell->yi = std::min(static_cast<int>(y), res - 2);
  const int zi = static_cast<int>(std::upper_bound(z_nodes_, z_nodes_ + res, z) - z_nodes_) - 1;
  cell->zi = std::clamp(zi, 0, res - 2);
  cell->dx = x - static_cast<float>(cell->xi);
  cell->dy = y - static_cast<float>(cell->yi);
  cell->dz = (z - z_nodes_[cell->zi]) / (z_nodes_[cell->zi + 1] - z_nodes_[cell->zi]);
  return true;
}

SigmoidPolynomial RgbToSpectrumTable::node(int sheet, int zi, int yi, int xi) const {
  const size_t res = static_cast<size_t>(resolution_);
  const float* c = coeffs_ + (((sheet * res + zi) * res + yi) * res + xi) * 3;
  return {c[0], c[1], c[2]};
}

BlendedSigmoids RgbToSpectrumTable::operator()(const Vec3& rgb) const {
  BlendedSigmoids b;
  Cell cell;
  SigmoidPolynomial grey;
  if (!locate(rgb, &cell, &grey)) {
    b.term[0] = grey;
    b.weight[0] = 1.0f;
    b.count = 1;
    return b;
  }
  for (int k = 0; k < 8; ++k) {
    const int ox = k & 1, oy = (k >> 1) & 1, oz = k >> 2;
    const float w = (ox ? cell.dx : 1.0f - cell.dx) * (oy ? cell.dy : 1.0f - cell.dy) *
                    (oz ? cell.dz : 1.0f - cell.dz);
    // Zero weight (on a face or node), or the black layer (the zero spectrum): no term.
    if (w == 0.0f || (cell.zi == 0 && oz == 0)) continue;
    b.term[b.count] = node(cell.sheet, cell.zi + oz, cell.yi + oy, cell.xi + ox);
    b.weight[b.count] = w;
    ++b.count;
  }
  return b;
}

SampledSpectrum BlendedSigmoids::sample(const SampledWavelengths& wl) const {
  // The grey axis: one constant term whose c2 may be infinite.
  if (count == 1 && term[0].c0 == 0.0f && term[0].c1 == 0.0f)
    return SampledSpectrum(weight[0] * SigmoidPolynomial::sigmoid(term[0].c2));
  float t[kSpectrumSamples], v[kSpectrumSamples] = {};
  for (int i = 0; i < kSpectrumSamples; ++i) {
    const float lambda = wl.lambda(i);
    t[i] = (lambda - kLambdaMin) * (1.0f / (kLambdaMax - kLambdaMin));
  }
  // Table terms are finite (|c| <= the fitter's cap), so no infinity test in the loop.
  for (int k = 0; k < count; ++k) {
    const SigmoidPolynomial& p = term[k];
    for (int i = 0; i < kSpectrumSamples; ++i) {
      const float x = (p.c0 * t[i] + p.c1) * t[i] + p.c2;
      v[i] += weight[k] * (0.5f + 0.5f * x / std::sqrt(1.0f + x * x));
    }
  }
  SampledSpectrum s;
  for (int i = 0; i < kSpectrumSamples; ++i) s[i] = std::isnan(t[i]) ? 0.0f : v[i];
  return s;
}

SampledSpectrum RgbAlbedoSpectrum::sample(const SampledWavelengths& wl) const {
  return blend_.sample(wl);
}

RgbUnboundedSpectrum::RgbUnboundedSpectrum(const RgbToSpectrumTable& table, const Vec3& rgb) {
  const Vec3 c(std::isfinite(rgb.x) ? std::max(rgb.x, 0.0f) : 0.0f,
               std::isfinite(rgb.y) ? std::max(rgb.y, 0.0f) : 0.0f,
               std::isfinite(rgb.z) ? std::max(rgb.z, 0.0f) : 0.0f);
  const float m = max_component(c);
  scale_ = 2.0f * m;
  blend_ = table(scale_ > 0.0f ? c / scale_ : Vec3(0.0f));
}

SampledSpectrum RgbUnboundedSpectrum::sample(const SampledWavelengths& wl) const {
  return blend_.sample(wl) * scale_;
}

RgbIlluminantSpectrum::RgbIlluminantSpectrum(const RgbToSpectrumTable& table, const Vec3& rgb)
    : unbounded_(table, rgb), illuminant_(&illuminant_spectrum(Illuminant::kD65)) {}

float RgbIlluminantSpectrum::operator()(float lambda) const {
  return unbounded_(lambda) * (*illuminant_)(lambda);
}

SampledSpectrum RgbIlluminantSpectrum::sample(const SampledWavelengths& wl) const {
  return unbounded_.sample(wl) * illuminant_->sample(wl);
}

ReflectanceSpectrum::ReflectanceSpectrum(const Vec3& rgb) {
  if (rgb.x == rgb.y && rgb.y == rgb.z) {
    scale_ = std::isfinite(rgb.x) ? std::max(rgb.x, 0.0f) : 0.0f;
    return;
  }
  grey_ = false;
  const RgbToSpectrumTable& table = RgbToSpectrumTable::rec709();
  const Vec3 c(std::isfinite(rgb.x) ? std::max(rgb.x, 0.0f) : 0.0f,
               std::isfinite(rgb.y) ? std::max(rgb.y, 0.0f) : 0.0f,
               std::isfinite(rgb.z) ? std::max(rgb.z, 0.0f) : 0.0f);
  const float m = max_component(c);
  if (m <= 1.0f) {
    blend_ = table(c);  // RgbAlbedoSpectrum
    scale_ = 1.0f;
  } else {
    scale_ = 2.0f * m;  // RgbUnboundedSpectrum
    blend_ = table(c / scale_);
  }
}

SampledSpectrum illuminant_at(const Vec3& rgb, const SampledWavelengths& wl) {
  if (rgb.x == rgb.y && rgb.y == rgb.z) {
    const float c = std::isfinite(rgb.x) ? std::max(rgb.x, 0.0f) : 0.0f;
    if (c == 0.0f) return SampledSpectrum(0.0f);
    return illuminant_spectrum(Illuminant::kD65).sample(wl) * c;
  }
  return RgbIlluminantSpectrum(RgbToSpectrumTable::rec709(), rgb).sample(wl);
}

}  // namespace photon::spectral
