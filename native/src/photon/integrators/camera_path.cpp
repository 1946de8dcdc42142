#include "photon/integrators/camera_path.h"

#include "photon/integrators/matte.h"
#include "photon/lights/direct_lighting.h"
#include "photon/lights/emitter_set.h"
#include "photon/render/world_shader.h"
#include "photon/spectral/rgb_uplift.h"

namespace photon {
namespace {

// Lamp surfaces, the world and suns that a segment reaches, if it counts emission.
bool add_escaped_or_lamp(const RenderContext& context, const Ray& ray, bool found, float t_hit,
                         uint32_t mask, const Vec3& throughput, bool count_emission,
                         bool camera_primary, Vec3* direct) {
  float t_light;
  Vec3 lamp;
  if (context.emitters->intersect_lamps(ray, found ? t_hit : ray.tmax, mask, &t_light, &lamp)) {
    if (count_emission) *direct += throughput * lamp;
    return true;
  }
  if (!found && count_emission) {
    // The ray left the scene (camera rays too, whatever their clip distance): world and suns.
    if (!(camera_primary && context.settings->transparent_background)) {
      *direct += throughput * world_seen_by(context, ray, mask);
    }
    *direct += throughput * context.lights->distant_radiance(ray.direction, mask);
  }
  return false;
}

// add_escaped_or_lamp for a spectral path: each light's value at the path's wavelengths.
bool add_escaped_or_lamp(const RenderContext& context, const PathState& state, bool found,
                         float t_hit, bool count_emission, bool camera_primary,
                         SpectralTally* direct) {
  const Ray& ray = state.ray;
  float t_light;
  Vec3 lamp;
  size_t index = 0;
  if (context.emitters->intersect_lamps(ray, found ? t_hit : ray.tmax, state.mask, &t_light, &lamp,
                                        &index)) {
    if (count_emission)
      direct->add(state.beta * context.lights->spectrum(index, lamp, state.wl), state.wl);
    return true;
  }
  if (!found && count_emission) {
    SampledSpectrum l = context.lights->distant_radiance(ray.direction, state.mask, state.wl);
    if (!(camera_primary && context.settings->transparent_background)) {
      const Vec3 world = world_seen_by(context, ray, state.mask);
      if (!is_black(world)) l += spectral::illuminant_at(world, state.wl);
    }
    direct->add(state.beta * l, state.wl);
  }
  return false;
}

// `bsdf` with its delta lobes only (the same frame and normals).
Bsdf delta_lobes(const Bsdf& bsdf) {
  Bsdf out(bsdf.frame().n, bsdf.ng(), bsdf.front_facing());
  for (int i = 0; i < bsdf.lobe_count(); ++i)
    if (bsdf.lobe(i).flags() & kLobeSpecular) out.add(bsdf.lobe(i));
  return out;
}

// The camera's part of a walk (path_walker.h): emission met on the way (counted after delta
// lobes only: light sampling counted the rest), alpha, mattes, light sampling, and the
// integrator's diffuse shading.
class CameraVisitor {
 public:
  CameraVisitor(const RenderContext& context, const CameraWalk& walk, Sampler& sampler,
                const DiffuseShader& at_diffuse, RadianceSample* result)
      : context_(context),
        walk_(walk),
        sampler_(sampler),
        at_diffuse_(at_diffuse),
        result_(result) {}

  bool segment(const PathState& state, bool found, const Hit& hit) {
    primary_ = state.see_through && state.mask == kVisibleCamera;
    const bool lamp =
        state.spectral
            ? add_escaped_or_lamp(context_, state, found, hit.t, state.last_delta, primary_,
                                  &spectral_.direct)
            : add_escaped_or_lamp(context_, state.ray, found, hit.t, state.mask, state.throughput,
                                  state.last_delta, primary_, &result_->direct);
    if (lamp) {
      if (state.depth == 0) result_->alpha = 1.0f;
      return false;
    }
    if (!found) {
      // Alpha: what the camera sees of the background through transparent surfaces.
      const Vec3& t = state.throughput;
      const float seen =
          state.spectral ? mean_in_use(state.beta, state.wl) : (t.x + t.y + t.z) / 3.0f;
      if (primary_ && state.depth > 0) result_->alpha = std::clamp(1.0f - seen, 0.0f, 1.0f);
      return false;
    }
    if (state.depth == 0) result_->alpha = 1.0f;
    path_length_ += hit.t;
    return true;
  }

