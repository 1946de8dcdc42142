#include "photon/lights/direct_lighting.h"

#include <cmath>

#include "photon/lights/emissive_mesh.h"
#include "photon/lights/emitter_set.h"
#include "photon/render/material_eval.h"
#include "photon/render/shadow_ray.h"
#include "photon/render/spectral_bsdf.h"
#include "photon/spectral/rgb_uplift.h"

namespace photon {
namespace {

// A light sample of `e` towards p for direct lighting, with the random numbers it takes.
bool sample_light(const Emitter& e, const Vec3& p, Sampler& sampler, LightSample* ls) {
  return e.sample_li(p, e.draw_li(sampler), nullptr, ls);
}

// Light sampling's solid-angle density of the point of emissive surface `e` a ray hit (0 when
// it is not e's).
float surface_pdf(const Emitter& e, const Hit& hit, const Vec3& wi, const Vec3& ng) {
  LightHit h;
  return e.surface_hit(hit.instance, hit.primitive, hit.t, dot(wi, ng), false, &h) ? h.pdf : 0.0f;
}

// How direct lighting sees colours: in RGB, or at the sampled wavelengths of a spectral path
// (emitters' values converted where they are used: Emitter::spectrum, the illuminant uplift of
// a surface's emission). The RGB instantiation is the RGB renderer's arithmetic, unchanged.
struct RgbColours {
  using Color = Vec3;
  using BsdfType = Bsdf;
  using Sample = BsdfSample;
  static Vec3 zero() { return Vec3(0.0f); }
  const Vec3& emitted(const Emitter&, const Vec3& rgb) const { return rgb; }
  const Vec3& surface(const Vec3& rgb) const { return rgb; }
  // Light `c` after the transparent surfaces a shadow ray crossed let `t` of it through.
  static Vec3 filtered(const Vec3& c, const Vec3& t) { return c * t; }
};

struct SpectralColours {
  using Color = SampledSpectrum;
  using BsdfType = SpectralBsdf;
  using Sample = SpectralBsdfSample;
  const SampledWavelengths& wl;
  static SampledSpectrum zero() { return SampledSpectrum(0.0f); }
  SampledSpectrum emitted(const Emitter& e, const Vec3& rgb) const { return e.spectrum(rgb, wl); }
  SampledSpectrum surface(const Vec3& rgb) const { return spectral::illuminant_at(rgb, wl); }
  // A Transparent closure's colour is a reflectance-like filter (as the BSDF's lobe weights).
  SampledSpectrum filtered(const SampledSpectrum& c, const Vec3& t) const {
    return t.x == 1.0f && t.y == 1.0f && t.z == 1.0f ? c : c * spectral::reflectance_at(t, wl);
  }
};

// Veach 1997, eq. 9.13 with beta = 2. Densities above ~1.8e19 (a light of tiny area seen from
// afar) overflow when squared: then the same weight is taken in ratio form, so it stays 1 for
// the far larger density instead of inf / inf = NaN, which dropped the light sample.
inline float power_heuristic(float f, float g) {
  const float f2 = f * f, g2 = g * g;
  if (std::isfinite(f2 + g2)) return f2 + g2 > 0.0f ? f2 / (f2 + g2) : 0.0f;
  if (!(f > 0.0f) || std::isnan(g)) return 0.0f;
  if (!std::isfinite(f)) return std::isfinite(g) ? 1.0f : 0.5f;
  const float r = g / f;
  return 1.0f / (1.0f + r * r);
}

// What a shadow ray from si towards wi lets through over `distance` (shadow_ray.h): 1 when
// nothing is in the way, 0 when something opaque is, the share transparent surfaces pass.
Vec3 transmittance(const RenderContext& context, const SurfaceInteraction& si, const Vec3& wi,
                   float distance) {
  Ray shadow;
  shadow.origin = offset_ray_origin(si.p, si.ng, wi, context.accel->length_scale());
  shadow.direction = wi;
  shadow.tmax = std::isfinite(distance) ? distance * (1.0f - 1e-4f) : INFINITY;
  return shadow_transmittance(*context.accel, context.textures, shadow);
}

// The same towards a sampled light point. A point on an emissive triangle is scene geometry:
// the shadow ray must stop short of that surface, or it ends inside it and the light occludes
// itself (everywhere the offset exceeds the tmax margin: nearly all light samples).
Vec3 transmittance(const RenderContext& context, const SurfaceInteraction& si,
                   const LightSample& ls) {
  if (!(length_squared(ls.surface_normal) > 0.0f) || !std::isfinite(ls.distance))
    return transmittance(context, si, ls.wi, ls.distance);
  const Ray shadow = shadow_ray_between(si.p, si.ng, si.p + ls.wi * ls.distance, ls.surface_normal,
                                        context.accel->length_scale());
  return shadow_transmittance(*context.accel, context.textures, shadow);
}

// Follows a BSDF-sampled ray from si along wi through the surfaces that let light straight
// through (shadow_ray.h), as a shadow ray would, calling visit(hit, t_from, t_to, t) for each
// surface it meets: `t_from` to `t_to` the stretch of the ray before the surface (distances
// from si.p; t_from 0 on the first), `t` the share of light the surfaces before it let through.
// When the ray leaves the scene, visit(nullptr, t_from, INFINITY, t). Stops at the first opaque
// surface, or after kShadowCrossings transparent ones.
template <class Visit>
void follow_bsdf_ray(const RenderContext& context, const SurfaceInteraction& si, const Vec3& wi,
                     Visit&& visit) {
  const Accel& accel = *context.accel;
  Ray ray;
  ray.origin = offset_ray_origin(si.p, si.ng, wi, accel.length_scale());
  ray.direction = wi;
  Vec3 t(1.0f);
  float t_from = 0.0f;
  for (int crossed = 0;; ++crossed) {
    Hit hit;
    if (!accel.intersect(ray, kVisibleShadow, &hit)) return visit(nullptr, t_from, INFINITY, t);
    const float t_to = crossed == 0 ? hit.t : dot(hit.p - si.p, wi);
    visit(&hit, t_from, t_to, t);
    if (crossed >= kShadowCrossings || !accel.has_transparent_shadows() ||
        !accel.triangle_material(hit.instance, hit.primitive).may_be_transparent())
      return;
    const SurfaceInteraction surface = accel.interaction(hit);
    t *= straight_transmittance(accel, context.textures, surface, wi);
    if (is_black(t)) return;
    ray = ray_past(ray, surface, accel.length_scale());
    t_from = t_to;
  }
}

// f |cos| towards a sampled light direction, and the BSDF's density of sampling it.
template <class B>
auto bsdf_towards(const B& bsdf, const Vec3& wo, const Vec3& wi, uint8_t lobes, float* pdf) {
  const auto f = bsdf.eval(wo, wi, lobes);
  *pdf = bsdf.pdf(wo, wi, lobes);
  return f * std::fabs(dot(bsdf.frame().n, wi));
}

// Light sample `ls` of emitter `e` (or of the emissive meshes), weighted against BSDF sampling.
template <class P>
typename P::Color light_sample_term(const P& colours, const RenderContext& context,
                                    const SurfaceInteraction& si, const typename P::BsdfType& bsdf,
                                    const Vec3& wo, uint8_t lobes, const Emitter& e,
                                    const LightSample& ls) {
  float pdf_bsdf;
  const typename P::Color f_cos = bsdf_towards(bsdf, wo, ls.wi, lobes, &pdf_bsdf);
  if (is_black(f_cos)) return P::zero();
  const Vec3 t = transmittance(context, si, ls);
  if (is_black(t)) return P::zero();
  const float w = ls.pdf > 0.0f ? power_heuristic(ls.pdf, pdf_bsdf) : 1.0f;
  return colours.filtered(f_cos * colours.emitted(e, ls.weight) * w, t);
}

// One BSDF sample's light, weighted against light sampling of the emitter(s) it can reach:
// a lamp, found analytically. `light_pmf` is the probability that light sampling picks it (1
// when every emitter is sampled).
template <class P>
typename P::Color bsdf_sample_term(const P& colours, const RenderContext& context,
                                   const SurfaceInteraction& si, const Emitter& e,
                                   const typename P::Sample& bs, float light_pmf) {
  switch (e.kind()) {
    case EmitterKind::kLamp: {
      LightHit h;
      if (!e.eval_li(si.p, bs.wi, &h)) return P::zero();
      const Vec3 t = transmittance(context, si, bs.wi, h.distance);
      if (is_black(t)) return P::zero();
      return colours.filtered(
          colours.emitted(e, h.radiance) * bs.weight * power_heuristic(bs.pdf, light_pmf * h.pdf),
          t);
    }
    case EmitterKind::kSurface:  // found by the scene's BVH: emissive_hit_term
    case EmitterKind::kWorld:    // found by rays leaving the scene
      break;
  }
  return P::zero();
}

// The world along a BSDF-sampled direction, if nothing occludes it. An environment map's light
// sample (and a world's through portals) covers the same directions: weighted against it by
// MIS; a uniform world without portals has no light sample, so the BSDF sample takes all of it.
template <class P>
typename P::Color world_bsdf_term(const P& colours, const RenderContext& context,
                                  const SurfaceInteraction& si, const Emitter& e,
                                  const typename P::Sample& bs) {
  const Vec3 rgb = e.radiance_at_infinity(bs.wi);
  if (is_black(rgb)) return P::zero();
  const Vec3 t = transmittance(context, si, bs.wi, INFINITY);
  if (is_black(t)) return P::zero();
  const typename P::Color le = colours.emitted(e, rgb);
  const float pdf_light = e.pdf_li_at_infinity(si.p, bs.wi);
  return colours.filtered(
      pdf_light > 0.0f ? le * bs.weight * power_heuristic(bs.pdf, pdf_light) : le * bs.weight, t);
}

// The emissive surfaces a BSDF-sampled ray meets (the first it hits, and those behind
// transparent ones), weighted against light sampling with density `surface_pdf(hit, light_si)`.
template <class P, class SurfacePdf>
typename P::Color emissive_hit_term(const P& colours, const RenderContext& context,
                                    const SurfaceInteraction& si, const typename P::Sample& bs,
                                    SurfacePdf&& surface_pdf) {
  typename P::Color l = P::zero();
  follow_bsdf_ray(context, si, bs.wi, [&](const Hit* hit, float, float, const Vec3& t) {
    if (!hit) return;
    const SurfaceInteraction light_si = context.accel->interaction(*hit);
    const float pdf_light = surface_pdf(*hit, light_si);
    if (!(pdf_light > 0.0f)) return;
    l += colours.filtered(
        colours.surface(emitted_radiance(*light_si.mat, light_si, context.textures)) * bs.weight *
            power_heuristic(bs.pdf, pdf_light),
        t);
  });
  return l;
}

// Every emitter sampled at every shading point (EmitterSet::every_light()).
template <class P>
typename P::Color every_light_radiance(const P& colours, const RenderContext& context,
                                       const SurfaceInteraction& si,
                                       const typename P::BsdfType& bsdf, const Vec3& wo,
                                       Sampler& sampler, uint8_t lobes) {
  typename P::Color l = P::zero();
  typename P::Sample bs;
  for (const Emitter* e : context.emitters->every_light()) {
    LightSample ls;
    if (sample_light(*e, si.p, sampler, &ls))
      l += light_sample_term(colours, context, si, bsdf, wo, lobes, *e, ls);
    if (!e->has_area()) continue;
    // BSDF sample, weighted against the light sample.
    const float u_lobe = sampler.get_1d();
    const Vec2 u = sampler.get_2d();
    if (!bsdf.sample(wo, u_lobe, u, lobes, &bs)) continue;
    switch (e->kind()) {
      case EmitterKind::kLamp:
        l += bsdf_sample_term(colours, context, si, *e, bs, 1.0f);
        break;
      case EmitterKind::kSurface:
        l += emissive_hit_term(colours, context, si, bs,
                               [&](const Hit& hit, const SurfaceInteraction& h) {
                                 return surface_pdf(*e, hit, bs.wi, h.ng);
                               });
        break;
      case EmitterKind::kWorld:
        l += world_bsdf_term(colours, context, si, *e, bs);
        break;
    }
  }
  return l;
}

// Many emitters: suns one by one, one emitter picked by the light tree, one BSDF sample
// weighted against it (the tree's pmf times the emitter's density is the light strategy's
// density, Conty Estevez & Kulla 2018 sec. 5.1), and the world.
template <class P>
typename P::Color tree_radiance(const P& colours, const RenderContext& context,
                                const SurfaceInteraction& si, const typename P::BsdfType& bsdf,
                                const Vec3& wo, Sampler& sampler, uint8_t lobes) {
  const EmitterSet& set = *context.emitters;
  const LightTree& tree = set.tree();
  typename P::Color l = P::zero();
  for (const Emitter* e : set.distant()) {
    LightSample ls;
    if (sample_light(*e, si.p, sampler, &ls))
      l += light_sample_term(colours, context, si, bsdf, wo, lobes, *e, ls);
  }
  if (!tree.empty()) {
    const float u_pick = sampler.get_1d();
    uint32_t index;
    float pmf;
    LightSample ls;
    if (tree.sample(si.p, u_pick, &index, &pmf)) {
      if (sample_light(set.tree_emitter(index), si.p, sampler, &ls)) {
        ls.weight = ls.weight / pmf;
        ls.pdf *= pmf;
        l += light_sample_term(colours, context, si, bsdf, wo, lobes, set.tree_emitter(index), ls);
      }
    } else {
      sampler.get_2d();  // keep the sampler's dimensions aligned between shading points
    }
    typename P::Sample bs;
    const float u_lobe = sampler.get_1d();
    const Vec2 u = sampler.get_2d();
    if (bsdf.sample(wo, u_lobe, u, lobes, &bs)) {
      // One scene ray (continued through transparent surfaces): it finds the emissive
      // triangles the sample hits and bounds the lamps that can be seen along it (lamps do not
      // occlude each other, as with every-light sampling; the geometry does).
      const EmissiveMeshes* emissive = set.emissive();
      const float margin = 1e-4f * context.accel->length_scale();
      follow_bsdf_ray(
          context, si, bs.wi, [&](const Hit* hit, float t_from, float t_to, const Vec3& t) {
            Ray lamp_ray;
            lamp_ray.origin = si.p;
            lamp_ray.direction = bs.wi;
            lamp_ray.tmax = hit ? t_to / (1.0f - 1e-4f) + margin : INFINITY;
            tree.for_each_hit(lamp_ray, [&](uint32_t i) {
              LightHit h;
              if (!set.tree_emitter(i).eval_li(si.p, bs.wi, &h)) return;
              if (hit && t_to < h.distance * (1.0f - 1e-4f)) return;  // behind the surface
              // Before the last transparent surface crossed: counted with the stretch before it.
              if (t_from > 0.0f && !(t_from < h.distance * (1.0f - 1e-4f))) return;
              const float pmf_i = tree.pmf(si.p, i);
              if (pmf_i > 0.0f)
                l += colours.filtered(colours.emitted(set.tree_emitter(i), h.radiance) * bs.weight *
                                          power_heuristic(bs.pdf, pmf_i * h.pdf),
                                      t);
            });
            const long tri = hit && emissive ? emissive->find(hit->instance, hit->primitive) : -1;
            if (tri >= 0) {
              const SurfaceInteraction light_si = context.accel->interaction(*hit);
              const uint32_t i = set.triangle_entry(static_cast<size_t>(tri));
              const float pdf_light =
                  tree.pmf(si.p, i) * surface_pdf(set.tree_emitter(i), *hit, bs.wi, light_si.ng);
              if (pdf_light > 0.0f)
                l += colours.filtered(
                    colours.surface(emitted_radiance(*light_si.mat, light_si, context.textures)) *
                        bs.weight * power_heuristic(bs.pdf, pdf_light),
                    t);
            }
          });
    }
  }
  if (const Emitter* world = set.world()) {
    LightSample ls;
    if (sample_light(*world, si.p, sampler, &ls))
      l += light_sample_term(colours, context, si, bsdf, wo, lobes, *world, ls);
    typename P::Sample bs;
    const float u_lobe = sampler.get_1d();
    const Vec2 u = sampler.get_2d();
    if (bsdf.sample(wo, u_lobe, u, lobes, &bs))
      l += world_bsdf_term(colours, context, si, *world, bs);
  }
  return l;
}

template <class P>
typename P::Color direct_radiance_in(const P& colours, const RenderContext& context,
                                     const SurfaceInteraction& si, const typename P::BsdfType& bsdf,
                                     const Vec3& wo, Sampler& sampler, uint8_t lobes) {
  lobes &= kLobeDiffuse | kLobeGlossy;  // delta lobes reach lights by ray tracing
  if (!(bsdf.flags() & lobes)) return P::zero();
  const typename P::Color l =
      context.emitters->use_tree()
          ? tree_radiance(colours, context, si, bsdf, wo, sampler, lobes)
          : every_light_radiance(colours, context, si, bsdf, wo, sampler, lobes);
  return is_finite(l) ? l : P::zero();
}

}  // namespace

Vec3 direct_radiance(const RenderContext& context, const SurfaceInteraction& si, const Bsdf& bsdf,
                     const Vec3& wo, Sampler& sampler, uint8_t lobes) {
  return direct_radiance_in(RgbColours{}, context, si, bsdf, wo, sampler, lobes);
}

SampledSpectrum direct_radiance(const RenderContext& context, const SurfaceInteraction& si,
                                const SpectralBsdf& bsdf, const Vec3& wo, Sampler& sampler,
                                uint8_t lobes) {
  return direct_radiance_in(SpectralColours{bsdf.wavelengths()}, context, si, bsdf, wo, sampler,
                            lobes);
}

Vec3 direct_radiance_with_and_without_shadows(const RenderContext& context,
                                              const SurfaceInteraction& si, const Bsdf& bsdf,
                                              const Vec3& wo, Sampler& sampler, Vec3* unshadowed) {
  constexpr uint8_t kLobes = kLobeDiffuse | kLobeGlossy;
  Vec3 shadowed(0.0f), free(0.0f);
  auto add = [&](const Vec3& contribution, const Vec3& transmitted) {
    if (!is_finite(contribution)) return;
    free += contribution;
    if (!is_black(transmitted)) shadowed += contribution * transmitted;
  };
  auto light_term = [&](const LightSample& ls) {
    float pdf_bsdf;
    const Vec3 f_cos = bsdf_towards(bsdf, wo, ls.wi, kLobes, &pdf_bsdf);
    if (!is_black(f_cos)) add(f_cos * ls.weight, transmittance(context, si, ls));
  };
  const EmitterSet& set = *context.emitters;
  const Emitter* world = nullptr;
  if (!set.use_tree()) {
    for (const Emitter* e : set.every_light()) {
      if (e->kind() == EmitterKind::kWorld) {
        world = e;
        continue;
      }
      LightSample ls;
      if (sample_light(*e, si.p, sampler, &ls)) light_term(ls);
    }
  } else {
    for (const Emitter* e : set.distant()) {
      LightSample ls;
      if (sample_light(*e, si.p, sampler, &ls)) light_term(ls);
    }
    if (!set.tree().empty()) {
      uint32_t index;
      float pmf;
      LightSample ls;
      if (set.tree().sample(si.p, sampler.get_1d(), &index, &pmf)) {
        if (sample_light(set.tree_emitter(index), si.p, sampler, &ls)) {
          ls.weight = ls.weight / pmf;
          light_term(ls);
        }
      } else {
        sampler.get_2d();
      }
    }
    world = set.world();
  }
  if (world && !(world->flags() & kEmitterBsdfSampledOnly)) {
    // An environment map by light sampling alone, as the lamps (its density is positive in
    // every direction, environment.h).
    LightSample ls;
    if (sample_light(*world, si.p, sampler, &ls)) light_term(ls);
  } else if (world) {
    BsdfSample bs;
    const float u_lobe = sampler.get_1d();
    const Vec2 u = sampler.get_2d();
    if (bsdf.sample(wo, u_lobe, u, kLobes, &bs))
      add(world->radiance_at_infinity(bs.wi) * bs.weight,
          transmittance(context, si, bs.wi, INFINITY));
  }
  *unshadowed = free;
  return shadowed;
}

Vec3 direct_irradiance(const RenderContext& context, const SurfaceInteraction& si,
                       Sampler& sampler) {
  // A Lambertian BSDF of albedo pi has f = 1, so its reflected radiance is the irradiance.
  Bsdf lambert(si.ns, si.ng, true);
  Lobe lobe;
  lobe.type = LobeType::kLambert;
  lobe.weight = Vec3(kPi);
  lambert.add(lobe);
  return direct_radiance(context, si, lambert, si.ns, sampler);
}

}  // namespace photon
