#include "photon/integrators/path_walker.h"

#include <algorithm>

namespace photon {

uint32_t visibility_after(uint8_t flags) {
  if (flags & kLobeTransmission) return kVisibleTransmission;
  if (flags & kLobeDiffuse) return kVisibleDiffuse;
  return kVisibleGlossy;
}

void count_bounce(const BsdfSample& s, PathState* state) {
  const uint8_t flags = s.flags;
  if (s.transparent)
    ++state->transparent_depth;
  else if (flags & kLobeReflection)
    ++((flags & kLobeDiffuse) ? state->diffuse_depth : state->glossy_depth);
  else
    ++state->transmission_depth;
}

void spawn_ray(const SurfaceInteraction& si, const Vec3& wi, float length_scale, Ray* ray) {
  ray->origin = offset_ray_origin(si.p, si.ng, wi, length_scale);
  ray->direction = wi;
  ray->tmin = 0.0f;
  ray->tmax = INFINITY;
}

bool continue_path(const PathRules& rules, const Bsdf& bsdf, const Vec3& wo, Sampler& sampler,
                   PathState* state, BsdfSample* s) {
  const float u_lobe = sampler.get_1d();
  const Vec2 u = sampler.get_2d();
  switch (rules.roulette) {
    case Roulette::kBounceAlbedo: {
      // Jensen 2001 sec. 5.2: survive with the bounce's albedo, q = max channel of f cos / pdf.
      const float u_survive = sampler.get_1d();
      if (!bsdf.sample(wo, u_lobe, u, rules.continue_lobes, s) || is_black(s->weight)) return false;
      const float q = std::min(1.0f, max_component(s->weight));
      if (!(u_survive < q)) return false;
      state->throughput = state->throughput * s->weight / q;
      break;
    }
    case Roulette::kPathThroughput: {
      if (!bsdf.sample(wo, u_lobe, u, rules.continue_lobes, s) || is_black(s->weight)) return false;
      state->throughput *= s->weight;
      // Arvo & Kirk 1990: survive with q = max channel of the path throughput, weight / q.
      if (state->depth >= rules.roulette_depth) {
        const float q = std::min(1.0f, max_component(state->throughput));
        if (!(sampler.get_1d() < q)) return false;
        state->throughput = state->throughput / q;
      }
      break;
    }
    case Roulette::kNone:
      if (!bsdf.sample(wo, u_lobe, u, rules.continue_lobes, s) || is_black(s->weight)) return false;
      state->throughput *= s->weight;
      break;
  }
  state->last_delta = s->is_delta();
  state->after_glossy = state->after_glossy || !s->is_delta();
  return true;
}

}  // namespace photon
