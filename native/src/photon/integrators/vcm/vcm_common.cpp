#include "photon/integrators/vcm/vcm_common.h"

#include <cmath>

#include "photon/base/ray_offset.h"
#include "photon/integrators/spectral_path.h"
#include "photon/lights/emitter_set.h"

namespace photon {

VcmMis VcmMis::make(VcmMode mode, float radius, uint64_t light_paths, int max_path_length) {
  VcmMis m;
  m.mode = mode;
  m.use_vc = mode != VcmMode::kPpm;
  m.use_vm = mode != VcmMode::kBpt;
  m.radius = radius;
  m.light_paths = std::max<uint64_t>(light_paths, 1);
  m.max_path_length = max_path_length;
  const double eta =
      kPi * static_cast<double>(radius) * radius * static_cast<double>(m.light_paths);
  m.vm_factor = m.use_vm ? static_cast<float>(eta) : 0.0f;
  m.vc_factor = m.use_vc && eta > 0.0 ? static_cast<float>(1.0 / eta) : 0.0f;
  m.vm_normalization = eta > 0.0 ? static_cast<float>(1.0 / eta) : 0.0f;
  return m;
}

VcmLights::VcmLights(const RenderContext& context, const PhotonFrame& frame,
                     std::vector<std::string>* warnings)
    : frame_(frame) {
  std::vector<double> weights;
  if (context.emitters) {
    for (const Emitter* e : context.emitters->every_light()) {
      const uint8_t f = e->flags();
      if (!(f & kEmitterBidirectional)) {
        if (warnings) warnings->push_back("an emitter VCM cannot sample was left out");
        continue;
      }
      const Vec3 power = e->power(frame.radius);
      const double w = (static_cast<double>(power.x) + power.y + power.z) / 3.0;
      if (!(w > 0.0) || !std::isfinite(w)) continue;
      const size_t i = emitters_.size();
      emitters_.push_back(e);
      flags_.push_back(f);
      weights.push_back(w);
      if (f & kEmitterInfinite)
        infinite_.push_back(i);
      else if (e->kind() == EmitterKind::kSurface)
        surface_ = static_cast<long>(i);
      else if (!(f & kEmitterDeltaPosition))
        lamps_.push_back(i);
    }
  }
  pick_ = Distribution1D(weights);
}

bool hit_at_infinity(const Emitter& e, const PhotonFrame& frame, const Vec3& direction,
                     LightHit* out) {
  out->radiance = e.radiance_at_infinity(direction, true);
  out->distance = INFINITY;
  out->direct_pdf = e.pdf_at_infinity(direction, true);
  out->emission_pdf = out->direct_pdf * scene_disc_pdf(frame);
  out->cos_light = 1.0f;
  return out->direct_pdf > 0.0f && is_finite(out->radiance);
}

Vec3 VcmColours::rgb(const SampledSpectrum& sum) const {
  if (!wl) return Vec3(sum[0], sum[1], sum[2]);
  SpectralTally tally;
  tally.sum = sum;
  return tally.rgb(*wl);
}

float VcmBsdf::pdf_reverse(const Vec3& wo, const Vec3& wi) const {
  if (dot(wi, rgb_->ng()) >= 0.0f) return pdf(wi, wo);
  const Bsdf behind = rgb_->seen_from_behind();
  return spectral_ ? SpectralBsdf(behind, spectral_->wavelengths()).pdf(wi, wo)
                   : behind.pdf(wi, wo);
}

bool VcmBsdf::sample(const Vec3& wo, float u_lobe, Vec2 u, VcmBsdfSample* out) const {
  if (spectral_) {
    SpectralBsdfSample s;
    if (!spectral_->sample(wo, u_lobe, u, kLobeAll, &s)) return false;
    *out = {s.wi, s.weight, s.pdf, s.flags, s.terminate, s.transparent};
    return true;
  }
  BsdfSample s;
  if (!rgb_->sample(wo, u_lobe, u, kLobeAll, &s)) return false;
  *out = {s.wi, rgb_lanes(s.weight), s.pdf, s.flags, false, s.transparent};
  return true;
}

bool vcm_visible(const Accel& accel, const Vec3& p, const Vec3& ng, const Vec3& q, const Vec3& nq) {
  const float scale = accel.length_scale();
  const Vec3 d = q - p;
  const Vec3 a = offset_ray_origin(p, ng, d, scale);
  const Vec3 b = is_black(nq * nq) ? q : offset_ray_origin(q, nq, -d, scale);
  const Vec3 ab = b - a;
  const float len = length(ab);
  if (!(len > 0.0f)) return true;
  Ray ray;
  ray.origin = a;
  ray.direction = ab / len;
  ray.tmin = 0.0f;
  ray.tmax = len * (1.0f - 1e-4f);
  return !accel.occluded(ray, kVisibleShadow);
}

bool vcm_visible_at_infinity(const Accel& accel, const Vec3& p, const Vec3& ng, const Vec3& w) {
  Ray ray;
  ray.origin = offset_ray_origin(p, ng, w, accel.length_scale());
  ray.direction = w;
  ray.tmin = 0.0f;
  ray.tmax = INFINITY;
  return !accel.occluded(ray, kVisibleShadow);
}

}  // namespace photon
