// The one path walker of the renderer: camera paths, final-gather rays, photons, radiosity
// shooting rays and irradiance-cache placement all run this loop. The walker owns tracing the
// segment, the depth limit, sampling the lobe that continues the path, Russian roulette,
// the ray-visibility class of the next segment and spawning the next ray off the surface; a
// caller only says what happens at a vertex (a visitor, below).
//
// Russian roulette (Arvo & Kirk 1990, "Particle Transport and Image Synthesis"): a path
// survives a vertex with probability q and its weight is divided by q, so the estimator stays
// unbiased and only its variance changes. Two rules, by the direction the path carries:
//  - kPathThroughput, for paths carrying importance from the camera (camera paths, final-gather
//    rays): from vertex `roulette_depth` on, q = min(1, max channel of the path throughput
//    including this vertex's BSDF weight) (pbrt-v4 sec. 13.1.5 / 14.1.5, "beta"); the first
//    bounces always continue, since they carry most of the image. The survival number is drawn
//    after the lobe sample, and only when roulette applies.
//  - kBounceAlbedo, for paths carrying power from the lights (photons, radiosity shooting):
//    at every vertex, q = min(1, max channel of this bounce's weight f cos / pdf), so a photon's
//    power never grows (Jensen 2001 sec. 5.2; pbrt-v3's SPPM photon pass). The lobe and the
//    survival numbers are drawn together before the lobe sample.
//  - kNone: no roulette (irradiance-cache placement, which must reach every point the camera
//    can shade, not a random subset of them).
//
// Specular chains: `continue_lobes` are the lobes a path continues through (camera paths and
// final gathers: glossy and specular, the diffuse ones being the integrator's estimate; photons
// every lobe, caustic photons and cache placement only delta lobes). No lobe is sampled at a
// vertex of depth >= `max_depth`. Camera paths keep camera visibility through Transparent BSDFs
// (a straight delta transmission), as Cycles' transparent bounces do; every other segment gets
// the visibility class of the lobe it was sampled from (visibility_after).
#pragma once

#include "photon/base/ray_offset.h"
#include "photon/integrators/integrator.h"
#include "photon/render/bsdf.h"
#include "photon/render/spectral_bsdf.h"

namespace photon {

enum class Roulette : uint8_t { kNone, kPathThroughput, kBounceAlbedo };

struct PathRules {
  int max_depth = 8;  // no lobe is sampled at vertices of this depth or deeper
  uint8_t continue_lobes = kLobeGlossy | kLobeSpecular;
  Roulette roulette = Roulette::kPathThroughput;
  int roulette_depth = 2;                     // kPathThroughput: first vertex depth with roulette
  bool transparent_keeps_visibility = false;  // camera paths through Transparent BSDFs
  // Paths that carry power: each refraction multiplies by Bsdf::adjoint_scale.
  bool adjoint = false;
};

// Rules of the paths that carry importance from the camera (camera paths, final gathers).
inline PathRules importance_rules(int max_depth) {
  PathRules r;
  r.max_depth = max_depth;
  return r;
}

// Rules of the paths that carry power from the lights (photons, radiosity shooting).
inline PathRules power_rules(int max_depth, uint8_t continue_lobes) {
  PathRules r;
  r.max_depth = max_depth;
  r.continue_lobes = continue_lobes;
  r.roulette = Roulette::kBounceAlbedo;
  r.adjoint = true;
  return r;
}

// Where a path stands. `throughput` is the camera-path weight or the photon's power; in
// spectral mode `beta` holds it at the wavelengths `wl` instead (wavelengths not in use, or
// terminated by dispersion, have beta 0).
struct PathState {
  Ray ray;
  uint32_t mask = kVisibleCamera;  // visibility class of the current segment
  Vec3 throughput{1.0f};
  bool spectral = false;
  SampledWavelengths wl;
  SampledSpectrum beta{1.0f};
  int depth = 0;  // bounces before the current segment's end
  // The bounces of `depth` by kind, as Cycles counts them for the Light Path node: reflections
  // off diffuse lobes, other reflections (glossy or mirror), transmissions, and straight
  // pass-throughs (Transparent BSDF, shadow catchers), which Cycles' Ray Depth leaves out.
  int diffuse_depth = 0, glossy_depth = 0, transmission_depth = 0, transparent_depth = 0;
  bool after_glossy = false;  // a rough (non-delta) lobe was sampled on the way
  // The last sampled lobe was delta (or there was none yet); Transparent pass-throughs leave
  // it as it was, since shadow rays see through them.
  bool last_delta = true;
  bool see_through = true;  // only Transparent pass-throughs since the path began

