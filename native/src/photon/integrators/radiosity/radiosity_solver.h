// Monte Carlo radiosity without form factors: stochastic Jacobi iterations with local lines
// (Dutre, Bekaert, Bala, "Advanced Global Illumination" (AGI) 2nd ed.,
// sec. 6.3 "Stochastic relaxation radiosity" and appendix C; Bekaert's PhD thesis 1999,
// "Hierarchical and stochastic algorithms for radiosity", on stochastic Jacobi iterations).
//
// In power form the radiosity system reads P_i = Pe_i + rho_i sum_j F_ji P_j.
// Since sum_j F_ij = 1 and F_ij is the probability that a cosine-distributed line leaving a
// uniform point of i lands on j (local lines), one Jacobi step P' = Pe + rho F^T P is
// estimated by shooting N rays, each from a source chosen with probability proportional to its
// power and carrying the same power P_T / N; the element a ray lands on receives rho times it
// (AGI sec. 6.3, solving the system of eq. 6.6). Two phases:
//  1. incremental shooting (AGI sec. 6.3; its variance: appendix C): shoot the unshot power dP
//     of the last step (first the lights themselves: Blender lights, emissive meshes, a uniform
//     world, through PhotonSources), add what lands to the total, repeat until the unshot power is
//     below `threshold` times the emitted power;
//  2. regular Jacobi iterations P(k+1) = Pe + rho F^T P(k), each estimated with fresh rays
//     (lights re-shot too), and averaged to cut the noise (AGI sec. 6.3, "regular
//     shooting").
// Rays that meet mirrors and glass follow them and land on the next diffuse element. Light
// sources are not elements here: their power is shot by the lights' own emission routines,
// and elements hold reflected power only (so emission is added exactly at display time).
#pragma once

#include <cstdint>
#include <vector>

#include "photon/integrators/integrator.h"
#include "photon/integrators/radiosity/radiosity_mesh.h"

namespace photon {

// Reflected power leaving one side of an element (W per channel), split by the path the light
// took: straight from a light, from a light through mirrors/glass, or after a diffuse bounce.
struct RadiosityPower {
  Vec3 direct, caustic, indirect;
  Vec3 total() const { return direct + caustic + indirect; }
};

struct RadiositySolveSettings {
  uint64_t rays = 4000000;  // total rays of the solve (time is about proportional)
  float threshold = 0.01f;  // incremental shooting stops below this unshot fraction
  int iterations = 4;       // regular Jacobi iterations averaged after shooting
  uint64_t seed = 0;
};

struct RadiositySolveStats {
  // Power balance (W, mean of the channels): emitted = absorbed + absorbed_specular + escaped
  // + unshot, for the incremental phase. Regular iterations each keep the same balance.
  double emitted = 0.0;
  double absorbed = 0.0;           // by diffuse elements (1 - rho)
  double absorbed_specular = 0.0;  // by tinted mirrors/glass, or lost at the depth limit
  double escaped = 0.0;            // left the scene
  double unshot = 0.0;             // reflected power never shot (below the threshold)
  uint64_t rays = 0;
  int incremental_iterations = 0;
  int regular_iterations = 0;
  double seconds = 0.0;
  bool stopped_early = false;
  // Deposits per patch side (2 per patch) in the steps the returned solution is made of (the
  // averaged iterations, or the shooting phase without them): a side hit k times has a relative
  // noise of about 1 / sqrt(k) (Bekaert 1999, sec. 6.3).
  std::vector<uint32_t> hits;
};

// Solves for the reflected power of every patch side (2 per patch: front = the side its
// elements' cross(e1, e2) point to, then back). Returns the best solution when stopped early; an
// empty vector when cancelled.
std::vector<RadiosityPower> solve_radiosity(const RenderContext& context, const RadiosityMesh& mesh,
                                            const RadiositySolveSettings& settings,
                                            const PrepareControl& control,
                                            RadiositySolveStats* stats);

}  // namespace photon
