#include "photon/integrators/radiosity/radiosity_refine.h"

#include <algorithm>
#include <cmath>

#include "photon/base/rng.h"
#include "photon/integrators/radiosity/radiosity_material.h"

namespace photon {
namespace {

double scalar_total(const RadiosityPower& p) {
  const Vec3 t = p.total();
  return (static_cast<double>(t.x) + t.y + t.z) / 3.0;
}

// One side of an element edge: the welded end vertices (ordered) and the element's patch, with
// the side flip of the first vertex (a patch's front may be its neighbour's back).
struct EdgeSide {
  uint64_t key;
  uint32_t patch;
  bool flip;
  bool operator<(const EdgeSide& o) const {
    if (key != o.key) return key < o.key;
    if (patch != o.patch) return patch < o.patch;
    return flip < o.flip;
  }
};

size_t patch_cap(uint64_t rays, const RadiosityMeshSettings& s) {
  if (rays == 0) return SIZE_MAX;
  return std::max<size_t>(s.min_patches,
                          static_cast<size_t>(rays / std::max<uint32_t>(s.min_rays_per_patch, 1)));
}

}  // namespace

std::vector<uint32_t> refinement_candidates(const RadiosityMesh& mesh,
                                            const std::vector<RadiosityPower>& power,
                                            const std::vector<uint32_t>& hits,
                                            const RadiosityRefineSettings& settings,
                                            size_t max_splits, double final_hits_scale) {
  const size_t patches = mesh.patch_count();
  if (max_splits == 0 || power.size() != 2 * patches || hits.size() != 2 * patches) return {};
  const double contrast =
      std::isfinite(settings.contrast) ? std::max(settings.contrast, 0.0f) : 0.2;
  const double sigmas =
      std::isfinite(settings.noise_sigmas) ? std::max(settings.noise_sigmas, 0.0f) : 2.0;

  // Element edges, sorted by their welded vertex pair: runs of equal keys are shared edges.
  std::vector<EdgeSide> edges;
  edges.reserve(3 * mesh.element_count());
  for (uint32_t e = 0; e < mesh.element_count(); ++e) {
    uint32_t v[3];
    bool flip[3];
    mesh.element_vertices(e, v, flip);
    for (int k = 0; k < 3; ++k) {
      const int l = (k + 1) % 3;
      const bool ordered = v[k] < v[l];
      const uint32_t a = ordered ? v[k] : v[l], b = ordered ? v[l] : v[k];
      edges.push_back(
          {static_cast<uint64_t>(a) << 32 | b, mesh.patch_of(e), ordered ? flip[k] : flip[l]});
    }
  }
  std::sort(edges.begin(), edges.end());

  const uint32_t max_levels = std::max<uint32_t>(settings.levels, 1);
  const double min_hits =
      std::isfinite(settings.min_child_hits) ? std::max(settings.min_child_hits, 0.0f) : 12.0;
  const double scale = std::isfinite(final_hits_scale) ? std::max(final_hits_scale, 0.0) : 1.0;
  auto splittable = [&](uint32_t p) {
    return !mesh.patch_clustered(p) && mesh.patch_element_count(p) == 1 &&
           mesh.patch_cell(p).level < max_levels;
  };
  std::vector<double> score(patches, 0.0);
  auto radiosity = [&](uint32_t p, uint32_t side, double* b, double* sigma) {
    const double area = mesh.patch_area(p);
    *b = area > 0.0 ? scalar_total(power[2 * p + side]) / area : 0.0;
    *sigma = *b / std::sqrt(std::max<double>(hits[2 * p + side], 1.0));
  };
  for (size_t first = 0; first < edges.size();) {
    size_t end = first + 1;
    while (end < edges.size() && edges[end].key == edges[first].key) ++end;
    for (size_t i = first; i < end; ++i)
      for (size_t j = i + 1; j < end; ++j) {
        const EdgeSide &p = edges[i], &q = edges[j];
        if (p.patch == q.patch || !(splittable(p.patch) || splittable(q.patch))) continue;
        for (uint32_t side = 0; side < 2; ++side) {
          double bp, sp, bq, sq;
          radiosity(p.patch, side, &bp, &sp);
          radiosity(q.patch, side ^ (p.flip != q.flip ? 1u : 0u), &bq, &sq);
          const double threshold =
              std::max(contrast * std::max(bp, bq), sigmas * std::sqrt(sp * sp + sq * sq));
          const double d = std::fabs(bp - bq);
          if (!(threshold > 0.0) || !(d > threshold)) continue;
          // The brighter side's quarters must be lit well enough in the final solve (the
          // darker side's absolute noise is smaller).
          const uint32_t bright_hits =
              bp >= bq ? hits[2 * p.patch + side] : hits[2 * q.patch + (side ^ (p.flip != q.flip))];
          if (0.25 * scale * bright_hits < min_hits) continue;
          const double s = d / threshold;
          for (uint32_t patch : {p.patch, q.patch})
            if (splittable(patch)) score[patch] = std::max(score[patch], s);
        }
      }
    first = end;
  }

  std::vector<uint32_t> marked;
  for (uint32_t p = 0; p < patches; ++p)
    if (score[p] > 0.0) marked.push_back(p);
  std::sort(marked.begin(), marked.end(), [&](uint32_t a, uint32_t b) {
    return score[a] != score[b] ? score[a] > score[b] : a < b;
  });
  if (marked.size() > max_splits) marked.resize(max_splits);
  return marked;
}

RadiosityRefined solve_radiosity_refined(const RenderContext& context,
                                         const RadiosityMeshSettings& mesh_settings,
                                         const RadiositySolveSettings& solve,
                                         const RadiosityRefineSettings& refine,
                                         const PrepareControl& control,
                                         std::vector<std::string>* warnings) {
  RadiosityRefined out;
  const float first_share = std::isfinite(refine.first_pass_rays)
                                ? std::clamp(refine.first_pass_rays, 0.0f, 0.9f)
                                : 0.25f;
  const uint64_t first_rays = static_cast<uint64_t>(static_cast<double>(solve.rays) * first_share);
  if (!refine.enabled || first_rays == 0) {
    out.mesh = RadiosityMesh(*context.scene, *context.accel, mesh_settings, is_radiosity_surface,
                             warnings);
    out.first_patches = out.mesh.patch_count();
    if (control.cancelled()) return out;
    out.power = solve_radiosity(context, out.mesh, solve, control, &out.stats);
    return out;
  }
  const uint64_t final_rays = solve.rays;  // the passes come on top (see the settings)

  // The first mesh: the automatic size aims at (1 - reserve) of the final patch budget.
  const bool automatic =
      !(mesh_settings.patch_size > 0.0f && std::isfinite(mesh_settings.patch_size));
  const float keep =
      std::isfinite(refine.reserve) ? 1.0f - std::clamp(refine.reserve, 0.0f, 0.9f) : 0.5f;
  const uint64_t budget_rays = mesh_settings.rays > 0 ? final_rays : 0;
  size_t budget = patch_cap(budget_rays, mesh_settings);
  RadiosityMeshSettings first = mesh_settings;
  first.split_cells = nullptr;
  first.rays = budget_rays;
  if (automatic) {
    budget = std::min(budget, mesh_settings.auto_elements);
    first.rays = static_cast<uint64_t>(static_cast<double>(budget_rays) * keep);
    first.auto_elements = std::max<size_t>(
        1, static_cast<size_t>(static_cast<double>(mesh_settings.auto_elements) * keep));
  }
  budget = std::min(budget, mesh_settings.max_elements);
  out.mesh = RadiosityMesh(*context.scene, *context.accel, first, is_radiosity_surface, warnings);
  out.first_patches = out.mesh.patch_count();
  if (control.cancelled()) return out;

  // Refinement passes, one level each: solve, mark, split. Later meshes keep the first's size.
  const uint32_t levels = std::clamp<uint32_t>(refine.levels, 1, 5);
  RadiosityMeshSettings refined = mesh_settings;
  refined.patch_size = out.mesh.patch_size();
  refined.rays = 0;  // the first mesh gave its warnings
  refined.max_levels = levels;
  std::vector<RadiosityCell> split;
  RadiositySolveStats pass_stats;
  const uint32_t passes = out.mesh.patch_count() <= refine.max_patches ? levels : 0;
  for (uint32_t pass = 0; pass < passes; ++pass) {
    RadiositySolveSettings pass_solve = solve;
    pass_solve.rays = first_rays;
    pass_solve.seed = hash_combine(solve.seed, 0x726566696e65ull + pass);  // independent
    RadiositySolveStats stats;
    std::vector<RadiosityPower> power =
        solve_radiosity(context, out.mesh, pass_solve, control, &stats);
    if (control.cancelled()) return out;
    out.first_rays += stats.rays;
    pass_stats.rays += stats.rays;
    pass_stats.seconds += stats.seconds;
    if (control.should_stop()) {  // stopped: show this solution
      out.power = std::move(power);
      out.stats = stats;
      out.stats.rays = pass_stats.rays;
      out.stats.seconds = pass_stats.seconds;
      return out;
    }
    // Each split adds 3 patches.
    const size_t count = out.mesh.patch_count();
    const size_t max_splits = budget > count ? (budget - count) / 3 : 0;
    const std::vector<uint32_t> marked =
        refinement_candidates(out.mesh, power, stats.hits, refine, max_splits,
                              static_cast<double>(final_rays) / std::max<uint64_t>(stats.rays, 1));
    if (marked.empty()) break;
    for (uint32_t p : marked) split.push_back(out.mesh.patch_cell(p));
    std::sort(split.begin(), split.end());
    refined.split_cells = &split;
    out.mesh =
        RadiosityMesh(*context.scene, *context.accel, refined, is_radiosity_surface, nullptr);
  }
  RadiositySolveSettings final_solve = solve;
  final_solve.rays = final_rays;
  out.power = solve_radiosity(context, out.mesh, final_solve, control, &out.stats);
  out.stats.rays += pass_stats.rays;
  out.stats.seconds += pass_stats.seconds;
  return out;
}

}  // namespace photon
