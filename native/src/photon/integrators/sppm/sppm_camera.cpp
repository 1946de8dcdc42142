#include "photon/integrators/sppm/sppm_camera.h"

#include <algorithm>

#include "photon/integrators/camera_path.h"

namespace photon {

bool is_visible_point(const Bsdf& bsdf) {
  for (int i = 0; i < bsdf.lobe_count(); ++i) {
    const Lobe& lobe = bsdf.lobe(i);
    const uint8_t flags = lobe.flags();
    if (flags & kLobeDiffuse) return true;
    if (!(flags & kLobeGlossy)) continue;
    switch (lobe.type) {
      case LobeType::kGgxReflection:
      case LobeType::kGgxGlass:
      case LobeType::kGgxRefraction: {
        // An anisotropic lobe is as sharp as its sharper direction.
        const float alpha = lobe.anisotropic() ? std::min(lobe.alpha, lobe.alpha_y) : lobe.alpha;
        if (alpha >= kSppmGlossyAlpha) return true;
        break;
      }
      default:
        return true;  // translucent, sheen: broad lobes
    }
  }
  return false;
}

SppmCameraSample trace_sppm_camera(const RenderContext& context, const Ray& camera_ray,
                                   Sampler& sampler, const PhotonKdTree& photons, float radius) {
  CameraWalk walk = camera_render_walk(context);
  walk.visible_point = &is_visible_point;
  SppmCameraSample out;
  const DiffuseShader at_visible_point = [&](const PathVertex& v, RadianceSample*) {
    out.visible_point = true;
    const Bsdf& bsdf = v.shading->bsdf;
    Vec3 phi(0.0f);
    uint32_t m = 0;
    photons.for_each_within(v.si->p, radius, [&](const SppmPhoton& ph) {
      phi += ph.beta * bsdf.eval(v.wo, ph.wi);
      ++m;
    });
    out.phi = v.throughput * phi;
    out.photons = m;
  };
  RadianceSample r;
  walk_camera_path(context, camera_ray, nullptr, sampler, walk, at_visible_point, &r);
  out.direct = r.direct;
  out.alpha = r.alpha;
  out.holdout = r.holdout;
  return out;
}

}  // namespace photon
