#include "photon/integrators/photon_map/photon_sources.h"

#include "photon/base/sampling.h"

namespace photon {
namespace {

double scalar_power(const Vec3& p) {
  return (static_cast<double>(p.x) + p.y + p.z) / 3.0;
}

}  // namespace

PhotonSources::PhotonSources(const RenderContext& context) : context_(context) {
  const Accel& accel = *context.accel;
  if (accel.instance_count() > 0) {
    center_ = (accel.bounds_min() + accel.bounds_max()) * 0.5f;
    // A floor relative to the scene: an absolute 1 mm spread a 0.1 mm scene's sun and world
    // photons over a disc 100x its size, so almost none landed.
    radius_ = std::max(0.5f * length(accel.bounds_max() - accel.bounds_min()),
                       1e-3f * accel.length_scale());
  }
  if (!is_finite(center_) || !std::isfinite(radius_)) {
    center_ = Vec3(0.0f);
    radius_ = 1.0f;
  }
  targets_ = specular_targets(*context.scene, accel);

  std::vector<double> global_weights, caustic_weights;
  if (accel.instance_count() > 0 && context.emitters) {
    for (const Emitter* e : context.emitters->every_light()) {
      const Vec3 power = e->power(radius_);
      if (!(scalar_power(power) > 0.0) || !is_finite(power)) continue;
      sources_.push_back(e);
      global_weights.push_back(scalar_power(power));
      caustic_weights.push_back(scalar_power(power) * e->coverage(targets_, radius_));
      total_power_ += power;
    }
  }
  global_ = Distribution1D(global_weights);
  if (!targets_.empty()) caustic_ = Distribution1D(caustic_weights);
}

bool PhotonSources::emit_global(Sampler& sampler, EmittedPhoton* out) const {
  float u_rest;
  const size_t k = global_.sample(sampler.get_1d(), &u_rest);
  const Vec2 u_pos = sampler.get_2d(), u_dir = sampler.get_2d();
  if (!sources_[k]->sample_le(PhotonFrame{center_, radius_}, u_rest, u_pos, u_dir, false, out))
    return false;
  out->power = out->power / global_.probability(k);
  out->emitter = sources_[k];
  return is_finite(out->power) && !is_black(out->power);
}

bool PhotonSources::emit_caustic(Sampler& sampler, EmittedPhoton* out) const {
  float u_pick;
  const size_t k = caustic_.sample(sampler.get_1d(), &u_pick);
  const Vec2 u_pos = sampler.get_2d(), u_dir = sampler.get_2d();
  if (!sources_[k]->sample_le_towards(targets_, PhotonFrame{center_, radius_}, u_pick, u_pos, u_dir,
                                      sampler, out))
    return false;
  out->power = out->power / caustic_.probability(k);
  out->emitter = sources_[k];
  return is_finite(out->power) && !is_black(out->power);
}

}  // namespace photon
