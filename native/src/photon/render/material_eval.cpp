#include "photon/render/material_eval.h"

#include "photon/scene/material_params.h"

namespace photon {
namespace {

constexpr float kWeightCutoff = 1e-5f;  // closures below this weight are skipped (Cycles: 1e-5)

// A texture lookup, unclamped (non-finite values already read as 0), or the constant.
struct InputReader {
  Vec2 uv;
  const TextureSet* textures;

  Vec3 raw(const Input& in, bool* textured) const {
    *textured = false;
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
    return std::clamp(in.channel == TextureChannel::kAlpha ? v.x : luminance(v), r.lo, r.hi);
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

// Cycles 3.4 Principled v1 (intern/cycles/kernel/svm/closure.h, PrincipledBsdfNode::expand):
// alpha mixes with a transparent BSDF; diffuse (Burley) weighted by (1 - metallic)(1 -
// transmission); a GGX specular layer with Schlick F0 = lerp(0.08 specular tint, base,
// metallic); glass weighted by transmission (1 - metallic) tinted by the base colour; a
// clearcoat layer of weight 0.25 clearcoat with F0 = 0.04.
void add_principled(const Closure& c, float w, const InputReader& reader, ShadingPoint* out) {
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
  if (diffuse_weight > 0.0f) {
    Lobe d;
    d.type = LobeType::kBurleyDiffuse;
    d.weight = base * (w * diffuse_weight);
    d.roughness = roughness;
    out->bsdf.add(d);
  }
  const float final_transmission = transmission * (1.0f - metallic);
  if (specular > 0.0f || metallic > 0.0f) {
    const float lum = luminance(base);
    const Vec3 hue = lum > 0.0f ? base / lum : Vec3(1.0f);
    const Vec3 tint = lerp(Vec3(1.0f), hue, in.unit(Param::kSpecularTint));
    Lobe s;
    s.type = LobeType::kGgxReflection;
    s.weight = Vec3(w * (1.0f - final_transmission));
    s.alpha = roughness * roughness;
    s.fresnel = FresnelMode::kSchlick;
    s.f0 = lerp(tint * (0.08f * specular), base, metallic);
    out->bsdf.add(s);
  }
  if (final_transmission > 0.0f) {
    Lobe g;
    g.type = LobeType::kGgxGlass;
    g.weight = base * (w * final_transmission);
    g.alpha = roughness * roughness;
    g.ior = ior;
    g.fresnel = FresnelMode::kDielectric;
    out->bsdf.add(g);
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
    out->bsdf.add(cc);
  }
}

void add_closure(const Closure& c, float w, const InputReader& reader, ShadingPoint* out) {
  if (c.type == ClosureType::kPrincipled) return add_principled(c, w, reader, out);
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
  switch (c.type) {
    case ClosureType::kDiffuse:
      l.type = LobeType::kLambert;
      break;
    case ClosureType::kGlossy:
      l.type = LobeType::kGgxReflection;
      l.fresnel = FresnelMode::kNone;
      break;
    case ClosureType::kGlass:
      l.type = LobeType::kGgxGlass;
      l.fresnel = FresnelMode::kDielectric;
      break;
    case ClosureType::kRefraction:
      l.type = LobeType::kGgxRefraction;
      l.fresnel = FresnelMode::kDielectric;
      break;
    case ClosureType::kTransparent:
      l.type = LobeType::kTransparent;
      break;
    case ClosureType::kTranslucent:
      l.type = LobeType::kTranslucent;
      break;
    default:
      return;
  }
  out->bsdf.add(l);
}

}  // namespace

const char* input_label(ClosureType type, Param p) {
  return param_spec(type, p).sockets[0];
}

ShadingPoint shade_surface(const SurfaceInteraction& si, const Vec3& wo, const Accel& accel,
                           const TextureSet* textures) {
  ShadingPoint out;
  const Material& m = si.mat ? *si.mat : Scene::default_material();
  const InputReader in{si.uv, textures};
  Vec3 ns = si.ns;
  for (const Closure& c : m.closures)
    if (c.normal.texture >= 0) {  // one shading normal per point: the first normal map
      ns = apply_normal_map(c.normal, si, accel, in);
      break;
    }
  const bool front = dot(si.ng, wo) >= 0.0f;
  out.bsdf = front ? Bsdf(ns, si.ng, true) : Bsdf(-ns, -si.ng, false);
  for (const Closure& c : m.closures) {
    const float w = closure_weight(c, in);
    if (w >= kWeightCutoff) add_closure(c, w, in, &out);
  }
  if (!is_finite(out.emission)) out.emission = Vec3(0.0f);
  out.holdout = std::min(out.holdout, 1.0f);  // Add Shader sums may exceed 1
  return out;
}

Vec3 emitted_radiance(const Material& material, const SurfaceInteraction& si,
                      const TextureSet* textures) {
  if (!material.may_emit()) return Vec3(0.0f);
  const InputReader in{si.uv, textures};
  Vec3 e(0.0f);
  for (const Closure& c : material.closures) {
    if (c.type != ClosureType::kEmission && c.type != ClosureType::kPrincipled) continue;
    float w = closure_weight(c, in);
    const ClosureReader r{in, c};
    if (c.type == ClosureType::kEmission) {
      e += r.color(Param::kColor) * (w * std::max(r.scalar(Param::kStrength), 0.0f));
    } else {
      w *= r.unit(Param::kAlpha);
      e += r.color(Param::kEmission) * (w * std::max(r.scalar(Param::kStrength), 0.0f));
    }
  }
  return is_finite(e) ? e : Vec3(0.0f);
}

}  // namespace photon
