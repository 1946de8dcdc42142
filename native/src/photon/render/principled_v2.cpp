#include "photon/render/principled_v2.h"

#include <algorithm>
#include <cmath>

#include "photon/base/optics.h"
#include "photon/render/microfacet_albedo.h"

namespace photon {
namespace principled_v2 {

float f0_from_ior(float ior) {
  const float r = (ior - 1.0f) / (ior + 1.0f);
  return r * r;
}

namespace {

float ior_from_f0(float f0) {
  const float s = std::sqrt(std::clamp(f0, 0.0f, 0.99f));
  return (1.0f + s) / (1.0f - s);
}

}  // namespace

float specular_eta(float ior, float level) {
  if (level == 0.5f) return ior;
  float eta = ior_from_f0(f0_from_ior(ior) * 2.0f * level);
  if (ior < 1.0f) eta = 1.0f / eta;
  return eta;
}

Vec3 f82_average(const Vec3& f0, const Vec3& tint) {
  // F82-tint's b (bsdf_lobes.h) and the cosine-weighted averages 2 int mu (1 - mu)^5 = 1 / 21 and
  // 2 int mu^2 (1 - mu)^6 = 1 / 126.
  constexpr float f = 6.0f / 7.0f;
  constexpr float f5 = (f * f) * (f * f) * f;
  const Vec3 b = (f0 + (Vec3(1.0f) - f0) * f5) * (7.0f / (f5 * f)) * (Vec3(1.0f) - tint);
  return f0 + (Vec3(1.0f) - f0) * (1.0f / 21.0f) - b * (1.0f / 126.0f);
}

Vec3 multiscatter_factor(float e, float e_avg, const Vec3& f_ss) {
  if (!(e > 0.0f)) return Vec3(1.0f);
  const float missing = (1.0f - e) / e;
  Vec3 out;
  for (int c = 0; c < 3; ++c) {
    // Kulla & Conty 2017, appendix: F_ms = F_ss E_avg / (1 - F_ss (1 - E_avg)).
    const float f_ms = f_ss[c] * e_avg / (1.0f - f_ss[c] * (1.0f - e_avg));
    out[c] = 1.0f + f_ms * missing;
  }
  return out;
}

}  // namespace principled_v2

namespace {

using namespace principled_v2;

constexpr float kCutoff = 1e-5f;  // Cycles' CLOSURE_WEIGHT_CUTOFF

Vec3 saturate(const Vec3& v) {
  return {std::clamp(v.x, 0.0f, 1.0f), std::clamp(v.y, 0.0f, 1.0f), std::clamp(v.z, 0.0f, 1.0f)};
}

// Below a layer of albedo `albedo` (per unit of `weight`, i.e. albedo / weight channel-wise where
// the weight is not zero): weight x clamp(1 - the largest such ratio, 0, 1).
Vec3 layered(const Vec3& weight, const Vec3& ratio) {
  float m = 0.0f;
  for (int c = 0; c < 3; ++c)
    if (weight[c] != 0.0f) m = std::max(m, ratio[c]);
  return weight * std::clamp(1.0f - m, 0.0f, 1.0f);
}

Vec3 rotate_about(const Vec3& v, const Vec3& k, float angle) {
  const float c = std::cos(angle), s = std::sin(angle);
  return v * c + cross(k, v) * s + k * (dot(k, v) * (1.0f - c));
}

// The GGX alphas of the metallic and specular layers (and whether they are anisotropic).
struct Alphas {
  float x, y;
  bool anisotropic;
  Vec3 tangent;
  float table_roughness() const {
    // Cycles reads its tables at sqrt(sqrt(alpha_x alpha_y)) of the saturated alphas.
    return std::sqrt(std::sqrt(std::min(x, 1.0f) * std::min(y, 1.0f)));
  }
};

Alphas alphas(const PrincipledV2Inputs& in, const PrincipledV2Geometry& geo) {
  Alphas a{in.roughness * in.roughness, in.roughness * in.roughness, false, Vec3(0.0f)};
  if (in.anisotropic > 0.0f && !is_black(geo.tangent)) {
    const float aspect = std::sqrt(1.0f - in.anisotropic * 0.9f);
    a.x /= aspect;
    a.y *= aspect;
    a.anisotropic = true;
    a.tangent = in.anisotropic_rotation != 0.0f
                    ? rotate_about(geo.tangent, geo.n, in.anisotropic_rotation * 2.0f * kPi)
                    : geo.tangent;
  }
  return a;
}

void set_alphas(const Alphas& a, Lobe* l) {
  l->alpha = a.x;
  if (a.anisotropic) {
    l->alpha_y = a.y;
    l->tangent = a.tangent;
  }
}

}  // namespace

Vec3 add_principled_v2(const PrincipledV2Inputs& in, float w, const PrincipledV2Geometry& geo,
                       Bsdf* bsdf) {
  const auto add = [&](const Lobe& l) {
    if (bsdf) bsdf->add(l);
  };
  Vec3 weight(w);
  const float alpha = std::clamp(in.alpha, 0.0f, 1.0f);
  if (alpha < 1.0f) {
    Lobe t;
    t.type = LobeType::kTransparent;
    t.weight = Vec3(w * (1.0f - alpha));
    add(t);
    weight = weight * alpha;
  }
  const Vec3 base = max(in.base_color, Vec3(0.0f));
  const Vec3 clamped_base = saturate(base);
  const Vec3 specular_tint = max(in.specular_tint, Vec3(0.0f));
  const float mu = std::clamp(dot(geo.wo, geo.n), 0.0f, 1.0f);

  // Coat.
  const float coat = std::max(in.coat_weight, 0.0f);
  if (coat > kCutoff) {
    const float coat_ior = std::max(in.coat_ior, 1.0f);
    const float cr = std::clamp(in.coat_roughness, 0.0f, 1.0f);
    Lobe c;
    c.type = LobeType::kGgxReflection;
    c.weight = weight * coat;
    c.alpha = cr * cr;
    c.fresnel = FresnelMode::kDielectric;
    c.ior = coat_ior;
    c.fixed_ior = true;
    c.correlated = true;
    c.normal = geo.coat_lobe_n;
    add(c);
    // Its albedo as a smooth surface's: the Fresnel factor at the coat normal.
    const float cos_c = std::clamp(dot(geo.wo, geo.coat_n), 0.0f, 1.0f);
    weight = layered(weight, Vec3(coat * fresnel_dielectric(cos_c, coat_ior)));
    const Vec3 tint = max(in.coat_tint, Vec3(0.0f));
    if (!(tint.x == 1.0f && tint.y == 1.0f && tint.z == 1.0f)) {
      // Beer's law through a coat of unit thickness, along the refracted view direction.
      const float inv = 1.0f / coat_ior;
      const float cos_t = std::sqrt(std::max(1.0f - inv * inv * (1.0f - cos_c * cos_c), 0.0f));
      const float depth = 1.0f / cos_t;
      Vec3 t;
      for (int k = 0; k < 3; ++k) t[k] = std::pow(tint[k], depth);
      weight = weight * lerp(Vec3(1.0f), t, coat);
    }
  }

  const Vec3 emission =
      max(in.emission, Vec3(0.0f)) * std::max(in.emission_strength, 0.0f) * weight;
  if (!bsdf) return emission;

  const Alphas a = alphas(in, geo);
  const float metallic = std::clamp(in.metallic, 0.0f, 1.0f);
  if (metallic > kCutoff) {
    Lobe m;
    m.type = LobeType::kGgxReflection;
    m.fresnel = FresnelMode::kF82Tint;
    m.f0 = clamped_base;
    m.tint = min(specular_tint, Vec3(1.0f));
    set_alphas(a, &m);
    m.correlated = true;
    m.normal = geo.lobe_n;
    m.weight = weight * metallic;
    if (in.multiscatter) {
      const float r = a.table_roughness();
      m.weight = m.weight * multiscatter_factor(microfacet_albedo::reflection_albedo(r, mu),
                                                microfacet_albedo::reflection_albedo_average(r),
                                                f82_average(m.f0, m.tint));
    }
    add(m);
    weight = weight * (1.0f - metallic);
  }

  const float ior = std::max(in.ior, 1e-5f);
  const float transmission = std::clamp(in.transmission, 0.0f, 1.0f);
  if (transmission > kCutoff) {
    Lobe t;
    t.type = LobeType::kGgxDielectric;
    t.fresnel = FresnelMode::kSchlickIor;
    t.ior = ior;  // inverted on back faces (Bsdf::eta)
    t.abbe = in.abbe;
    const float r = std::clamp(in.roughness, 0.0f, 1.0f);
    t.alpha = r * r;
    t.f0 = saturate(Vec3(f0_from_ior(ior)) * specular_tint);
    t.tint = Vec3(std::sqrt(clamped_base.x), std::sqrt(clamped_base.y), std::sqrt(clamped_base.z));
    t.correlated = true;
    t.normal = geo.lobe_n;
    t.weight = weight * transmission;
    if (in.multiscatter) {
      // The transmission tint stands for the lobe's colour (as Cycles assumes).
      const float eta = geo.front ? ior : 1.0f / ior;
      t.weight =
          t.weight * multiscatter_factor(microfacet_albedo::glass_albedo(r, mu, eta),
                                         microfacet_albedo::glass_albedo_average(r, eta), t.tint);
    }
    add(t);
    weight = weight * (1.0f - transmission);
  }

  // Specular: the IOR level scales F0 by changing the IOR.
  const float eta = specular_eta(ior, std::max(in.specular_ior_level, 0.0f));
  if (eta != 1.0f) {
    const float f0_real = f0_from_ior(eta);
    Lobe s;
    s.type = LobeType::kGgxReflection;
    s.fresnel = FresnelMode::kSchlickIor;
    s.ior = eta;
    s.fixed_ior = true;
    s.f0 = saturate(Vec3(f0_real) * specular_tint);
    set_alphas(a, &s);
    s.correlated = true;
    s.normal = geo.lobe_n;
    const float r = a.table_roughness();
    Vec3 darkening(1.0f);  // the part of the scaling Cycles keeps in the closure's weight
    Vec3 scale(1.0f);
    if (in.multiscatter) {
      const float e = microfacet_albedo::reflection_albedo(r, mu);
      // Kulla & Conty's fit of the cosine-weighted average of the dielectric Fresnel factor.
      const float real_fss = eta < 1.0f
                                 ? 0.997118f + eta * (0.1014f - eta * (0.965241f + eta * 0.130607f))
                                 : (eta - 1.0f) / (4.08567f + 1.00071f * eta);
      const float sf = 1.0f - f0_real > 0.0f
                           ? std::clamp((real_fss - f0_real) / (1.0f - f0_real), 0.0f, 1.0f)
                           : 1.0f;
      const Vec3 fss = s.f0 + (Vec3(1.0f) - s.f0) * sf;
      scale = multiscatter_factor(e, microfacet_albedo::reflection_albedo_average(r), fss);
      if (e > 0.0f) darkening = scale * e;  // scale / (1 + (1 - E) / E)
    }
    s.weight = weight * scale;
    add(s);
    // Attenuate the diffuse below by the layer's directional albedo.
    const float sa = microfacet_albedo::schlick_ior_factor_average(r, mu, eta);
    const Vec3 albedo = s.f0 + (Vec3(1.0f) - s.f0) * sa;
    weight = layered(weight, darkening * albedo);
  }

  // Diffuse, with the subsurface share rendered as diffuse of the clamped base colour.
  const float subsurface = std::clamp(in.subsurface, 0.0f, 1.0f);
  Lobe d;
  d.type = LobeType::kLambert;
  if (in.diffuse_roughness > 0.0f) {
    d.type = LobeType::kOrenNayar;
    d.roughness = in.diffuse_roughness;
    d.oren_nayar_multiscatter = true;
    d.tint = clamped_base;
  }
  d.weight = (base * (1.0f - subsurface) + clamped_base * subsurface) * weight;
  d.normal = geo.lobe_n;
  add(d);
  return emission;
}

}  // namespace photon