  VertexStep vertex(PathState& state, const Hit& hit, const SurfaceInteraction& si) {
    const Vec3 wo = -state.ray.direction;
    // Holdouts and shadow catchers are mattes to camera rays only (matte.h).
    const Matte matte = primary_ ? matte_at(context_, hit) : Matte::kNone;
    if (matte == Matte::kShadowCatcher) {
      // A see-through filter of the shadow ratio: whatever lies behind (the world, or
      // transparency with Film > Transparent) shows darkened by the shadows cast here.
      if (walk_.radiance) {
        const Vec3 ratio = shadow_catcher_ratio(context_, si, wo, sampler_);
        if (state.spectral)
          state.beta *= spectral::reflectance_at(ratio, state.wl);
        else
          state.throughput *= ratio;
      }
      return VertexStep::pass_through();
    }
    sp_ = shade(context_, si, wo, camera_shade_ray(state, path_length_));
    if (primary_ && (matte == Matte::kHoldout || sp_.holdout > 0.0f)) {
      // Cycles' integrate_surface_holdout: the held-out share of the throughput leaves the
      // pixel's colour and alpha; a surface held out entirely ends the path.
      const Vec3 held = matte == Matte::kHoldout ? hold_out_object(&sp_) : Vec3(sp_.holdout);
      const Vec3& t = state.throughput;
      result_->holdout +=
          state.spectral ? mean_in_use(state.beta, state.wl) * (held.x + held.y + held.z) / 3.0f
                         : (t.x * held.x + t.y * held.y + t.z * held.z) / 3.0f;
      if (held.x >= 1.0f && held.y >= 1.0f && held.z >= 1.0f) return VertexStep::stop();
    }
    if (state.last_delta && !is_black(sp_.emission)) {
      if (state.spectral)
        spectral_.direct.add(state.beta * spectral::illuminant_at(sp_.emission, state.wl),
                             state.wl);
      else
        result_->direct += state.throughput * sp_.emission;
    }
    const Bsdf& bsdf = sp_.bsdf;
    if (bsdf.empty()) return VertexStep::stop();
    if (state.spectral) {
      sbsdf_ = SpectralBsdf(bsdf, state.wl);
      vertex_ = SpectralVertex{&state.wl, state.beta, &sbsdf_, &spectral_};
    }

    const PathVertex v{&si,
                       &sp_,
                       wo,
                       state.throughput,
                       state.depth,
                       state.after_glossy,
                       diffuse_seen_,
                       path_length_,
                       state.spectral ? &vertex_ : nullptr};
    if (walk_.radiance && (bsdf.flags() & walk_.light_sampled)) {
      if (state.spectral)
        spectral_.direct.add(
            state.beta * direct_radiance(context_, si, sbsdf_, wo, sampler_, walk_.light_sampled),
            state.wl);
      else
        result_->direct += state.throughput *
                           direct_radiance(context_, si, bsdf, wo, sampler_, walk_.light_sampled);
    }
    if (walk_.visible_point) {
      if (walk_.visible_point(bsdf)) {
        // The first such vertex is the visible point; there and at later ones the photons
        // stand for every non-delta lobe, and the path goes on through the delta lobes only.
        if (!diffuse_seen_) at_diffuse_(v, result_);
        diffuse_seen_ = true;
        delta_ = delta_lobes(bsdf);
        if (delta_.empty()) return VertexStep::stop();
        if (!state.spectral) return VertexStep::scatter(delta_);
        sdelta_ = SpectralBsdf(delta_, state.wl);
        return VertexStep::scatter(delta_, &sdelta_);
      }
    } else if (bsdf.flags() & kLobeDiffuse) {
      at_diffuse_(v, result_);
      diffuse_seen_ = true;
    }
    return VertexStep::scatter(bsdf, state.spectral ? &sbsdf_ : nullptr);
  }

