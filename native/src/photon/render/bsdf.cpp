#include "photon/render/bsdf.h"

#include <array>

#include "photon/render/bsdf_lobes.h"
#include "photon/render/bsdf_mixture.h"

namespace photon {

using namespace bsdf_lobes;
Vec3 lobe_reflection_fresnel(const Lobe& lobe, float cos_oh, float eta) {
  return reflection_fresnel(lobe, lobe.f0, cos_oh, eta, lobe.tint);
}

bool Lobe::dispersive() const {
  if (!(abbe > 0.0f)) return false;
  switch (type) {
    case LobeType::kGgxGlass:
    case LobeType::kGgxRefraction:
    case LobeType::kGgxDielectric:
      return true;
    case LobeType::kGgxReflection:
      return fresnel == FresnelMode::kDielectric || fresnel == FresnelMode::kInterpolated;
    default:
      return false;
  }
}

uint8_t Lobe::flags() const {
  const uint8_t rough = is_delta(*this) ? kLobeSpecular : kLobeGlossy;
  switch (type) {
    case LobeType::kLambert:
    case LobeType::kBurleyDiffuse:
    case LobeType::kOrenNayar:
      return kLobeReflection | kLobeDiffuse;
    case LobeType::kSheen:
    case LobeType::kVelvet:
      // Not Lambertian: its weight is no hemispherical reflectance, so the photon map's
      // irradiance estimate must not stand in for it; it is sampled and ray traced.
      return kLobeReflection | kLobeGlossy;
    case LobeType::kTranslucent:
      return kLobeTransmission | kLobeGlossy;
    case LobeType::kGgxReflection:
      return kLobeReflection | rough;
    case LobeType::kGgxGlass:
    case LobeType::kGgxDielectric:
      return kLobeReflection | kLobeTransmission | rough;
    case LobeType::kGgxRefraction:
      return kLobeTransmission | rough;
    case LobeType::kTransparent:
      return kLobeTransmission | kLobeSpecular;
  }
  return 0;
}

Bsdf::Bsdf(const Vec3& ns, const Vec3& ng, bool front_facing) : front_facing_(front_facing) {
  const bool ns_ok = is_unit_direction(ns), ng_ok = is_unit_direction(ng);
  valid_ = ns_ok || ng_ok;
  const Vec3 n = normalize(ns_ok ? ns : (ng_ok ? ng : Vec3(0.0f, 0.0f, 1.0f)));
  ng_ = ng_ok ? normalize(ng) : n;
  frame_ = Frame(n);
}

void Bsdf::set_smooth_normal(const Vec3& n) {
  if (!is_unit_direction(n)) return;
  smooth_n_ = normalize(n);
  has_smooth_ = true;
  const Vec3 d = smooth_n_ - frame_.n;
  bumped_ = length_squared(d) > 0.0f;
}

void Bsdf::add(const Lobe& lobe) {
  if (!valid_) return;
  Lobe l = lobe;
  // Sanitise parameters so no NaN can reach the renderer: negative or NaN colours are black,
  // roughness is clamped to its range and a NaN or non-positive ior falls back to the default.
  for (int c = 0; c < 3; ++c) {
    const float w = l.weight[c];
    l.weight[c] = std::isfinite(w) ? std::max(w, 0.0f) : 0.0f;
    const float f = l.f0[c];
    l.f0[c] = std::isfinite(f) ? std::clamp(f, 0.0f, 1.0f) : 0.0f;
    const float t = l.tint[c];
    l.tint[c] = std::isfinite(t) ? std::clamp(t, 0.0f, 1.0f) : 0.0f;
  }
  if (is_black(l.weight)) return;
  // GGX alphas within [0, 1], as Cycles 3.4's microfacet setup saturates both (an anisotropic
  // lobe's long axis, r^2 / aspect, is cut at 1 there too).
  l.alpha = std::isfinite(l.alpha) ? std::clamp(l.alpha, 0.0f, 1.0f) : 0.0f;
  if (l.anisotropic())
    l.alpha_y = std::isfinite(l.alpha_y) ? std::clamp(l.alpha_y, 0.0f, 1.0f) : l.alpha;
  l.roughness = std::isfinite(l.roughness) ? std::clamp(l.roughness, 0.0f, 1.0f) : 0.0f;
  if (!(l.ior > 0.0f) || !std::isfinite(l.ior)) l.ior = 1.45f;
  l.ior = std::clamp(l.ior, 1e-3f, 1e3f);
  l.abbe = std::isfinite(l.abbe) && l.abbe > 0.0f ? l.abbe : 0.0f;
  // The lobe's own frame: its normal (when above the geometric surface) and tangent.
  Frame own = frame_;
  bool has_own = false;
  if (is_unit_direction(l.normal) && is_finite(l.normal)) {
    const Vec3 n = normalize(l.normal);
    if (dot(n, ng_) > 1e-3f && dot(n, frame_.n) < 1.0f) {
      own = Frame(n);
      has_own = true;
    }
  }
  if (l.anisotropic() && is_finite(l.tangent)) {
    const Vec3 t = l.tangent - own.n * dot(own.n, l.tangent);
    if (length_squared(t) > 1e-12f) {
      own.t = normalize(t);
      own.b = cross(own.n, own.t);
      has_own = true;
    }
  }
  l.normal = Vec3(0.0f);
  l.tangent = Vec3(0.0f);
  if (count_ < kMaxLobes) {
    lobe_frames_[count_] = own;
    own_frame_[count_] = has_own;
    lobes_[count_++] = l;
    return;
  }
  // Full: keep the kMaxLobes heaviest lobes (by their largest weight channel), so a material
  // of many closures loses its faintest ones rather than whichever came last.
  int lightest = 0;
  for (int i = 1; i < count_; ++i)
    if (max_component(lobes_[i].weight) < max_component(lobes_[lightest].weight)) lightest = i;
  if (max_component(l.weight) > max_component(lobes_[lightest].weight)) {
    lobes_[lightest] = l;
    lobe_frames_[lightest] = own;
    own_frame_[lightest] = has_own;
  }
}

uint8_t Bsdf::flags() const {
  uint8_t f = 0;
  for (int i = 0; i < count_; ++i) f |= lobes_[i].flags();
  return f;
}

bool Bsdf::to_local(const Vec3& wo, Vec3* wo_local, Vec3* wo_world) const {
  if (count_ == 0 || !is_unit_direction(wo)) return false;
  *wo_world = unit(wo);
  *wo_local = frame_.to_local(*wo_world);
  // wo must be above both the shading and the geometric surface (grazing counts as below).
  return wo_local->z > 1e-7f && dot(*wo_world, ng_) != 0.0f;
}

bool Bsdf::lobe_local(int i, const Vec3& wo_world, const Vec3& wo, const Vec3& wi_world,
                      const Vec3& wi, Vec3* lwo, Vec3* lwi) const {
  if (!own_frame_[i]) {
    *lwo = wo;
    *lwi = wi;
    return true;
  }
  *lwo = lobe_frames_[i].to_local(wo_world);
  *lwi = lobe_frames_[i].to_local(wi_world);
  return lwo->z > 1e-7f;
}

float Bsdf::eta(const Lobe& l) const {
  return front_facing_ || l.fixed_ior ? l.ior : 1.0f / l.ior;
}

int Bsdf::refracting_lobe(const Vec3& wo, const Vec3& wi) const {
  if (!(dot(wo, ng_) * dot(wi, ng_) < 0.0f)) return -1;
  int found = -1;
  for (int i = 0; i < count_; ++i) {
    const Lobe& l = lobes_[i];
    switch (l.type) {
      case LobeType::kGgxGlass:
      case LobeType::kGgxRefraction:
      case LobeType::kGgxDielectric:
        if (found >= 0 && (lobes_[found].ior != l.ior || lobes_[found].abbe != l.abbe)) return -1;
        if (found < 0) found = i;
        break;
      case LobeType::kTranslucent:
        return -1;
      default:
        break;
    }
  }
  return found;
}

float Bsdf::adjoint_scale(const Vec3& wo, const Vec3& wi) const {
  const int i = refracting_lobe(wo, wi);
  if (i < 0) return 1.0f;
  const float e = eta(lobes_[i]);
  return e > 0.0f && std::isfinite(e) ? 1.0f / (e * e) : 1.0f;
}

int Bsdf::selection_probabilities(const Vec3& wo_local, uint8_t mask, float* probs) const {
  float total = 0.0f;
  int selected = 0;
  for (int i = 0; i < count_; ++i) {
    probs[i] = 0.0f;
    if (!(lobes_[i].flags() & mask)) continue;
    Vec3 lwo = wo_local;
    if (own_frame_[i]) {
      lwo = lobe_frames_[i].to_local(frame_.to_world(wo_local));
      if (!(lwo.z > 1e-7f)) continue;  // wo below the lobe's own normal: it cannot scatter
    }
    probs[i] = std::max(0.0f, max_component(lobe_albedo(lobes_[i], lwo, eta(lobes_[i]))));
    total += probs[i];
  }
  if (!(total > 0.0f) || !std::isfinite(total)) return 0;
  for (int i = 0; i < count_; ++i) {
    probs[i] /= total;
    if (probs[i] > 0.0f) ++selected;
  }
  return selected;
}

namespace {

// The lobes' own RGB colours (bsdf_mixture.h's colour model).
struct RgbColours {
  using Color = Vec3;
  using Sample = BsdfSample;
  static constexpr bool kSpectral = false;
  const Lobe* lobes;
  const Vec3& weight(int i) const { return lobes[i].weight; }
  const Vec3& f0(int i) const { return lobes[i].f0; }
  const Vec3& tint(int i) const { return lobes[i].tint; }
  bool dispersive(int) const { return false; }
};

}  // namespace

Vec3 Bsdf::eval(const Vec3& wo, const Vec3& wi, uint8_t mask) const {
  return BsdfMixture::eval(*this, RgbColours{lobes_}, wo, wi, mask);
}

float Bsdf::pdf(const Vec3& wo, const Vec3& wi, uint8_t mask) const {
  return BsdfMixture::pdf(*this, RgbColours{lobes_}, wo, wi, mask);
}

float Bsdf::pdf_reverse(const Vec3& wo, const Vec3& wi, uint8_t mask) const {
  if (dot(wi, ng_) >= 0.0f) return pdf(wi, wo, mask);
  return seen_from_behind().pdf(wi, wo, mask);
}

Bsdf Bsdf::seen_from_behind() const {
  Bsdf b(-frame_.n, -ng_, !front_facing_);
  b.valid_ = valid_;
  if (has_smooth_) b.set_smooth_normal(-smooth_n_);
  for (int i = 0; i < count_; ++i) {
    Lobe l = lobes_[i];
    if (own_frame_[i]) {
      l.normal = -lobe_frames_[i].n;
      l.tangent = lobe_frames_[i].t;
    }
    b.add(l);
  }
  return b;
}

bool Bsdf::sample(const Vec3& wo, float u_lobe, Vec2 u, uint8_t mask, BsdfSample* out) const {
  return BsdfMixture::sample(*this, RgbColours{lobes_}, wo, u_lobe, u, mask, out);
}

Vec3 Bsdf::diffuse_reflectance() const {
  Vec3 r(0.0f);
  for (int i = 0; i < count_; ++i)
    if (lobes_[i].flags() & kLobeDiffuse) r += lobes_[i].weight;
  return r;
}

Vec3 Bsdf::diffuse_reflectance(const Vec3& wo) const {
  return BsdfMixture::diffuse_reflectance(*this, RgbColours{lobes_}, wo);
}

bool Bsdf::bump_shadowed(int i) const {
  return is_diffuse_type(lobes_[i]) &&
         (own_frame_[i] ? has_smooth_ && length_squared(smooth_n_ - lobe_frames_[i].n) > 0.0f
                        : bumped_);
}

float Bsdf::shadowing_mean(int i) const {
  return bump_shadowed(i) ? bump_shadowing_mean(dot(smooth_n_, lobe_normal(i))) : 1.0f;
}

float bsdf_lobes::bump_shadowing_mean(float cos_smooth_bumped) {
  // Midpoint quadrature over cosine-distributed wi about the bumped normal, per table entry.
  constexpr int kEntries = 65, kGrid = 48;
  static const std::array<float, kEntries> table = [] {
    std::array<float, kEntries> t{};
    for (int e = 0; e < kEntries; ++e) {
      const float c = static_cast<float>(e) / (kEntries - 1);
      const Vec3 smooth(std::sqrt(std::max(0.0f, 1.0f - c * c)), 0.0f, c);
      double sum = 0.0;
      for (int a = 0; a < kGrid; ++a)
        for (int b = 0; b < kGrid; ++b) {
          const Vec3 wi = sample_cosine_hemisphere(Vec2((a + 0.5f) / kGrid, (b + 0.5f) / kGrid));
          sum += bump_shadowing(smooth, Vec3(0.0f, 0.0f, 1.0f), wi);
        }
      t[e] = static_cast<float>(sum / (kGrid * kGrid));
    }
    return t;
  }();
  const float x = std::clamp(cos_smooth_bumped, 0.0f, 1.0f) * (kEntries - 1);
  const int lo = std::min(static_cast<int>(x), kEntries - 2);
  const float f = x - lo;
  return table[lo] + f * (table[lo + 1] - table[lo]);
}

Vec3 Bsdf::albedo(const Vec3& wo, uint8_t mask) const {
  Vec3 wo_l, wo_w;
  if (!to_local(wo, &wo_l, &wo_w)) return Vec3(0.0f);
  Vec3 a(0.0f);
  for (int i = 0; i < count_; ++i) {
    if (!(lobes_[i].flags() & mask)) continue;
    Vec3 lwo = wo_l;
    if (own_frame_[i]) {
      lwo = lobe_frames_[i].to_local(wo_w);
      if (!(lwo.z > 1e-7f)) continue;
    }
    a += lobe_albedo(lobes_[i], lwo, eta(lobes_[i]));
  }
  return a;
}

}  // namespace photon
