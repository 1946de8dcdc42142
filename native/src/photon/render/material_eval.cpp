#include "photon/render/material_eval.h"

#include <optional>

#include "photon/base/optics.h"
#include "photon/render/microfacet_albedo.h"
#include "photon/render/principled_v2.h"
#include "photon/render/shader_globals.h"
#include "photon/render/valid_reflection.h"
#include "photon/scene/material_params.h"
#include "photon/shading/program_eval.h"

namespace photon {
namespace {

constexpr float kWeightCutoff = 1e-5f;  // closures below this weight are skipped (Cycles: 1e-5)

// A program register or texture lookup, unclamped (non-finite values already read as 0), or
// the constant.
struct InputReader {
  Vec2 uv;
  const TextureSet* textures;
  const float* registers = nullptr;  // the material's program after it ran, or null

  Vec3 raw(const Input& in, bool* textured) const {
    *textured = false;
    if (in.reg >= 0 && registers) {
      const Vec3 v = load3(registers, in.reg);
      *textured = true;
      return Vec3(std::isfinite(v.x) ? v.x : 0.0f, std::isfinite(v.y) ? v.y : 0.0f,
                  std::isfinite(v.z) ? v.z : 0.0f);
    }
    if (in.texture >= 0 && textures) {
      float rgba[4];
      if (textures->lookup(in.texture, uv, rgba)) {
        *textured = true;
        return in.channel == TextureChannel::kAlpha ? Vec3(rgba[3])
                                                    : Vec3(rgba[0], rgba[1], rgba[2]);
      }
    }
    return is_finite(in.value) ? in.value : Vec3(0.0f);
  }
  // Textured values are clamped to the input's range after the lookup, as constants are when
  // the material is built (an albedo texture of 1000 must not multiply energy by 1000).
  Vec3 color(const Input& in, ParamRange r) const {
    bool textured;
    const Vec3 v = raw(in, &textured);
    if (!textured) return max(v, Vec3(0.0f));
    return {std::clamp(v.x, r.lo, r.hi), std::clamp(v.y, r.lo, r.hi), std::clamp(v.z, r.lo, r.hi)};
  }
  // A colour feeding a scalar socket becomes its luminance (Blender's implicit conversion).
  float scalar(const Input& in, ParamRange r) const {
    bool textured;
    const Vec3 v = raw(in, &textured);
    if (!textured) return v.x;
    // A register already holds the scalar (the add-on converts colours to floats as Blender
    // does); a texture's colour becomes its luminance.
    const bool scalar = in.reg >= 0 || in.channel == TextureChannel::kAlpha;
    return std::clamp(scalar ? v.x : luminance(v), r.lo, r.hi);
  }
  float unit(const Input& in) const { return std::clamp(scalar(in, {0.0f, 1.0f}), 0.0f, 1.0f); }
};

// One closure's inputs, each read within its range.
struct ClosureReader {
  const InputReader& in;
  const Closure& c;
  Vec3 color(Param p) const { return in.color(c[p], param_range(c.type, p)); }
  float scalar(Param p) const { return in.scalar(c[p], param_range(c.type, p)); }
  float unit(Param p) const { return in.unit(c[p]); }
};

float closure_weight(const Closure& c, const InputReader& in) {
  float w = 1.0f;
  for (const WeightFactor& f : c.weight) {
    const float v = in.unit(f.fac);
    w *= f.complement ? 1.0f - v : v;
  }
  return w;
}

// A tangent-space Normal Map node (Blender's convention: colour 2c - 1 in (T, B, N), then
// N' = normalize(N + (N_map - N) * strength)). Returns `ns` unchanged when it cannot apply.
Vec3 apply_normal_map(const NormalMap& map, const SurfaceInteraction& si, const Accel& accel,
                      const InputReader& in) {
  if (map.texture < 0 || !in.textures || !(map.strength > 0.0f)) return si.ns;
  float rgba[4];
  if (!in.textures->lookup(map.texture, in.uv, rgba)) return si.ns;
  Vec3 dpdu, dpdv;
  if (!accel.uv_tangents(si.instance, si.primitive, &dpdu, &dpdv)) return si.ns;
  const Vec3 n = si.ns;
  Vec3 t = dpdu - n * dot(n, dpdu);
  if (!(length_squared(t) > 0.0f)) return si.ns;
  t = normalize(t);
  Vec3 b = cross(n, t);
  if (dot(b, dpdv) < 0.0f) b = -b;
  const Vec3 local(2.0f * rgba[0] - 1.0f, 2.0f * rgba[1] - 1.0f, 2.0f * rgba[2] - 1.0f);
  Vec3 mapped = t * local.x + b * local.y + n * local.z;
  if (!(length_squared(mapped) > 0.0f)) return si.ns;
  mapped = normalize(n + (normalize(mapped) - n) * map.strength);
  // A bent normal must stay on the geometric normal's side, or the surface turns black.
  if (!is_finite(mapped) || dot(mapped, si.ng) <= 1e-3f) return si.ns;
  return mapped;
}

// What closures need of the shading point besides their inputs, in the BSDF's orientation
// (normals facing wo's side).
struct LobeGeometry {
  Vec3 wo;                 // towards the viewer
  Vec3 n;                  // the closure's shading normal
  Vec3 lobe_n{0.0f};       // the closure's normal when it differs from the BSDF's, else zero
  Vec3 tangent{0.0f};      // the UV map's dP/du, or zero without UVs
  Vec3 clearcoat_n{0.0f};  // the Clearcoat Normal (or the interpolated normal), zero: the BSDF's
  bool front = true;
};

// Rodrigues' rotation of v about the unit axis k by `angle` radians (right-handed).
Vec3 rotate_about(const Vec3& v, const Vec3& k, float angle) {
  const float c = std::cos(angle), s = std::sin(angle);
  return v * c + cross(k, v) * s + k * (dot(k, v) * (1.0f - c));
}

// The tangent of an anisotropic lobe: dP/du turned by `rotation` turns about the normal (as
// Cycles 3.4 turns its closure's T by rotation x 2 pi).
Vec3 rotated_tangent(const LobeGeometry& g, float rotation) {
  if (rotation == 0.0f) return g.tangent;
  return rotate_about(g.tangent, g.n, rotation * 2.0f * kPi);
}

// Cycles 3.4 Principled v1 (intern/cycles/kernel/svm/closure.h, PrincipledBsdfNode::expand):
// alpha mixes with a transparent BSDF; diffuse (Burley) weighted by (1 - metallic)(1 -
// transmission); a GGX specular layer with Schlick F0 = lerp(0.08 specular tint, base,
// metallic); glass weighted by transmission (1 - metallic) tinted by the base colour; a
// clearcoat layer of weight 0.25 clearcoat with F0 = 0.04, on its own normal when linked.
// Sheen (weight sheen x diffuse weight, tinted towards the base colour's hue by Sheen Tint),
// anisotropic specular (alpha_x = r^2 / aspect, alpha_y = r^2 aspect, aspect = sqrt(1 - 0.9
// anisotropic)) and the glass, always split into reflection with Roughness and refraction with
// 1 - (1 - roughness)(1 - transmission roughness), follow the same function. Subsurface is
// rendered as Cycles renders it without SSS: the diffuse colour mixes towards Subsurface
// Color by the Subsurface weight.
void add_principled(const Closure& c, float w, const InputReader& reader, const LobeGeometry& geo,
                    ShadingPoint* out) {
  const ClosureReader in{reader, c};
  const float alpha = in.unit(Param::kAlpha);
  if (alpha < 1.0f) {
    Lobe t;
    t.type = LobeType::kTransparent;
    t.weight = Vec3(w * (1.0f - alpha));
    out->bsdf.add(t);
  }
  w *= alpha;
  if (w < kWeightCutoff) return;
  out->emission += in.color(Param::kEmission) * (std::max(in.scalar(Param::kStrength), 0.0f) * w);

  const Vec3 base = in.color(Param::kColor);
  const float metallic = in.unit(Param::kMetallic);
  const float transmission = in.unit(Param::kTransmission);
  const float roughness = in.unit(Param::kRoughness);
  const float specular = std::max(in.scalar(Param::kSpecular), 0.0f);
  const float ior = std::max(in.scalar(Param::kIor), 1e-3f);

  const float diffuse_weight = (1.0f - metallic) * (1.0f - transmission);
  const float lum = luminance(base);
  const Vec3 hue = lum > 0.0f ? base / lum : Vec3(1.0f);
  if (diffuse_weight > 0.0f) {
    const float subsurface = in.unit(Param::kSubsurface);
    const Vec3 diffuse_color =
        subsurface > 0.0f ? lerp(base, in.color(Param::kSubsurfaceColor), subsurface) : base;
    Lobe d;
    d.type = LobeType::kBurleyDiffuse;
    d.weight = diffuse_color * (w * diffuse_weight);
    d.roughness = roughness;
    d.normal = geo.lobe_n;
    out->bsdf.add(d);
    const float sheen = std::max(in.scalar(Param::kSheen), 0.0f);
    if (sheen > kWeightCutoff) {
      Lobe sh;
      sh.type = LobeType::kSheen;
      sh.weight = lerp(Vec3(1.0f), hue, in.unit(Param::kSheenTint)) * (w * sheen * diffuse_weight);
      sh.normal = geo.lobe_n;
      out->bsdf.add(sh);
    }
  }
  const float final_transmission = transmission * (1.0f - metallic);
  const float specular_tint = in.unit(Param::kSpecularTint);
  if (specular > 0.0f || metallic > 0.0f) {
    const Vec3 tint = lerp(Vec3(1.0f), hue, specular_tint);
    Lobe s;
    s.type = LobeType::kGgxReflection;
    s.weight = Vec3(w * (1.0f - final_transmission));
    s.alpha = roughness * roughness;
    s.fresnel = FresnelMode::kSchlick;
    s.f0 = lerp(tint * (0.08f * specular), base, metallic);
    const float anisotropic = in.unit(Param::kAnisotropic);
    if (anisotropic > 0.0f && !is_black(geo.tangent)) {
      const float aspect = std::sqrt(std::max(1.0f - anisotropic * 0.9f, 0.0f));
      s.alpha = roughness * roughness / aspect;
      s.alpha_y = roughness * roughness * aspect;
      s.tangent = rotated_tangent(geo, in.scalar(Param::kAnisotropicRotation));
    }
    s.normal = geo.lobe_n;
    out->bsdf.add(s);
  }
  if (final_transmission > 0.0f) {
    // Cycles 3.4 splits the glass whenever the distribution is GGX (the node's default) or
    // Roughness <= 0.05, Transmission Roughness 0 included: a GGX reflection weighted by the
    // dielectric Fresnel of the shading normal, its microfacets tinted by cspec0 (the base
    // colour by Specular Tint, not the base colour itself) blended to white towards grazing
    // and total reflection (interpolate_fresnel_color), and a GGX refraction with alpha from
    // 1 - (1 - roughness)(1 - transmission roughness) weighted by the rest and the base colour.
    // Unlike a glass lobe with the microfacet Fresnel (Walter 2007, eq. 21) the refraction
    // returns nothing where a microfacet reflects totally, so rough glass keeps less energy:
    // a Roughness 0.3 glass sphere is 10% darker than with the single glass lobe.
    const float transmission_roughness = in.unit(Param::kTransmissionRoughness);
    const float cos_o = std::clamp(dot(geo.wo, geo.n), 0.0f, 1.0f);
    const float fresnel = fresnel_dielectric(cos_o, geo.front ? ior : 1.0f / ior);
    Lobe r;
    r.type = LobeType::kGgxReflection;
    r.weight = Vec3(w * final_transmission * fresnel);
    r.alpha = roughness * roughness;
    r.fresnel = FresnelMode::kInterpolated;
    r.f0 = lerp(Vec3(1.0f), base, specular_tint);
    r.ior = ior;
    r.abbe = c.abbe;
    r.normal = geo.lobe_n;
    out->bsdf.add(r);
    const float rt = 1.0f - (1.0f - roughness) * (1.0f - transmission_roughness);
    Lobe t;
    t.type = LobeType::kGgxRefraction;
    t.weight = base * (w * final_transmission * (1.0f - fresnel));
    t.alpha = rt * rt;
    t.ior = ior;
    t.abbe = c.abbe;
    t.normal = geo.lobe_n;
    out->bsdf.add(t);
  }
  const float clearcoat = std::max(in.scalar(Param::kClearcoat), 0.0f);
  if (clearcoat > 0.0f) {
    const float r = in.unit(Param::kClearcoatRoughness);
    Lobe cc;
    cc.type = LobeType::kGgxReflection;
    cc.weight = Vec3(w * 0.25f * clearcoat);
    cc.alpha = r * r;
    cc.fresnel = FresnelMode::kSchlick;
    cc.f0 = Vec3(0.04f);
    cc.normal = geo.clearcoat_n;
    out->bsdf.add(cc);
  }
}

// A Principled v2 closure's inputs read at the shading point.
PrincipledV2Inputs principled_v2_inputs(const Closure& c, const InputReader& reader) {
  const ClosureReader in{reader, c};
  PrincipledV2Inputs p;
  p.base_color = in.color(Param::kColor);
  p.metallic = in.unit(Param::kMetallic);
  p.roughness = in.unit(Param::kRoughness);
  p.ior = in.scalar(Param::kIor);
  p.alpha = in.unit(Param::kAlpha);
  p.subsurface = in.unit(Param::kSubsurface);
  p.diffuse_roughness = in.unit(Param::kDiffuseRoughness);
  p.specular_ior_level = in.scalar(Param::kSpecularIorLevel);
  p.specular_tint = in.color(Param::kSpecularTintColor);
  p.anisotropic = in.unit(Param::kAnisotropic);
  p.anisotropic_rotation = in.scalar(Param::kAnisotropicRotation);
  p.transmission = in.unit(Param::kTransmission);
  p.coat_weight = in.scalar(Param::kCoatWeight);
  p.coat_roughness = in.unit(Param::kCoatRoughness);
  p.coat_ior = in.scalar(Param::kCoatIor);
  p.coat_tint = in.color(Param::kCoatTint);
  p.emission = in.color(Param::kEmission);
  p.emission_strength = in.scalar(Param::kStrength);
  p.multiscatter = c.multiscatter;
  p.abbe = c.abbe;
  return p;
}

PrincipledV2Geometry principled_v2_geometry(const LobeGeometry& geo, const Vec3& bsdf_n) {
  PrincipledV2Geometry g;
  g.wo = geo.wo;
  g.n = geo.n;
  g.lobe_n = geo.lobe_n;
  g.coat_lobe_n = geo.clearcoat_n;
  g.coat_n = is_black(geo.clearcoat_n) ? bsdf_n : geo.clearcoat_n;
  g.tangent = geo.tangent;
  g.front = geo.front;
  return g;
}

void add_closure(const Closure& c, float w, const InputReader& reader, const LobeGeometry& geo,
                 ShadingPoint* out) {
  if (c.type == ClosureType::kPrincipled) return add_principled(c, w, reader, geo, out);
  if (c.type == ClosureType::kPrincipledV2) {
    out->emission +=
        add_principled_v2(principled_v2_inputs(c, reader), w,
                          principled_v2_geometry(geo, out->bsdf.frame().n), &out->bsdf);
    return;
  }
  if (c.type == ClosureType::kHoldout) {
    out->holdout += w;
    return;
  }
  const ClosureReader in{reader, c};
  const Vec3 color = in.color(Param::kColor) * w;
  if (c.type == ClosureType::kEmission) {
    out->emission += color * std::max(in.scalar(Param::kStrength), 0.0f);
    return;
  }
  Lobe l;
  l.weight = color;
  const float r = c.sharp ? 0.0f : in.unit(Param::kRoughness);
  l.alpha = r * r;
  l.ior = std::max(in.scalar(Param::kIor), 1e-3f);
  l.beckmann = c.beckmann;  // read only by the microfacet lobes
  switch (c.type) {
    case ClosureType::kDiffuse:
      // Cycles 3.4: Lambert at roughness 0, else Oren-Nayar with sigma = roughness; Cycles
      // 4.3+ adds the multiple scattering of the node's colour.
      l.type = r > 0.0f ? LobeType::kOrenNayar : LobeType::kLambert;
      l.roughness = r;
      l.alpha = 0.0f;
      if (c.diffuse_multiscatter) {
        l.oren_nayar_multiscatter = true;
        l.tint = in.color(Param::kColor);
      }
      break;
    case ClosureType::kAnisotropic: {
      // Cycles 3.4 Anisotropic BSDF: anisotropy a clamped to +-0.99, alpha_x = r^2 (1 - a) and
      // alpha_y = r^2 / (1 - a) for a >= 0, alpha_x = r^2 / (1 + a), alpha_y = r^2 (1 + a)
      // below. Without a tangent (no UVs) it stays isotropic.
      l.type = LobeType::kGgxReflection;
      l.fresnel = FresnelMode::kNone;
      const float a = std::clamp(in.scalar(Param::kAnisotropic), -0.99f, 0.99f);
      if (!is_black(geo.tangent) && a != 0.0f) {
        const float r2 = l.alpha;
        l.alpha = a < 0.0f ? r2 / (1.0f + a) : r2 * (1.0f - a);
        l.alpha_y = a < 0.0f ? r2 * (1.0f + a) : r2 / (1.0f - a);
        l.tangent = rotated_tangent(geo, in.scalar(Param::kAnisotropicRotation));
      }
      if (c.cycles4) {
        // Blender 4's Glossy BSDF: Cycles 4's microfacet model, and with Multiscatter GGX the
        // energy single scattering loses put back, coloured by the node's colour
        // (bsdf_microfacet_setup_fresnel_constant).
        l.correlated = true;
        if (c.multiscatter && w > 0.0f) {
          const float ax = std::min(l.alpha, 1.0f);
          const float ay = l.anisotropic() ? std::min(l.alpha_y, 1.0f) : ax;
          const float rough = std::sqrt(std::sqrt(ax * ay));
          const float mu = std::clamp(dot(geo.wo, geo.n), 0.0f, 1.0f);
          l.weight = l.weight * principled_v2::multiscatter_factor(
                                    microfacet_albedo::reflection_albedo(rough, mu),
                                    microfacet_albedo::reflection_albedo_average(rough),
                                    min(color / w, Vec3(1.0f)));
        }
      }
      break;
    }
    case ClosureType::kGlossy:
      l.type = LobeType::kGgxReflection;
      l.fresnel = FresnelMode::kNone;
      break;
    case ClosureType::kGlass:
      l.abbe = c.abbe;
      if (c.cycles4) {
        // Blender 4's Glass BSDF: one GGX interface reflecting and refracting with each
        // microfacet's dielectric Fresnel (Cycles' generalized Schlick with F0 = F0(IOR) and
        // a negative exponent: the real Fresnel), both tinted by the colour; Multiscatter GGX
        // scales it up by the energy single scattering loses (the glass albedo table).
        l.type = LobeType::kGgxDielectric;
        l.fresnel = FresnelMode::kSchlickIor;
        l.f0 = Vec3(principled_v2::f0_from_ior(l.ior));
        l.tint = Vec3(1.0f);
        l.correlated = true;
        if (c.multiscatter && w > 0.0f) {
          const float mu = std::clamp(dot(geo.wo, geo.n), 0.0f, 1.0f);
          const float eta = geo.front ? l.ior : 1.0f / l.ior;
          l.weight = l.weight * principled_v2::multiscatter_factor(
                                    microfacet_albedo::glass_albedo(r, mu, eta),
                                    microfacet_albedo::glass_albedo_average(r, eta),
                                    min(color / w, Vec3(1.0f)));
        }
        break;
      }
      l.type = LobeType::kGgxGlass;
      l.fresnel = FresnelMode::kDielectric;
      break;
    case ClosureType::kRefraction:
      l.type = LobeType::kGgxRefraction;
      l.fresnel = FresnelMode::kDielectric;
      l.abbe = c.abbe;
      l.correlated = c.cycles4;  // Cycles 4's height-correlated masking-shadowing
      break;
    case ClosureType::kTransparent:
      l.type = LobeType::kTransparent;
      break;
    case ClosureType::kTranslucent:
      l.type = LobeType::kTranslucent;
      break;
    case ClosureType::kVelvet:
      // Cycles saturates Sigma (and its velvet takes at least 0.01).
      l.type = LobeType::kVelvet;
      l.roughness = std::clamp(in.scalar(Param::kSigma), 0.0f, 1.0f);
      l.alpha = 0.0f;
      break;
    default:
      return;
  }
  if (l.type != LobeType::kTransparent) l.normal = geo.lobe_n;  // straight through either way
  out->bsdf.add(l);
}

// A normal from the program (Bump, Normal Map), in world space on the incoming ray's side:
// turned to the geometric normal's side for the Bsdf, which flips both for back faces.
Vec3 program_normal(const Vec3& n, const SurfaceInteraction& si, bool front) {
  if (!is_finite(n) || !(length_squared(n) > 0.0f)) return si.ns;
  Vec3 ns = normalize(front ? n : -n);
  // A bent normal must stay on the geometric normal's side, or the surface turns black.
  if (dot(ns, si.ng) <= 1e-3f) return si.ns;
  return ns;
}

bool same_vector(const Vec3& a, const Vec3& b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

// The material's program run at a shading point, when it has one.
class ProgramRun {
 public:
  ProgramRun(const Material& m, const SurfaceInteraction& si, const Vec3& wo, const Accel* accel,
             const TextureSet* textures, const ShadeRay& ray) {
    if (m.program.empty()) return;
    registers_.emplace(m.program);
    const ShaderGlobals g = surface_globals(si, wo, accel, textures, ray);
    run_program(m.program, g, registers_->data());
  }
  const float* registers() { return registers_ ? registers_->data() : nullptr; }

 private:
  std::optional<ProgramRegisters> registers_;
};

}  // namespace

const char* input_label(ClosureType type, Param p) {
  return param_spec(type, p).sockets[0];
}

ShadingPoint shade_surface(const SurfaceInteraction& si, const Vec3& wo, const Accel& accel,
                           const TextureSet* textures, const ShadeRay& ray) {
  ShadingPoint out;
  const Material& m = si.mat ? *si.mat : Scene::default_material();
  InputReader in{si.uv, textures};
  const bool front = dot(si.ng, wo) >= 0.0f;
  ProgramRun run(m, si, wo, &accel, textures, ray);
  in.registers = run.registers();
  // Each closure shades with its own Normal input, or the interpolated normal when unlinked (as
  // Cycles' closures do). The BSDF's frame takes the first closure's linked normal; closures
  // whose normal differs get lobes with their own frames.
  const auto closure_normal = [&](const Closure& c, bool* linked) {
    *linked = true;
    if (c.normal_reg >= 0 && in.registers)
      return program_normal(load3(in.registers, c.normal_reg), si, front);
    if (c.normal.texture >= 0) return apply_normal_map(c.normal, si, accel, in);
    *linked = false;
    return si.ns;
  };
  Vec3 ns = si.ns;
  for (const Closure& c : m.closures) {
    bool linked;
    const Vec3 n = closure_normal(c, &linked);
    if (linked) {
      ns = n;
      break;
    }
  }
  // Both normals on the viewer's side, each shading normal turned (as Cycles turns every
  // closure's N) so that the view direction's mirror reflection stays above the surface.
  const Vec3 ng_view = front ? si.ng : -si.ng;
  const auto view_normal = [&](const Vec3& n) {
    return ensure_valid_reflection(ng_view, wo, front ? n : -n);
  };
  const Vec3 ns_view = view_normal(ns);
  out.bsdf = Bsdf(ns_view, ng_view, front);
  // A normal other than the interpolated one (Bump, Normal Map, or turned above): diffuse
  // lobes get Cycles' bump shadowing term.
  const Vec3 smooth_view = front ? si.ns : -si.ns;
  out.bsdf.set_smooth_normal(smooth_view);
  LobeGeometry geo;
  geo.wo = wo;
  geo.front = front;
  if (m.needs_tangent()) {
    Vec3 dpdu, dpdv;
    if (accel.uv_tangents(si.instance, si.primitive, &dpdu, &dpdv) && is_finite(dpdu))
      geo.tangent = dpdu;
  }
  for (const Closure& c : m.closures) {
    const float w = closure_weight(c, in);
    if (w < kWeightCutoff) continue;
    bool linked;
    const Vec3 n = closure_normal(c, &linked);
    const bool own = !same_vector(n, ns);
    geo.n = own ? view_normal(n) : out.bsdf.frame().n;
    geo.lobe_n = own ? geo.n : Vec3(0.0f);
    // Cycles' clearcoat shades with the Clearcoat Normal when linked, else the interpolated
    // normal (not the closure's Normal).
    Vec3 coat_n = si.ns;
    if (c.clearcoat_normal_reg >= 0 && in.registers)
      coat_n = program_normal(load3(in.registers, c.clearcoat_normal_reg), si, front);
    geo.clearcoat_n = same_vector(coat_n, ns) ? Vec3(0.0f) : view_normal(coat_n);
    add_closure(c, w, in, geo, &out);
  }
  if (!is_finite(out.emission)) out.emission = Vec3(0.0f);
  out.holdout = std::min(out.holdout, 1.0f);  // Add Shader sums may exceed 1
  return out;
}

void eval_material_aovs(const Material& material, const SurfaceInteraction& si, const Vec3& wo,
                        const Accel& accel, const TextureSet* textures, const ShadeRay& ray,
                        Vec3* out) {
  if (material.aovs.empty()) return;
  InputReader in{si.uv, textures};
  ProgramRun run(material, si, wo, &accel, textures, ray);
  in.registers = run.registers();
  for (size_t k = 0; k < material.aovs.size(); ++k) {
    const MaterialAov& aov = material.aovs[k];
    bool textured;
    const Vec3 v = in.raw(aov.value, &textured);
    // A register holds what the socket holds; a texture's colour into the Value input becomes
    // its luminance (Blender's implicit conversion).
    const bool texture_color = aov.value.reg < 0 && aov.value.texture >= 0 &&
                               aov.value.channel == TextureChannel::kColor && textured;
    out[k] = aov.color ? v : Vec3(texture_color ? luminance(v) : v.x, 0.0f, 0.0f);
  }
}

Vec3 emitted_radiance(const Material& material, const SurfaceInteraction& si,
                      const TextureSet* textures, const Vec3* wo) {
  if (!material.may_emit()) return Vec3(0.0f);
  InputReader in{si.uv, textures};
  ProgramRun run(material, si, wo ? *wo : si.ng, nullptr, textures, ShadeRay{});
  in.registers = run.registers();
  Vec3 e(0.0f);
  for (const Closure& c : material.closures) {
    if (c.type != ClosureType::kEmission && c.type != ClosureType::kPrincipled &&
        c.type != ClosureType::kPrincipledV2)
      continue;
    float w = closure_weight(c, in);
    const ClosureReader r{in, c};
    if (c.type == ClosureType::kEmission) {
      e += r.color(Param::kColor) * (w * std::max(r.scalar(Param::kStrength), 0.0f));
    } else if (c.type == ClosureType::kPrincipledV2) {
      // Seen from wo (else head-on) through the coat, on the interpolated normal.
      const Vec3 n = dot(si.ns, wo ? *wo : si.ng) >= 0.0f ? si.ns : -si.ns;
      PrincipledV2Geometry g;
      g.wo = wo ? *wo : n;
      g.n = n;
      g.coat_n = n;
      e += add_principled_v2(principled_v2_inputs(c, in), w, g, nullptr);
    } else {
      w *= r.unit(Param::kAlpha);
      e += r.color(Param::kEmission) * (w * std::max(r.scalar(Param::kStrength), 0.0f));
    }
  }
  return is_finite(e) ? e : Vec3(0.0f);
}

}  // namespace photon
