// Follows a camera ray through the non-diffuse lobes of the surfaces it meets (Jensen
// 2001 sec. 9.1: specular and glossy reflection and refraction, ray traced), adding emission met on
// the way and direct light at every vertex (direct_lighting.h). The diffuse lobes' indirect light
// is left to the integrator, through `shade_diffuse`. The loop itself is the shared path walker
// (path_walker.h); this file adds what only camera paths do: lamps and the world seen along the
// path, alpha, holdouts and shadow catchers (matte.h).
//
// Irradiance-cache placement walks camera paths with this same code (walk_camera_path with
// cache_placement_walk()), so its records land exactly where camera paths gather.
#pragma once

#include <functional>

#include "photon/integrators/integrator.h"
#include "photon/integrators/path_walker.h"
#include "photon/integrators/spectral_path.h"
#include "photon/render/material_eval.h"

namespace photon {

// The light a spectral camera path gathers, by pass (RadianceSample's direct, indirect, caustic).
struct SpectralSample {
  SpectralTally direct, indirect, caustic;
};

// A spectral camera path at a vertex: where its integrator adds what it estimates there.
struct SpectralVertex {
  const SampledWavelengths* wl;  // the path's, with its pdfs as they are at this vertex
  SampledSpectrum beta;          // camera -> this vertex, without the vertex's own BSDF
  const SpectralBsdf* bsdf;      // the vertex's BSDF at the wavelengths
  SpectralSample* light;         // add(L, *wl) here; RGB estimates may go to the RadianceSample
};

struct PathVertex {
  const SurfaceInteraction* si;  // normals as wound by the mesh
  const ShadingPoint* shading;   // BSDF with normals facing wo
  Vec3 wo;
  Vec3 throughput;             // camera -> this vertex, without the vertex's own BSDF
  int depth = 0;               // bounces before this vertex
  bool after_glossy = false;   // a rough (non-delta) lobe was sampled on the way here
  bool after_diffuse = false;  // an earlier vertex of this path had a diffuse lobe
  float path_length = 0.0f;    // distance along the path from the camera to this vertex
  const SpectralVertex* spectral = nullptr;  // set on spectral paths (throughput is then unused)
};

using DiffuseShader = std::function<void(const PathVertex& vertex, RadianceSample* result)>;

// How a camera path is walked.
struct CameraWalk {
  PathRules rules;
  // Estimate radiance (direct light at each vertex, shadow-catcher filters). Off, the walk only
  // follows the path and uses `sampler` for nothing but its lobe choices.
  bool radiance = true;
  // The lobes lit by light sampling at every vertex (radiosity leaves out the diffuse lobes:
  // its solution already holds their direct light).
  uint8_t light_sampled = kLobeDiffuse | kLobeGlossy;
  // Stochastic progressive photon mapping: when set, the first vertex whose BSDF it accepts is
  // the path's visible point (Hachisuka & Jensen 2009): `at_diffuse` is called there, and only
  // there. Photons estimate the non-delta lobes of that BSDF, so from there (and from every
  // later vertex it accepts) the path goes on through delta lobes only: mirror and glass
  // layers keep their reflections, while indirect light at later rough vertices is left out.
  bool (*visible_point)(const Bsdf& bsdf) = nullptr;
  // Spectral mode: the path carries wavelengths (spectral_path.h), its own sample's unless
  // `wavelengths` gives them (an SPPM iteration's, shared by its photons).
  bool spectral = false;
  const SampledWavelengths* wavelengths = nullptr;
};

// The render's camera walk: glossy and specular lobes ray traced up to max_depth bounces,
// Russian roulette on the throughput (path_walker.h).
CameraWalk camera_render_walk(const RenderContext& context,
                              uint8_t light_sampled = kLobeDiffuse | kLobeGlossy);

// The walk that places irradiance-cache records: the render walk, but through delta lobes only
// (camera paths final-gather only at diffuse points reached through them, see
// PhotonMapIntegrator::shade_diffuse) and without roulette, so that a record exists wherever
// any camera sample may gather, not where one random path happened to survive.
CameraWalk cache_placement_walk(const RenderContext& context);

// Radiance of the world along a ray that left the scene with visibility class `mask` (a world
// that tells camera rays apart shows them its camera branch); suns are not included.
Vec3 world_seen_by(const RenderContext& context, const Ray& ray, uint32_t mask);

// Walks the path of one camera ray, calling `at_diffuse` at every vertex with a diffuse lobe.
// `first`, if given, is the camera ray's already traced first hit.
void walk_camera_path(const RenderContext& context, const Ray& camera_ray, const CameraHit* first,
                      Sampler& sampler, const CameraWalk& walk, const DiffuseShader& at_diffuse,
                      RadianceSample* result);

// Traces the path of one camera sample with the render walk.
inline void trace_camera_path(const RenderContext& context, const Ray& camera_ray,
                              const CameraHit& first, Sampler& sampler,
                              const DiffuseShader& shade_diffuse, RadianceSample* result,
                              uint8_t light_sampled = kLobeDiffuse | kLobeGlossy) {
  walk_camera_path(context, camera_ray, &first, sampler, camera_render_walk(context, light_sampled),
                   shade_diffuse, result);
}

// Shading of `si` as seen along -ray_direction, with the context's textures, for a ray of the
// kind `ray` (Light Path node).
inline ShadingPoint shade(const RenderContext& context, const SurfaceInteraction& si,
                          const Vec3& wo, const ShadeRay& ray = ShadeRay{}) {
  return shade_surface(si, wo, *context.accel, context.textures, ray);
}

// The Light Path view of a camera path's segment: its visibility class (camera, diffuse, glossy,
// transmission), its bounce counts by kind (Cycles's: Ray Depth leaves out transparent
// pass-throughs), and the distance travelled from the camera.
ShadeRay camera_shade_ray(const PathState& state, float path_length);

}  // namespace photon