  // Adds the spectral path's light to `result` in Rec.709 (at the path's wavelengths).
  void finish(const SampledWavelengths& wl) {
    result_->direct += spectral_.direct.rgb(wl);
    result_->indirect += spectral_.indirect.rgb(wl);
    result_->caustic += spectral_.caustic.rgb(wl);
  }

  void scattered(const PathState&, bool) {}

 private:
  const RenderContext& context_;
  const CameraWalk& walk_;
  Sampler& sampler_;
  const DiffuseShader& at_diffuse_;
  RadianceSample* result_;
  ShadingPoint sp_;  // the current vertex's shading, alive while its BSDF is sampled
  Bsdf delta_;       // after a visible point: its delta lobes, which the path samples
  // Spectral paths: the two BSDFs at the path's wavelengths, the vertex handed to the
  // integrator, and the light gathered so far.
  SpectralBsdf sbsdf_, sdelta_;
  SpectralVertex vertex_{};
  SpectralSample spectral_;
  bool primary_ = true;
  bool diffuse_seen_ = false;  // a vertex with a diffuse lobe was shaded
  float path_length_ = 0.0f;
};

}  // namespace

Vec3 world_seen_by(const RenderContext& context, const Ray& ray, uint32_t mask) {
  // A world that tells camera rays apart (Light Path) shows them its camera branch.
  const World& world = context.scene->world;
  return mask == kVisibleCamera && world.reads_ray_type
             ? world_radiance(world, ray.direction, kRayCamera, context.textures)
             : context.emitters->world_radiance(ray.direction);
}

ShadeRay camera_shade_ray(const PathState& state, float path_length) {
  ShadeRay ray;
  switch (state.mask) {
    case kVisibleCamera:
      ray.flags = kRayCamera;
      break;
    case kVisibleDiffuse:
      ray.flags = kRayDiffuse | kRayReflect;
      break;
    case kVisibleTransmission:
      ray.flags = kRayTransmit | (state.last_delta ? kRaySingular : kRayGlossy);
      break;
    default:
      ray.flags = kRayReflect | (state.last_delta ? kRaySingular : kRayGlossy);
      break;
  }
  ray.length = path_length;
  const auto clamp_depth = [](int d) { return static_cast<uint16_t>(std::clamp(d, 0, 65535)); };
  ray.depth = clamp_depth(state.depth - state.transparent_depth);
  ray.diffuse_depth = clamp_depth(state.diffuse_depth);
  ray.glossy_depth = clamp_depth(state.glossy_depth);
  ray.transmission_depth = clamp_depth(state.transmission_depth);
  ray.transparent_depth = clamp_depth(state.transparent_depth);
  return ray;
}

CameraWalk camera_render_walk(const RenderContext& context, uint8_t light_sampled) {
  CameraWalk walk;
  walk.rules = importance_rules(context.settings->max_depth);
  walk.rules.transparent_keeps_visibility = true;
  walk.light_sampled = light_sampled;
  walk.spectral = spectral_mode(context);
  return walk;
}

CameraWalk cache_placement_walk(const RenderContext& context) {
  CameraWalk walk = camera_render_walk(context);
  walk.rules.continue_lobes = kLobeSpecular;
  walk.rules.roulette = Roulette::kNone;
  walk.radiance = false;
  // Records are placed where RGB paths through glass arrive (the final gather is RGB).
  walk.spectral = false;
  return walk;
}

void walk_camera_path(const RenderContext& context, const Ray& camera_ray, const CameraHit* first,
                      Sampler& sampler, const CameraWalk& walk, const DiffuseShader& at_diffuse,
                      RadianceSample* result) {
  PathState state;
  state.ray = camera_ray;
  state.mask = kVisibleCamera;
  if (walk.spectral)
    state.start_spectral(
        walk.wavelengths ? *walk.wavelengths : sample_wavelengths(*context.settings, sampler),
        SampledSpectrum(1.0f));
  CameraVisitor visitor(context, walk, sampler, at_diffuse, result);
  walk_path(context, walk.rules, &state, sampler, visitor, first);
  // The wavelengths only (the tallies hold L / pdf): their pdfs may have changed on the way.
  if (walk.spectral) visitor.finish(state.wl);
}

}  // namespace photon
