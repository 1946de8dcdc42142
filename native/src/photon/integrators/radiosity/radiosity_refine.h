// Adaptive refinement of the radiosity mesh where the light changes (Cohen, Greenberg, Immel,
// Brock, "An efficient radiosity approach for realistic image synthesis", IEEE CG&A 1986;
// Cohen & Wallace, "Radiosity and Realistic Image Synthesis" 1993, ch. 8, "a posteriori"
// meshing): a first solve on the area-sized mesh (radiosity_mesh.h) with a share of the rays,
// then every subdivided patch whose radiosity differs from an edge neighbour's by more than a
// relative threshold, and by more than the Monte Carlo noise of the two estimates, is split into 2
// x 2, within the patch budget of the ray count; the refined mesh is solved again. This repeats for
// a few levels (each pass splitting the split patches again where the difference persists). Part of
// the automatic patch budget is held back for the refinement, so patches move from uniformly lit
// areas to shadow boundaries and other gradients.
#pragma once

#include <string>
#include <vector>

#include "photon/integrators/radiosity/radiosity_mesh.h"
#include "photon/integrators/radiosity/radiosity_solver.h"

namespace photon {

struct RadiosityRefineSettings {
  bool enabled = true;
  // Each refinement pass solves with this share of the rays, on top of the final solve (which
  // has all of them): a pass's marking needs a few tens of rays per patch to see through the
  // noise, so the passes cost about levels * first_pass_rays more time.
  float first_pass_rays = 0.25f;
  uint32_t levels = 2;   // refinement passes (each splits once more: 4x finer edges at most)
  float reserve = 0.5f;  // share of the automatic patch budget kept for splits
  // An edge is refined when |B_p - B_q| exceeds both contrast * max(B_p, B_q) and noise_sigmas
  // standard deviations of the difference (relative noise 1 / sqrt(deposits) per patch side).
  float contrast = 0.2f;
  float noise_sigmas = 2.0f;
  // An edge is refined only if the quarters of its brighter patch can each expect this many ray
  // deposits in the final solve (its deposits in the pass, scaled by the rays, over 4): finer
  // patches than the rays can light show as blotches (relative noise about 1 / sqrt(deposits)).
  float min_child_hits = 12.0f;
  // Meshes with more patches are not refined: a refined instance's lattice has 4^levels times
  // the points, too much memory for millions of patches (only a manual patch size gets there).
  size_t max_patches = 250000;
};

// Subdivided patches of `mesh` (below `levels` of refinement) to split, best first (largest
// difference over its threshold), at most `max_splits`. `power` and `hits`: 2 per patch, as
// solve_radiosity gives.
std::vector<uint32_t> refinement_candidates(const RadiosityMesh& mesh,
                                            const std::vector<RadiosityPower>& power,
                                            const std::vector<uint32_t>& hits,
                                            const RadiosityRefineSettings& settings,
                                            size_t max_splits, double final_hits_scale = 1.0);

struct RadiosityRefined {
  RadiosityMesh mesh;
  std::vector<RadiosityPower> power;  // empty when cancelled
  RadiositySolveStats stats;          // of the final solve (rays: both solves)
  size_t first_patches = 0;           // patches of the first solve's mesh
  uint64_t first_rays = 0;            // rays of the refinement passes
};

// Meshes and solves the scene of `context`, with local refinement unless disabled (then the
// mesh and solve are exactly the unrefined ones). Warnings are appended to `warnings`.
RadiosityRefined solve_radiosity_refined(const RenderContext& context,
                                         const RadiosityMeshSettings& mesh_settings,
                                         const RadiositySolveSettings& solve,
                                         const RadiosityRefineSettings& refine,
                                         const PrepareControl& control,
                                         std::vector<std::string>* warnings);

}  // namespace photon
