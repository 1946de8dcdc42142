#include "photon/integrators/matte.h"

#include <algorithm>

#include "photon/lights/direct_lighting.h"

namespace photon {

Matte matte_at(const RenderContext& context, const Hit& hit) {
  const uint32_t index = context.accel->scene_instance(hit.instance);
  const std::vector<Instance>& instances = context.scene->instances;
  if (index >= instances.size()) return Matte::kNone;
  const Instance& instance = instances[index];
  if (instance.holdout) return Matte::kHoldout;
  if (instance.shadow_catcher) return Matte::kShadowCatcher;
  return Matte::kNone;
}

Vec3 hold_out_object(ShadingPoint* sp) {
  const Bsdf& bsdf = sp->bsdf;
  Bsdf kept(bsdf.frame().n, bsdf.ng(), bsdf.front_facing());
  Vec3 transparency(0.0f);
  for (int i = 0; i < bsdf.lobe_count(); ++i) {
    const Lobe& lobe = bsdf.lobe(i);
    if (lobe.type != LobeType::kTransparent) continue;
    kept.add(lobe);
    transparency += lobe.weight;
  }
  sp->bsdf = kept;
  sp->emission = Vec3(0.0f);
  sp->holdout = 0.0f;
  return max(Vec3(1.0f) - transparency, Vec3(0.0f));
}

Vec3 shadow_catcher_ratio(const RenderContext& context, const SurfaceInteraction& si,
                          const Vec3& wo, Sampler& sampler) {
  ShadingPoint sp = shade_surface(si, wo, *context.accel, context.textures);
  if (!(sp.bsdf.flags() & (kLobeDiffuse | kLobeGlossy))) {
    Bsdf lambert(sp.bsdf.frame().n, sp.bsdf.ng(), sp.bsdf.front_facing());
    Lobe lobe;
    lobe.type = LobeType::kLambert;
    lobe.weight = Vec3(1.0f);
    lambert.add(lobe);
    sp.bsdf = lambert;
  }
  Vec3 unshadowed;
  const Vec3 shadowed =
      direct_radiance_with_and_without_shadows(context, si, sp.bsdf, wo, sampler, &unshadowed);
  // Unlit points show nothing of the catcher (1); inf / inf from absurd lamps does too.
  auto ratio = [](float with, float without) {
    const float r = without > 0.0f ? with / without : 1.0f;
    return r >= 0.0f ? std::min(r, 1.0f) : 1.0f;
  };
  return {ratio(shadowed.x, unshadowed.x), ratio(shadowed.y, unshadowed.y),
          ratio(shadowed.z, unshadowed.z)};
}

}  // namespace photon
