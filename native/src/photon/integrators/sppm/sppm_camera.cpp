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
        return true;  // translucent, sheen, velvet: broad lobes
    }
  }
  return false;
}

SppmCameraSample trace_sppm_camera(const RenderContext& context, const Ray& camera_ray,
                                   Sampler& sampler, const PhotonKdTree& photons, float radius,
                                   const SampledWavelengths* wl) {
  CameraWalk walk = camera_render_walk(context);
  walk.visible_point = &is_visible_point;
  walk.spectral = wl != nullptr;
  walk.wavelengths = wl;
  SppmCameraSample out;
  const DiffuseShader at_visible_point = [&](const PathVertex& v, RadianceSample*) {
    out.visible_point = true;
    uint32_t m = 0;
    if (v.spectral) {
      // The photons and the camera path share the iteration's wavelengths. A path whose
      // wavelengths were terminated keeps the hero, its weight times the number in use: the
      // camera path's tally applies that factor for its own termination (its pdfs), a
      // photon's is applied here unless the camera path already did.
      const SpectralVertex& sv = *v.spectral;
      const bool camera_terminated = sv.wl->active_count() < wl->active_count();
      const float hero_factor = camera_terminated ? 1.0f : static_cast<float>(wl->active_count());
      SampledSpectrum phi(0.0f);
      photons.for_each_within(v.si->p, radius, [&](const SppmPhoton& ph) {
        const SampledSpectrum f = sv.bsdf->eval(v.wo, ph.wi) * ph.spectral_beta();
        phi += ph.terminated() ? f * hero_factor : f;
        ++m;
      });
      SpectralTally tally;
      tally.add(sv.beta * phi, *sv.wl);
      out.phi = tally.rgb(*sv.wl);
      out.photons = m;
      return;
    }
    const Bsdf& bsdf = v.shading->bsdf;
    Vec3 phi(0.0f);
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