  bool black() const { return spectral ? is_black(beta) : is_black(throughput); }
  // Spectral mode: starts at wavelengths `w` with weight `b` at each one in use (0 elsewhere).
  void start_spectral(const SampledWavelengths& w, const SampledSpectrum& b) {
    spectral = true;
    wl = w;
    for (int i = 0; i < spectral::kSpectrumSamples; ++i) beta[i] = w.active(i) ? b[i] : 0.0f;
  }
};

// What the visitor decides at a vertex.
struct VertexStep {
  enum Kind : uint8_t { kStop, kPassThrough, kScatter };
  Kind kind = kStop;
  const Bsdf* bsdf = nullptr;  // kScatter: the BSDF to sample (kept alive by the visitor)
  // kScatter of a spectral path: the same BSDF at the path's wavelengths (kept alive too).
  const SpectralBsdf* spectral = nullptr;

  static VertexStep stop() { return {}; }
  static VertexStep pass_through() { return {kPassThrough, nullptr, nullptr}; }
  static VertexStep scatter(const Bsdf& bsdf, const SpectralBsdf* spectral = nullptr) {
    return {kScatter, &bsdf, spectral};
  }
};

// The ray visibility class of the next segment after a sampled lobe (Cycles' ray types).
uint32_t visibility_after(uint8_t lobe_flags);

// Adds a sampled bounce to the path's per-kind depths.
void count_bounce(const BsdfSample& sample, PathState* state);

// Moves `ray` on to start at `si` in direction `wi`, offset off the surface by the scene's
// length scale (ray_offset.h).
void spawn_ray(const SurfaceInteraction& si, const Vec3& wi, float length_scale, Ray* ray);

// Samples the lobe that continues the path at a vertex of `bsdf` seen from `wo` and applies
// Russian roulette; on success updates the throughput and the chain flags of `state` (not yet
// its ray) and returns the sample. False ends the path. A spectral path samples `spectral`
// (the same BSDF at its wavelengths) with the same random numbers, updates beta, and
// terminates its secondary wavelengths after a dispersive refraction; `sample`'s weight is then
// not set.
bool continue_path(const PathRules& rules, const Bsdf& bsdf, const SpectralBsdf* spectral,
                   const Vec3& wo, Sampler& sampler, PathState* state, BsdfSample* sample);

// The walk. `state` holds the first ray, its visibility and the initial throughput. With
// `first`, the first segment's hit is already traced (camera rays are traced in batches).
//
// The visitor provides:
//   bool segment(const PathState&, bool found, const Hit&)   after each segment is traced;
//       false ends the path (a lamp was met). The path also ends when nothing was found.
//   VertexStep vertex(PathState&, const Hit&, const SurfaceInteraction&)   what the vertex does;
//       it may scale the throughput (e.g. a shadow catcher's filter).
//   void scattered(const PathState&, bool continues)   after a kScatter vertex, with the
//       outcome of sampling and roulette (the throughput is the continuing one when true).
template <typename Visitor>
void walk_path(const RenderContext& context, const PathRules& rules, PathState* state,
               Sampler& sampler, Visitor& visitor, const CameraHit* first = nullptr) {
  const float length_scale = context.accel->length_scale();
  for (;; ++state->depth) {
    Hit hit;
    bool found;
    if (first && state->depth == 0) {
      found = first->found;
      if (found) hit = first->hit;
    } else {
      found = context.accel->intersect(state->ray, state->mask, &hit);
    }
    if (!visitor.segment(*state, found, hit) || !found) return;
    const SurfaceInteraction si = context.accel->interaction(hit);
    const VertexStep step = visitor.vertex(*state, hit, si);
    if (step.kind == VertexStep::kStop) return;
    if (step.kind == VertexStep::kPassThrough) {
      // Straight on through the surface (a shadow catcher): same ray class, same chain.
      if (state->black() || state->depth >= rules.max_depth) return;
      ++state->transparent_depth;
      spawn_ray(si, state->ray.direction, length_scale, &state->ray);
      continue;
    }
    BsdfSample s;
    const bool continues =
        state->depth < rules.max_depth &&
        continue_path(rules, *step.bsdf, step.spectral, -state->ray.direction, sampler, state, &s);
    visitor.scattered(*state, continues);
    if (!continues) return;
    // A straight delta transmission (a Transparent BSDF) keeps a camera ray a camera ray.
    count_bounce(s, state);
    const bool transparent = rules.transparent_keeps_visibility && s.is_delta() &&
                             !(s.flags & kLobeReflection) &&
                             dot(s.wi, state->ray.direction) > 0.9999f;
    state->see_through = state->see_through && transparent;
    if (!transparent) state->mask = visibility_after(s.flags);
    spawn_ray(si, s.wi, length_scale, &state->ray);
  }
}

}  // namespace photon
