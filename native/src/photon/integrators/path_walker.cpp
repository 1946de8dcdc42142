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

namespace {

// A power-carrying path through a refraction takes the adjoint BSDF's factor into the sample's
// weight. Russian roulette by the bounce's albedo is drawn before it: the factor is no loss of
// energy but its spreading into a denser medium, and photons through a closed glass object,
// multiplied by 1 / eta^2 and then eta^2, keep their power and their number.
void apply_adjoint(const PathRules& rules, const Bsdf& bsdf, const Vec3& wo, BsdfSample* s) {
  if (rules.adjoint && (s->flags & kLobeTransmission) && !s->transparent)
    s->weight *= bsdf.adjoint_scale(wo, s->wi);
}

// continue_path for a spectral path: the same draws and rules on beta. Q of Russian roulette
// is taken over the wavelengths (beta is 0 at those not in use).
bool continue_spectral_path(const PathRules& rules, const SpectralBsdf& bsdf, const Vec3& wo,
                            Sampler& sampler, PathState* state, BsdfSample* s) {
  const float u_lobe = sampler.get_1d();
  const Vec2 u = sampler.get_2d();
  // The survival number is drawn where the RGB path draws it.
  const float u_survive = rules.roulette == Roulette::kBounceAlbedo ? sampler.get_1d() : 0.0f;
  SpectralBsdfSample ss;
  if (!bsdf.sample(wo, u_lobe, u, rules.continue_lobes, &ss)) return false;
  // A dispersive refraction: only the hero wavelength goes on (its weight is the only one).
  if (ss.terminate) state->wl.terminate_secondary();
  SampledSpectrum weight = ss.weight;
  for (int i = 0; i < spectral::kSpectrumSamples; ++i)
    if (!state->wl.active(i)) weight[i] = state->beta[i] = 0.0f;
  if (is_black(weight)) return false;
  const SampledSpectrum adjoint = rules.adjoint && (ss.flags & kLobeTransmission) && !ss.transparent
                                      ? bsdf.adjoint_scale(wo, ss.wi)
                                      : SampledSpectrum(1.0f);
  switch (rules.roulette) {
    case Roulette::kBounceAlbedo: {
      const float q = std::min(1.0f, max_component(weight));
      if (!(u_survive < q)) return false;
      state->beta = state->beta * weight * adjoint / q;
      break;
    }
    case Roulette::kPathThroughput:
      state->beta *= weight * adjoint;
      if (state->depth >= rules.roulette_depth) {
        const float q = std::min(1.0f, max_component(state->beta));
        if (!(sampler.get_1d() < q)) return false;
        state->beta = state->beta / q;
      }
      break;
    case Roulette::kNone:
      state->beta *= weight * adjoint;
      break;
  }
  s->wi = ss.wi;
  s->pdf = ss.pdf;
  s->flags = ss.flags;
  s->transparent = ss.transparent;
  if (!ss.transparent) state->last_delta = ss.is_delta();
  state->after_glossy = state->after_glossy || !ss.is_delta();
  return true;
}

}  // namespace

bool continue_path(const PathRules& rules, const Bsdf& bsdf, const SpectralBsdf* spectral,
                   const Vec3& wo, Sampler& sampler, PathState* state, BsdfSample* s) {
  if (state->spectral && spectral)
    return continue_spectral_path(rules, *spectral, wo, sampler, state, s);
  const float u_lobe = sampler.get_1d();
  const Vec2 u = sampler.get_2d();
  switch (rules.roulette) {
    case Roulette::kBounceAlbedo: {
      // Jensen 2001 sec. 5.2: survive with the bounce's albedo, q = max channel of f cos / pdf.
      const float u_survive = sampler.get_1d();
      if (!bsdf.sample(wo, u_lobe, u, rules.continue_lobes, s) || is_black(s->weight)) return false;
      const float q = std::min(1.0f, max_component(s->weight));
      if (!(u_survive < q)) return false;
      apply_adjoint(rules, bsdf, wo, s);
      state->throughput = state->throughput * s->weight / q;
      break;
    }
    case Roulette::kPathThroughput: {
      if (!bsdf.sample(wo, u_lobe, u, rules.continue_lobes, s) || is_black(s->weight)) return false;
      apply_adjoint(rules, bsdf, wo, s);
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
      apply_adjoint(rules, bsdf, wo, s);
      state->throughput *= s->weight;
      break;
  }
  // A Transparent pass-through is no bounce for light sampling: shadow rays cross it
  // (render/shadow_ray.h), so emission beyond it was estimated at the last real bounce.
  if (!s->transparent) state->last_delta = s->is_delta();
  state->after_glossy = state->after_glossy || !s->is_delta();
  return true;
}

}  // namespace photon
