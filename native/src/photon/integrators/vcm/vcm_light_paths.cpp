#include "photon/integrators/vcm/vcm_light_paths.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "photon/integrators/camera_path.h"
#include "photon/integrators/path_walker.h"
#include "photon/integrators/photon_map/photon_memory.h"

namespace photon {
namespace {

constexpr uint64_t kChunk = 1024;                      // subpaths per parallel work item
constexpr uint64_t kLightStream = 0x56434D4C49474854;  // "VCMLIGHT"

struct ChunkOutput {
  std::vector<VcmLightVertex> vertices;
  std::vector<uint64_t> path_size;
  std::vector<VcmSplat> splats;
  uint64_t rays = 0;
};

// Light tracing (Georgiev et al. 2012 strategy t = 1; SmallVCM's ConnectToCamera): the vertex
// seen by the pinhole, with the camera's density relative to this strategy (tech. report eq.
// 44 with the pixel filter's density left to the splat).
void connect_to_camera(const RenderContext& context, const VcmCamera& camera, const VcmMis& mis,
                       const VcmColours& colours, const SampledWavelengths& path_wl,
                       const VcmLightVertex& v, const VcmBsdf& bsdf, float continuation,
                       ChunkOutput* out) {
  Vec2 raster;
  float cos_axis, distance;
  if (!camera.project(v.p, &raster, &cos_axis, &distance)) return;
  const Vec3 to_camera = (camera.position() - v.p) / distance;
  const SampledSpectrum f = bsdf.eval(v.wo, to_camera) * bsdf.adjoint_scale(v.wo, to_camera);
  if (is_black(f)) return;
  const float cos_surface = std::fabs(dot(v.ng, to_camera));
  // The adjoint BSDF with the shading normal (Veach eq. 5.17): the geometric cosine towards
  // the camera is in image_to_surface.
  const float ns_wo = std::fabs(dot(bsdf.frame().n, v.wo)), ng_wo = std::fabs(dot(v.ng, v.wo));
  if (!(ng_wo > 1e-9f)) return;
  const float image_to_surface =
      camera.raster_to_solid_angle(cos_axis) * cos_surface / (distance * distance);
  const float rev_pdf = bsdf.pdf_reverse(v.wo, to_camera) * continuation;
  const float n = static_cast<float>(mis.light_paths);
  VcmSplat s;
  s.x = raster.x;
  s.y = raster.y;
  SampledSpectrum value(0.0f);
  colours.add(&value, v.throughput * f * (ns_wo / ng_wo * image_to_surface / n), path_wl);
  s.value = colours.rgb(value);
  s.a = image_to_surface / n * (mis.vm_factor + v.dvcm + v.dvc * rev_pdf);
  if (!is_finite(s.value) || !std::isfinite(s.a)) return;
  if (!vcm_visible(*context.accel, v.p, v.ng, camera.position(), Vec3(0.0f))) return;
  out->splats.push_back(s);
}

void trace_one(const RenderContext& context, const VcmLights& lights, const VcmCamera& camera,
               const VcmMis& mis, const VcmColours& colours, Sampler& sampler, ChunkOutput* out) {
  float u_rest;
  const size_t k = lights.pick(sampler.get_1d(), &u_rest);
  const Vec2 u_pos = sampler.get_2d(), u_dir = sampler.get_2d();
  EmittedPhoton e;
  if (!lights.emitter(k).sample_le(lights.frame(), u_rest, u_pos, u_dir, true, &e)) return;
  const float pick = lights.pick_probability(k);
  const uint8_t flags = lights.flags(k);
  const float emission_pdf = e.pdf_pos * e.pdf_dir * pick;
  if (!(emission_pdf > 0.0f)) return;
  // Tech. report eqs. 31-33: the subpath's first vertex.
  SampledSpectrum throughput =
      colours.emitted(lights.emitter(k), e.radiance) * (e.cos_light / emission_pdf);
  SampledWavelengths path_wl = colours.wl ? *colours.wl : SampledWavelengths();
  float dvcm = e.direct_pdf * pick / emission_pdf;
  float dvc = (flags & (kEmitterDeltaPosition | kEmitterDeltaDirection))
                  ? 0.0f
                  : ((flags & kEmitterInfinite) ? 1.0f : e.cos_light) / emission_pdf;
  float dvm = dvc * mis.vc_factor;
  const bool infinite = (flags & kEmitterInfinite) != 0;
  Ray ray = e.ray;
  uint32_t mask = kVisibleDiffuse | kVisibleGlossy | kVisibleTransmission | kVisibleShadow;
  const float length_scale = context.accel->length_scale();
  for (int path_length = 1;; ++path_length) {
    Hit hit;
    ++out->rays;
    if (!context.accel->intersect(ray, mask, &hit)) return;
    const SurfaceInteraction si = context.accel->interaction(hit);
    const Vec3 wo = -ray.direction;
    const ShadingPoint sp = shade(context, si, wo);
    if (sp.bsdf.empty()) return;
    const VcmBsdf bsdf(sp.bsdf, colours.wl ? &path_wl : nullptr);
    const Vec3 ng = dot(si.ng, wo) >= 0.0f ? si.ng : -si.ng;
    const float cos_in = std::fabs(dot(ng, wo));
    if (!(cos_in > 1e-7f)) return;
    // Eqs. 34-36: the segment's distance and the cosine at this end.
    if (path_length > 1 || !infinite) dvcm *= hit.t * hit.t;
    dvcm /= cos_in;
    dvc /= cos_in;
    dvm /= cos_in;
    const float continuation = vcm_continuation(sp.bsdf, wo);
    if (vcm_connectible(sp.bsdf)) {
      VcmLightVertex v;
      v.hit = hit;
      v.p = si.p;
      v.ng = ng;
      v.wo = wo;
      v.throughput = throughput;
      v.dvcm = dvcm;
      v.dvc = dvc;
      v.dvm = dvm;
      v.path_length = path_length;
      v.terminated = colours.wl && path_wl.active_count() < colours.wl->active_count();
      if (!is_finite(throughput) || !is_finite(si.p)) return;
      out->vertices.push_back(v);
      if (mis.use_vc && path_length + 1 <= mis.max_path_length)
        connect_to_camera(context, camera, mis, colours, path_wl, v, bsdf, continuation, out);
    }
    if (path_length + 2 > mis.max_path_length) return;
    // Scattering with Russian roulette by the BSDF's albedo (both densities carry it).
    const float u_lobe = sampler.get_1d();
    const Vec2 u = sampler.get_2d();
    const float u_survive = sampler.get_1d();
    VcmBsdfSample s;
    if (!bsdf.sample(wo, u_lobe, u, &s) || is_black(s.weight) || !(s.pdf > 0.0f)) return;
    if (!(u_survive < continuation)) return;
    const float cos_out = std::fabs(dot(ng, s.wi));
    const float dir_pdf = s.pdf * continuation;
    if (s.is_delta()) {
      dvcm = 0.0f;
      dvc *= cos_out;
      dvm *= cos_out;
    } else {
      const float rev_pdf = bsdf.pdf_reverse(wo, s.wi) * continuation;
      dvc = cos_out / dir_pdf * (dvc * rev_pdf + dvcm + mis.vm_factor);
      dvm = cos_out / dir_pdf * (dvm * rev_pdf + dvcm * mis.vc_factor + 1.0f);
      dvcm = 1.0f / dir_pdf;
    }
    throughput =
        throughput * s.weight * (adjoint_correction(bsdf.frame().n, ng, wo, s.wi) / continuation);
    if (!s.transparent && (s.flags & kLobeTransmission)) throughput *= bsdf.adjoint_scale(wo, s.wi);
    if (s.terminate) path_wl.terminate_secondary();  // the weight is the hero's alone
    if (is_black(throughput)) return;
    mask = visibility_after(s.flags);
    spawn_ray(si, s.wi, length_scale, &ray);
  }
}

}  // namespace

VcmLightPass trace_vcm_light_paths(const RenderContext& context, const VcmLights& lights,
                                   const VcmCamera& camera, const VcmMis& mis, uint32_t iteration,
                                   const std::atomic<bool>& cancel, const VcmColours& colours) {
  VcmLightPass pass;
  const uint64_t count = mis.light_paths;
  pass.path_end.assign(count, 0);
  if (lights.empty()) return pass;
  const uint64_t chunks = (count + kChunk - 1) / kChunk;
  std::vector<ChunkOutput> outputs(chunks);
  const uint64_t stream = hash_combine(kLightStream, iteration);
  const uint64_t seed = context.settings->seed;
  const auto stratify = static_cast<uint32_t>(std::min<uint64_t>(count, UINT32_MAX));
  tbb::parallel_for(tbb::blocked_range<uint64_t>(0, chunks, 1), [&](const auto& r) {
    for (uint64_t c = r.begin(); c != r.end(); ++c) {
      if (cancel.load(std::memory_order_relaxed)) return;
      ChunkOutput& out = outputs[c];
      const uint64_t lo = c * kChunk, hi = std::min(count, lo + kChunk);
      for (uint64_t i = lo; i < hi; ++i) {
        Sampler sampler(seed, stream, static_cast<uint32_t>(i), stratify);
        const size_t before = out.vertices.size();
        trace_one(context, lights, camera, mis, colours, sampler, &out);
        out.path_size.push_back(out.vertices.size() - before);
      }
    }
  });
  if (cancel.load(std::memory_order_relaxed)) {
    pass.cancelled = true;
    return pass;
  }
  size_t vertices = 0, splats = 0;
  for (const ChunkOutput& out : outputs) {
    vertices += out.vertices.size();
    splats += out.splats.size();
  }
  pass.vertices.reserve(vertices);
  pass.splats.reserve(splats);
  uint64_t path = 0, end = 0;
  for (const ChunkOutput& out : outputs) {
    pass.vertices.insert(pass.vertices.end(), out.vertices.begin(), out.vertices.end());
    pass.splats.insert(pass.splats.end(), out.splats.begin(), out.splats.end());
    for (uint64_t size : out.path_size) pass.path_end[path++] = (end += size);
    pass.rays += out.rays;
  }
  return pass;
}

double vcm_light_pass_peak_bytes(double paths, double vertices_per_path, double splats_per_path) {
  // path_end in the pass and path_size in the chunks: 8 bytes each per subpath.
  const double pass = paths * (vertices_per_path * sizeof(VcmLightVertex) +
                               splats_per_path * sizeof(VcmSplat) + 8.0);
  const double grid = paths * vertices_per_path * 24.0;
  return std::max(2.0 * pass + 8.0 * paths, pass + grid);
}

VcmLightPathPlan plan_vcm_light_paths(const RenderContext& context, const VcmLights& lights,
                                      const VcmCamera& camera, const VcmMis& mis,
                                      uint64_t requested, double budget_bytes) {
  VcmLightPathPlan plan;
  plan.light_paths = requested;
  // Below this bound (every subpath storing a vertex and a splat at every bounce) no pilot is
  // needed.
  const double bound = mis.max_path_length;
  if (!(budget_bytes > 0.0) ||
      vcm_light_pass_peak_bytes(static_cast<double>(requested), bound, bound) <= budget_bytes)
    return plan;
  constexpr uint64_t kPilotPaths = 4096;
  constexpr uint32_t kPilotIteration = 0xFFFFFFFFu;
  VcmMis pilot_mis = mis;
  pilot_mis.light_paths = kPilotPaths;
  const std::atomic<bool> no_cancel{false};
  const VcmLightPass pilot =
      trace_vcm_light_paths(context, lights, camera, pilot_mis, kPilotIteration, no_cancel);
  const double vertices = static_cast<double>(pilot.vertices.size()) / kPilotPaths;
  const double splats = static_cast<double>(pilot.splats.size()) / kPilotPaths;
  plan.requested_bytes =
      vcm_light_pass_peak_bytes(static_cast<double>(requested), vertices, splats);
  plan.light_paths =
      count_that_fits(requested, vcm_light_pass_peak_bytes(1.0, vertices, splats), budget_bytes);
  // The grid indexes vertices with 32 bits; a tenth kept spare for subpaths longer than the
  // pilot's.
  if (vertices > 0.0)
    plan.light_paths =
        std::min<uint64_t>(plan.light_paths, static_cast<uint64_t>(0.9 * 4294967295.0 / vertices));
  plan.light_paths = std::max<uint64_t>(plan.light_paths, 1);
  return plan;
}

void apply_vcm_splats(const std::vector<VcmSplat>& splats, const VcmCamera& camera,
                      const FilmFrame& s, std::vector<Vec3>* image) {
  const int width = s.x1 - s.x0;
  const float h = camera.filter_half_support();
  for (const VcmSplat& sp : splats) {
    // Pixels whose centre (px + 0.5, py + 0.5) is within the filter's support of the point.
    const int x_lo = std::max(s.x0, static_cast<int>(std::ceil(sp.x - h - 0.5f)));
    const int x_hi = std::min(s.x1 - 1, static_cast<int>(std::floor(sp.x + h - 0.5f)));
    const int y_lo = std::max(s.y0, static_cast<int>(std::ceil(sp.y - h - 0.5f)));
    const int y_hi = std::min(s.y1 - 1, static_cast<int>(std::floor(sp.y + h - 0.5f)));
    for (int py = y_lo; py <= y_hi; ++py)
      for (int px = x_lo; px <= x_hi; ++px) {
        const float f = camera.filter_pdf(sp.x - (px + 0.5f), sp.y - (py + 0.5f));
        if (!(f > 0.0f)) continue;
        (*image)[static_cast<size_t>(py - s.y0) * width + (px - s.x0)] +=
            sp.value * (f / (1.0f + f * sp.a));
      }
  }
}

}  // namespace photon
