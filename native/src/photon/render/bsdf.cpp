#include "photon/render/bsdf.h"

#include "photon/base/microfacet.h"
#include "photon/base/optics.h"
#include "photon/base/sampling.h"

namespace photon {
namespace {

// Below this distance from 1 a relative index of refraction leaves directions unchanged: the
// glass and refraction lobes are then delta lobes whatever their roughness (a rough interface
// with equal indices refracts every microfacet straight through).
constexpr float kUnitEtaEpsilon = 1e-4f;

bool is_unit_direction(const Vec3& w) {
  const float l2 = length_squared(w);
  return std::isfinite(l2) && l2 > 1e-12f;
}

// Normalises only when needed, so a direction that sample() returned maps to bit-identical
// local coordinates in pdf() and eval() (near total internal reflection 1 - F is steep enough
// for an ulp to show).
Vec3 unit(const Vec3& w) {
  const float l2 = length_squared(w);
  return std::fabs(l2 - 1.0f) < 4e-7f ? w : w / std::sqrt(l2);
}

// The largest GGX alpha of a lobe (both axes of an anisotropic one).
float max_alpha(const Lobe& l) {
  return l.anisotropic() ? std::max(l.alpha, l.alpha_y) : l.alpha;
}

bool is_delta(const Lobe& l) {
  switch (l.type) {
    case LobeType::kGgxReflection:
      return max_alpha(l) < kDeltaAlpha;
    case LobeType::kGgxGlass:
    case LobeType::kGgxRefraction:
      return l.alpha < kDeltaAlpha || std::fabs(l.ior - 1.0f) < kUnitEtaEpsilon;
    case LobeType::kTransparent:
      return true;
    default:
      return false;
  }
}

// The GGX functions of a lobe: anisotropic ones with both alphas (the isotropic path keeps the
// isotropic functions, so isotropic lobes are unchanged to the bit).
float lobe_d(const Lobe& l, const Vec3& h) {
  return l.anisotropic() ? ggx_d(h, l.alpha, l.alpha_y) : ggx_d(h, l.alpha);
}
float lobe_g2(const Lobe& l, const Vec3& wo, const Vec3& wi, const Vec3& h) {
  if (!l.anisotropic()) return ggx_g2(wo, wi, h, l.alpha);
  return ggx_g1(wo, h, l.alpha, l.alpha_y) * ggx_g1(wi, h, l.alpha, l.alpha_y);
}
float lobe_visible_normal_pdf(const Lobe& l, const Vec3& wo, const Vec3& h) {
  return l.anisotropic() ? ggx_visible_normal_pdf(wo, h, l.alpha, l.alpha_y)
                         : ggx_visible_normal_pdf(wo, h, l.alpha);
}
Vec3 lobe_sample_visible_normal(const Lobe& l, const Vec3& wo, Vec2 u) {
  return l.anisotropic() ? ggx_sample_visible_normal(wo, l.alpha, l.alpha_y, u)
                         : ggx_sample_visible_normal(wo, l.alpha, u);
}

// Fresnel of a kGgxReflection lobe at the microfacet cosine `cos_oh`.
Vec3 reflection_fresnel(const Lobe& l, float cos_oh, float eta) {
  switch (l.fresnel) {
    case FresnelMode::kDielectric:
      return Vec3(fresnel_dielectric(cos_oh, eta));
    case FresnelMode::kSchlick:
      return fresnel_schlick(l.f0, cos_oh);
    case FresnelMode::kInterpolated: {
      const float f_normal = fresnel_dielectric(1.0f, eta);
      const float fh =
          f_normal < 1.0f ? (fresnel_dielectric(cos_oh, eta) - f_normal) / (1.0f - f_normal) : 1.0f;
      return l.f0 + (Vec3(1.0f) - l.f0) * fh;
    }
    default:
      return Vec3(1.0f);
  }
}

// Where the generalized half vector of a refraction (Walter 2007, eq. 16) is valid: wo above,
// wi below, both on the front of the microfacet h (oriented to +z). `eta` = n_wi / n_wo.
struct RefractionGeometry {
  Vec3 h;
  float cos_oh = 0.0f, cos_ih = 0.0f;
  float denom2 = 0.0f;  // (wo.h + eta wi.h)^2
  bool valid = false;
};

RefractionGeometry refraction_geometry(const Vec3& wo, const Vec3& wi, float eta) {
  RefractionGeometry g;
  Vec3 h = wo + wi * eta;
  const float l2 = length_squared(h);
  if (!(l2 > 1e-12f)) return g;
  h = h / std::sqrt(l2);
  if (h.z < 0.0f) h = -h;
  g.h = h;
  g.cos_oh = dot(wo, h);
  g.cos_ih = dot(wi, h);
  if (g.cos_oh <= 0.0f || g.cos_ih >= 0.0f) return g;
  const float d = g.cos_oh + eta * g.cos_ih;
  g.denom2 = d * d;
  g.valid = g.denom2 > 1e-20f;
  return g;
}

struct LobeEval {
  Vec3 f{0.0f};      // f(wo, wi) without the cosine
  float pdf = 0.0f;  // solid-angle density of this lobe's sampling routine
};

// The share of a glass lobe that reflects: Cycles 3.4's Glass BSDF (svm/closure.h) weights
// its GGX reflection closure by the dielectric Fresnel of the shading normal, F(wo.z), and its
// GGX refraction closure by 1 - F(wo.z); neither applies a Fresnel term per microfacet.
float glass_fresnel(const Vec3& wo, float eta) {
  return fresnel_dielectric(wo.z, eta);
}

// Microfacet reflection (Walter 2007, eq. 20) of a GGX reflection or glass lobe, wo.z and wi.z
// > 0, with the pdf of visible-normal sampling (Heitz 2018, eq. 17 and the reflection
// Jacobian 1 / (4 wo.h)). Glass picks reflection with probability F(wo.z).
LobeEval ggx_reflection(const Lobe& l, const Vec3& wo, const Vec3& wi, float eta) {
  LobeEval r;
  const Vec3 h = normalize(wo + wi);
  const float cos_oh = dot(wo, h);
  if (cos_oh <= 0.0f) return r;
  const float d = lobe_d(l, h);
  const float g = lobe_g2(l, wo, wi, h);
  const bool glass = l.type == LobeType::kGgxGlass;
  const Vec3 fr = glass ? Vec3(glass_fresnel(wo, eta)) : reflection_fresnel(l, cos_oh, eta);
  r.f = l.weight * fr * (d * g / (4.0f * wo.z * wi.z));
  r.pdf = lobe_visible_normal_pdf(l, wo, h) / (4.0f * cos_oh) * (glass ? fr.x : 1.0f);
  return r;
}

// Microfacet refraction (Walter 2007, eq. 21) without the radiance scaling 1/eta^2 (see
// bsdf.h), wo.z > 0 > wi.z; the pdf uses the refraction Jacobian (eq. 17). Glass weights it by
// 1 - F(wo.z) (and picks it with that probability); the Refraction lobe refracts everything.
// Where the sampled microfacet reflects totally, neither returns light (as in Cycles 3.4).
LobeEval ggx_transmission(const Lobe& l, const Vec3& wo, const Vec3& wi, float eta) {
  LobeEval r;
  const RefractionGeometry geo = refraction_geometry(wo, wi, eta);
  if (!geo.valid) return r;
  const float d = lobe_d(l, geo.h);
  const float g = lobe_g2(l, wo, wi, geo.h);
  const float t = l.type == LobeType::kGgxGlass ? 1.0f - glass_fresnel(wo, eta) : 1.0f;
  const float jacobian = eta * eta * std::fabs(geo.cos_ih) / geo.denom2;  // d(h) / d(wi)
  r.f = l.weight * (t * d * g * jacobian * geo.cos_oh / (wo.z * std::fabs(wi.z)));
  r.pdf = t * lobe_visible_normal_pdf(l, wo, geo.h) * jacobian;
  return r;
}

// Chiang, Li & Burley 2019, "Taming the Shadow Terminator", eq. 4 with its smooth cubic
// (eq. 5): G = min(1, (Ns.wi) / ((Nb.wi)(Ns.Nb))) for the smooth normal Ns and the bumped
// normal Nb, smoothed as -G^3 + G^2 + G; 0 when wi is below the smooth surface.
float bump_shadowing(const Vec3& smooth_n, const Vec3& bumped_n, const Vec3& wi) {
  const float denominator = dot(bumped_n, wi) * dot(smooth_n, bumped_n);
  const float g = denominator != 0.0f ? dot(smooth_n, wi) / denominator : 0.0f;
  if (!(g < 1.0f)) return g >= 1.0f ? 1.0f : 0.0f;  // NaN: black
  if (g < 0.0f) return 0.0f;
  return g * (1.0f + g - g * g);
}

// The lobes Cycles counts as diffuse closures (CLOSURE_IS_BSDF_DIFFUSE).
bool is_diffuse_type(const Lobe& l) {
  return l.type == LobeType::kLambert || l.type == LobeType::kBurleyDiffuse ||
         l.type == LobeType::kTranslucent;
}

// f and pdf of one non-delta lobe, in the local frame (wo.z > 0). `reflect` is the geometric
// classification of the pair; a lobe only contributes where the shading frame agrees with it.
LobeEval eval_lobe(const Lobe& l, const Vec3& wo, const Vec3& wi, bool reflect, float eta) {
  LobeEval r;
  const bool shading_reflect = reflect && wi.z > 0.0f;
  const bool shading_transmit = !reflect && wi.z < 0.0f;
  switch (l.type) {
    case LobeType::kLambert:
      if (!shading_reflect) break;
      r.f = l.weight * kInvPi;
      r.pdf = cosine_hemisphere_pdf(wi.z);
      break;
    case LobeType::kBurleyDiffuse: {
      if (!shading_reflect) break;
      // Burley 2012, "Physically-Based Shading at Disney", sec. 5.3, as in Cycles' Principled
      // v1 diffuse (no retro-reflection term split off).
      const Vec3 h = normalize(wo + wi);
      const float cos_d = dot(wi, h);
      const float f90 = 0.5f + 2.0f * l.roughness * cos_d * cos_d;
      const float fl = schlick_weight(wi.z), fv = schlick_weight(wo.z);
      r.f = l.weight * (kInvPi * (1.0f + (f90 - 1.0f) * fl) * (1.0f + (f90 - 1.0f) * fv));
      r.pdf = cosine_hemisphere_pdf(wi.z);
      break;
    }
    case LobeType::kTranslucent:
      if (!shading_transmit) break;
      r.f = l.weight * kInvPi;
      r.pdf = cosine_hemisphere_pdf(-wi.z);
      break;
    case LobeType::kOrenNayar: {
      if (!shading_reflect) break;
      // Cycles 3.4 bsdf_oren_nayar: f = A + B t with s = wi.wo - cos_i cos_o, t = s / max(cos_i,
      // cos_o) where s > 0 (else s), A = 1 / (pi + (3 pi - 4) / 6 sigma), B = sigma A.
      const float sigma = l.roughness;
      const float a = 1.0f / (kPi + ((3.0f * kPi - 4.0f) / 6.0f) * sigma);
      const float b = sigma * a;
      float t = dot(wi, wo) - wi.z * wo.z;
      if (t > 0.0f) t /= std::max(wi.z, wo.z);
      r.f = l.weight * std::max(a + b * t, 0.0f);
      r.pdf = cosine_hemisphere_pdf(wi.z);
      break;
    }
    case LobeType::kSheen: {
      if (!shading_reflect) break;
      const Vec3 h = normalize(wo + wi);
      r.f = l.weight * schlick_weight(dot(wi, h));
      r.pdf = cosine_hemisphere_pdf(wi.z);
      break;
    }
    case LobeType::kGgxReflection:
      if (shading_reflect) r = ggx_reflection(l, wo, wi, eta);
      break;
    case LobeType::kGgxGlass:
      if (shading_reflect) r = ggx_reflection(l, wo, wi, eta);
      if (shading_transmit) r = ggx_transmission(l, wo, wi, eta);
      break;
    case LobeType::kGgxRefraction:
      if (shading_transmit) r = ggx_transmission(l, wo, wi, eta);
      break;
    case LobeType::kTransparent:
      break;
  }
  return r;
}

// Samples a direction from one non-delta lobe (local frame, wo.z > 0) and says whether it is a
// reflection. `u_choice` picks reflection or transmission for glass. Returns false when no
// direction comes out (refraction lobe at total internal reflection).
bool sample_lobe(const Lobe& l, const Vec3& wo, float eta, float u_choice, Vec2 u, Vec3* wi,
                 bool* reflection) {
  *reflection = true;
  switch (l.type) {
    case LobeType::kLambert:
    case LobeType::kBurleyDiffuse:
    case LobeType::kOrenNayar:
    case LobeType::kSheen:
      *wi = sample_cosine_hemisphere(u);
      return true;
    case LobeType::kTranslucent:
      *wi = -sample_cosine_hemisphere(u);
      *reflection = false;
      return true;
    case LobeType::kGgxReflection: {
      const Vec3 h = lobe_sample_visible_normal(l, wo, u);
      *wi = reflect(wo, h);
      return true;
    }
    case LobeType::kGgxGlass:
    case LobeType::kGgxRefraction: {
      const Vec3 h = lobe_sample_visible_normal(l, wo, u);
      const float f = l.type == LobeType::kGgxGlass ? glass_fresnel(wo, eta) : 0.0f;
      if (u_choice < f) {
        *wi = reflect(wo, h);
        return true;
      }
      *reflection = false;
      return refract(wo, h, eta, wi);
    }
    case LobeType::kTransparent:
      return false;
  }
  return false;
}

struct DeltaSample {
  Vec3 wi;
  Vec3 f{0.0f};       // throughput f |cos| integrated over the delta, for this event
  float prob = 1.0f;  // probability of this event within the lobe
  uint8_t flags = 0;
};

// Samples a delta lobe (local frame, wo.z > 0).
bool sample_delta_lobe(const Lobe& l, const Vec3& wo, float eta, float u_choice, DeltaSample* s) {
  const Vec3 n(0.0f, 0.0f, 1.0f);
  switch (l.type) {
    case LobeType::kGgxReflection:
      s->wi = reflect(wo, n);
      s->f = l.weight * reflection_fresnel(l, wo.z, eta);
      s->flags = kLobeReflection | kLobeSpecular;
      return true;
    case LobeType::kGgxGlass: {
      const float f = fresnel_dielectric(wo.z, eta);  // 1 on total internal reflection
      if (u_choice < f) {
        s->wi = reflect(wo, n);
        s->f = l.weight * f;
        s->prob = f;
        s->flags = kLobeReflection | kLobeSpecular;
        return true;
      }
      if (!refract(wo, n, eta, &s->wi)) return false;
      s->f = l.weight * (1.0f - f);
      s->prob = 1.0f - f;
      s->flags = kLobeTransmission | kLobeSpecular;
      return true;
    }
    case LobeType::kGgxRefraction:
      if (!refract(wo, n, eta, &s->wi)) return false;
      s->f = l.weight;
      s->flags = kLobeTransmission | kLobeSpecular;
      return true;
    case LobeType::kTransparent:
      s->wi = -wo;
      s->f = l.weight;
      s->flags = kLobeTransmission | kLobeSpecular;
      return true;
    default:
      return false;
  }
}

// The albedo estimate of one lobe at wo (local), used for lobe selection.
Vec3 lobe_albedo(const Lobe& l, const Vec3& wo, float eta) {
  if (l.type == LobeType::kGgxReflection) return l.weight * reflection_fresnel(l, wo.z, eta);
  // Sheen grows towards grazing; Cycles picks it by (1 - cos_o)^5 (its avg_value). A floor
  // keeps it selectable at normal incidence, where it still reflects light.
  if (l.type == LobeType::kSheen) return l.weight * std::max(schlick_weight(wo.z), 0.02f);
  return l.weight;
}

}  // namespace

Vec3 lobe_reflection_fresnel(const Lobe& lobe, float cos_oh, float eta) {
  return reflection_fresnel(lobe, cos_oh, eta);
}

uint8_t Lobe::flags() const {
  const uint8_t rough = is_delta(*this) ? kLobeSpecular : kLobeGlossy;
  switch (type) {
    case LobeType::kLambert:
    case LobeType::kBurleyDiffuse:
    case LobeType::kOrenNayar:
      return kLobeReflection | kLobeDiffuse;
    case LobeType::kSheen:
      // Not Lambertian: its weight is no hemispherical reflectance, so the photon map's
      // irradiance estimate must not stand in for it; it is sampled and ray traced.
      return kLobeReflection | kLobeGlossy;
    case LobeType::kTranslucent:
      return kLobeTransmission | kLobeGlossy;
    case LobeType::kGgxReflection:
      return kLobeReflection | rough;
    case LobeType::kGgxGlass:
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
  return front_facing_ ? l.ior : 1.0f / l.ior;
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

void Bsdf::eval_mixture(const Vec3& wo_world, const Vec3& wo, const Vec3& wi_world, const Vec3& wi,
                        uint8_t mask, const float* probs, Vec3* f, float* pdf) const {
  *f = Vec3(0.0f);
  *pdf = 0.0f;
  const bool reflect = dot(wi_world, ng_) * dot(wo_world, ng_) > 0.0f;
  for (int i = 0; i < count_; ++i) {
    const Lobe& l = lobes_[i];
    if (!(l.flags() & mask) || is_delta(l)) continue;
    Vec3 lwo, lwi;
    if (!lobe_local(i, wo_world, wo, wi_world, wi, &lwo, &lwi)) continue;
    const LobeEval e = eval_lobe(l, lwo, lwi, reflect, eta(l));
    // Each diffuse lobe is shadowed by how far its own normal bends from the smooth one.
    const Vec3& ln = own_frame_[i] ? lobe_frames_[i].n : frame_.n;
    const bool shadowed =
        is_diffuse_type(l) &&
        (own_frame_[i] ? has_smooth_ && length_squared(smooth_n_ - ln) > 0.0f : bumped_);
    *f += shadowed ? e.f * bump_shadowing(reflect ? smooth_n_ : -smooth_n_, ln, wi_world) : e.f;
    if (probs) *pdf += probs[i] * e.pdf;
  }
}

Vec3 Bsdf::eval(const Vec3& wo, const Vec3& wi, uint8_t mask) const {
  Vec3 wo_l, wo_w;
  if (!to_local(wo, &wo_l, &wo_w) || !is_unit_direction(wi)) return Vec3(0.0f);
  const Vec3 wi_w = unit(wi);
  Vec3 f;
  float pdf;
  eval_mixture(wo_w, wo_l, wi_w, frame_.to_local(wi_w), mask, nullptr, &f, &pdf);
  return is_finite(f) ? f : Vec3(0.0f);
}

float Bsdf::pdf(const Vec3& wo, const Vec3& wi, uint8_t mask) const {
  Vec3 wo_l, wo_w;
  if (!to_local(wo, &wo_l, &wo_w) || !is_unit_direction(wi)) return 0.0f;
  float probs[kMaxLobes];
  if (selection_probabilities(wo_l, mask, probs) == 0) return 0.0f;
  const Vec3 wi_w = unit(wi);
  Vec3 f;
  float pdf;
  eval_mixture(wo_w, wo_l, wi_w, frame_.to_local(wi_w), mask, probs, &f, &pdf);
  return std::isfinite(pdf) ? pdf : 0.0f;
}

bool Bsdf::sample(const Vec3& wo, float u_lobe, Vec2 u, uint8_t mask, BsdfSample* out) const {
  Vec3 wo_l, wo_w;
  if (!to_local(wo, &wo_l, &wo_w)) return false;
  if (!std::isfinite(u_lobe) || !std::isfinite(u.x) || !std::isfinite(u.y)) return false;
  u_lobe = std::clamp(u_lobe, 0.0f, 0.99999994f);
  u = Vec2(std::clamp(u.x, 0.0f, 0.99999994f), std::clamp(u.y, 0.0f, 0.99999994f));
  float probs[kMaxLobes];
  if (selection_probabilities(wo_l, mask, probs) == 0) return false;

  // Choose a lobe and remap u_lobe to [0, 1) within its interval for the lobe's own choice.
  int k = -1;
  float cdf = 0.0f;
  for (int i = 0; i < count_; ++i) {
    if (probs[i] <= 0.0f) continue;
    k = i;
    if (u_lobe < cdf + probs[i]) break;
    cdf += probs[i];
  }
  const float u_choice = std::clamp((u_lobe - cdf) / probs[k], 0.0f, 0.99999994f);
  const Lobe& lobe = lobes_[k];
  const float lobe_eta = eta(lobe);
  const float wo_ng = dot(wo_w, ng_);
  // wo in the chosen lobe's frame (its selection probability is zero when wo is below it).
  const Frame& lobe_frame = own_frame_[k] ? lobe_frames_[k] : frame_;
  const Vec3 lobe_wo = own_frame_[k] ? lobe_frame.to_local(wo_w) : wo_l;

  if (is_delta(lobe)) {
    DeltaSample s;
    if (!sample_delta_lobe(lobe, lobe_wo, lobe_eta, u_choice, &s)) return false;
    const Vec3 wi = normalize(lobe_frame.to_world(s.wi));
    // The geometric normal must agree with the event (Veach 1997, sec. 5.3).
    const bool reflect = dot(wi, ng_) * wo_ng > 0.0f;
    if (reflect != ((s.flags & kLobeReflection) != 0)) return false;
    const float pdf = probs[k] * s.prob;
    if (!(pdf > 0.0f)) return false;
    out->wi = wi;
    out->pdf = pdf;
    out->weight = s.f / pdf;
    out->flags = s.flags;
    out->transparent = lobe.type == LobeType::kTransparent;
    return is_finite(out->weight);
  }

  Vec3 wi_l;
  bool reflection;
  if (!sample_lobe(lobe, lobe_wo, lobe_eta, u_choice, u, &wi_l, &reflection)) return false;
  const Vec3 wi = normalize(lobe_frame.to_world(wi_l));
  wi_l = frame_.to_local(wi);
  const Vec3 lobe_wi = own_frame_[k] ? lobe_frame.to_local(wi) : wi_l;
  const bool reflect = dot(wi, ng_) * wo_ng > 0.0f;
  // An event that ends on the wrong side of the shading or the geometric surface (a microfacet
  // reflection below the horizon, say) is not returned: eval() and pdf() count neither, so
  // sample() follows pdf() exactly. Glass must check the event itself, since a reflection
  // below the surface lands where its own refraction density is not zero.
  if (reflect != reflection || (reflection ? lobe_wi.z <= 0.0f : lobe_wi.z >= 0.0f)) return false;
  if (!(eval_lobe(lobe, lobe_wo, lobe_wi, reflect, lobe_eta).pdf > 0.0f)) return false;
  Vec3 f;
  float pdf;
  eval_mixture(wo_w, wo_l, wi, wi_l, mask, probs, &f, &pdf);
  if (!(pdf > 0.0f) || !std::isfinite(pdf)) return false;
  out->wi = wi;
  out->pdf = pdf;
  out->weight = f * (std::fabs(wi_l.z) / pdf);
  // The lobe's flags, narrowed to the event that happened (reflection or transmission).
  out->flags = lobe.flags() & ~(reflect ? kLobeTransmission : kLobeReflection);
  return is_finite(out->weight);
}

Vec3 Bsdf::diffuse_reflectance() const {
  Vec3 r(0.0f);
  for (int i = 0; i < count_; ++i)
    if (lobes_[i].flags() & kLobeDiffuse) r += lobes_[i].weight;
  return r;
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
