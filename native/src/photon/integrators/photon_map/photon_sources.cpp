#include "photon/integrators/photon_map/photon_sources.h"

#include "photon/base/sampling.h"

namespace photon {
namespace {

double scalar_power(const Vec3& p) { return (static_cast<double>(p.x) + p.y + p.z) / 3.0; }

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
  auto add = [&](Kind kind, size_t light, const Vec3& power, float coverage) {
    if (!(scalar_power(power) > 0.0) || !is_finite(power)) return;
    sources_.push_back({kind, light});
    global_weights.push_back(scalar_power(power));
    caustic_weights.push_back(scalar_power(power) * coverage);
    total_power_ += power;
  };
  if (accel.instance_count() > 0) {
    const LightSet& lights = *context.lights;
    for (size_t i = 0; i < lights.size(); ++i)
      add(Kind::kLight, i, lights.power(i, radius_), lights.coverage(i, targets_, radius_));
    if (context.emissive && !context.emissive->empty()) {
      // Emissive meshes aim at targets from their centre; a coarse share is enough, the
      // photons' power corrects for it.
      add(Kind::kEmissive, 0, context.emissive->power(), targets_.empty() ? 0.0f : 0.5f);
    }
    // A uniform world: every direction, through a disc covering the scene: 4 pi * pi R^2 * L.
    const Vec3 world = max(context.scene->world.color, Vec3(0.0f));
    if (!is_black(world)) add(Kind::kWorld, 0, world * (4.0f * kPi * kPi * radius_ * radius_), 0.0f);
  }
  global_ = Distribution1D(global_weights);
  if (!targets_.empty()) caustic_ = Distribution1D(caustic_weights);
}

bool PhotonSources::emit_global(Sampler& sampler, EmittedPhoton* out) const {
  float u_rest;
  const size_t k = global_.sample(sampler.get_1d(), &u_rest);
  const Vec2 u_pos = sampler.get_2d(), u_dir = sampler.get_2d();
  const Source& s = sources_[k];
  switch (s.kind) {
    case Kind::kLight:
      context_.lights->emit(s.light, center_, radius_, u_pos, u_dir, out);
      break;
    case Kind::kEmissive:
      context_.emissive->emit(u_rest, u_pos, u_dir, &out->ray, &out->power);
      break;
    case Kind::kWorld: {
      // Travelling along d, entering through a disc perpendicular to d that covers the scene.
      const Vec3 d = sample_uniform_sphere(u_dir);
      const Frame f(d);
      const Vec2 q = sample_concentric_disk(u_pos);
      out->ray.origin = center_ + (f.t * q.x + f.b * q.y) * radius_ - d * (2.0f * radius_);
      out->ray.direction = d;
      out->ray.tmin = 0.0f;
      out->ray.tmax = INFINITY;
      out->power = context_.scene->world.color * (4.0f * kPi * kPi * radius_ * radius_);
      break;
    }
  }
  out->power = out->power / global_.probability(k);
  return is_finite(out->power) && !is_black(out->power);
}

bool PhotonSources::emit_caustic(Sampler& sampler, EmittedPhoton* out) const {
  float u_pick;
  const size_t k = caustic_.sample(sampler.get_1d(), &u_pick);
  const Vec2 u_pos = sampler.get_2d(), u_dir = sampler.get_2d();
  const Source& s = sources_[k];
  bool ok = false;
  if (s.kind == Kind::kLight) {
    ok = context_.lights->emit_towards(s.light, targets_, center_, radius_, u_pick, u_pos, u_dir,
                                       out);
  } else if (s.kind == Kind::kEmissive) {
    // A point by power, then a direction to a target; two-sided emission sees |cos|.
    Vec3 q, n;
    const size_t tri = context_.emissive->pick_point(u_pick, u_pos, &q, &n);
    Vec3 d;
    float pdf;
    if (ConeMixture(q, targets_).sample(sampler.get_1d(), u_dir, &d, &pdf)) {
      const EmissiveTriangle& t = context_.emissive->triangle(tri);
      const float cos_n = std::fabs(dot(d, n));
      out->ray.origin = offset_ray_origin(q, n, d, context_.accel->length_scale());
      out->ray.direction = d;
      out->ray.tmin = 0.0f;
      out->ray.tmax = INFINITY;
      out->power = t.radiance * (cos_n * t.area / (context_.emissive->pick_probability(tri) * pdf));
      ok = cos_n > 0.0f;
    }
  }
  if (!ok) return false;
  out->power = out->power / caustic_.probability(k);
  return is_finite(out->power) && !is_black(out->power);
}

}  // namespace photon
