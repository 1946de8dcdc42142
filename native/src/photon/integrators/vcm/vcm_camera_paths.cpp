#include "photon/integrators/vcm/vcm_camera_paths.h"

#include <cmath>

#include "photon/integrators/camera_path.h"
#include "photon/integrators/path_walker.h"
#include "photon/scene/camera.h"

namespace photon {
namespace {

// The camera subpath at a vertex.
struct CameraState {
  SampledSpectrum throughput{0.0f};
  SampledWavelengths wl;  // spectral: the iteration's, terminated by a dispersive refraction
  bool terminated = false;
  float dvcm = 0.0f, dvc = 0.0f, dvm = 0.0f;
  int path_length = 1;
  bool specular_path = true;  // only delta lobes since the camera
};

// The weight of emission met by the camera path at its `path_length`-th vertex, with the
// emitter's densities already scaled by its pick probability (tech. report eq. 43).
float emission_weight(const CameraState& c, float direct_pdf, float emission_pdf, float dvcm,
                      float dvc) {
  if (c.path_length == 1) return 1.0f;
  return 1.0f / (1.0f + direct_pdf * dvcm + emission_pdf * dvc);
}

// A light subpath's vertex shaded again for connections (at its subpath's wavelengths).
struct ShadedLightVertex {
  ShadingPoint sp;
  VcmBsdf bsdf;  // refers to sp.bsdf: the vertex is not moved once shaded
  float continuation = 0.0f;
};

class CameraPath {
 public:
  CameraPath(const RenderContext& context, const VcmLights& lights, const VcmMis& mis,
             const VcmColours& colours, const VcmLightPass& pass, uint64_t light_path,
             const VcmGrid& grid, Sampler& sampler)
      : context_(context),
        lights_(lights),
        mis_(mis),
        colours_(colours),
        pass_(pass),
        grid_(grid),
        sampler_(sampler) {
    begin_ = pass.path_begin(light_path);
    end_ = pass.path_end.empty() ? 0 : pass.path_end[light_path];
  }

  SampledSpectrum next_event(const CameraState& c, const Vec3& p, const Vec3& ng, const Vec3& wo,
                             const VcmBsdf& bsdf, float continuation) {
    const SampledSpectrum black(0.0f);
    const float u_pick = sampler_.get_1d();
    const Vec2 u = sampler_.get_2d();
    if (lights_.empty() || c.path_length + 1 > mis_.max_path_length) return black;
    float u_rest;
    const size_t k = lights_.pick(u_pick, &u_rest);
    LightSample il;
    LightSampleU lu;
    lu.pick = u_rest;
    lu.uv = u;
    if (!lights_.emitter(k).sample_li(p, lu, &lights_.frame(), &il)) return black;
    const float pick = lights_.pick_probability(k);
    const SampledSpectrum f = bsdf.eval(wo, il.wi);
    if (is_black(f) || !(il.direct_pdf > 0.0f)) return black;
    const float cos_shading = std::fabs(dot(bsdf.frame().n, il.wi));
    const float cos_geometric = std::fabs(dot(ng, il.wi));
    const bool delta = (lights_.flags(k) & (kEmitterDeltaPosition | kEmitterDeltaDirection)) != 0;
    const float dir_pdf = delta ? 0.0f : bsdf.pdf(wo, il.wi) * continuation;
    const float rev_pdf = bsdf.pdf_reverse(wo, il.wi) * continuation;
    // Tech. report eqs. 38-40.
    const float w_light = dir_pdf / (pick * il.direct_pdf);
    const float w_camera = il.emission_pdf * cos_geometric / (il.direct_pdf * il.cos_light) *
                           (mis_.vm_factor + c.dvcm + c.dvc * rev_pdf);
    const float weight = 1.0f / (w_light + 1.0f + w_camera);
    const SampledSpectrum value = colours_.emitted(lights_.emitter(k), il.radiance) * f *
                                  (weight * cos_shading / (pick * il.direct_pdf));
    if (is_black(value) || !is_finite(value)) return black;
    const bool visible =
        std::isfinite(il.distance)
            ? vcm_visible(*context_.accel, p, ng, p + il.wi * il.distance, il.surface_normal)
            : vcm_visible_at_infinity(*context_.accel, p, ng, il.wi);
    return visible ? value : black;
  }

  SampledSpectrum connect(const CameraState& c, const Vec3& p, const Vec3& ng, const Vec3& wo,
                          const VcmBsdf& bsdf, float continuation) {
    SampledSpectrum sum(0.0f);
    if (begin_ == end_) return sum;
    if (shaded_.empty()) {
      shaded_.resize(end_ - begin_);
      for (size_t i = begin_; i < end_; ++i) {
        const VcmLightVertex& v = pass_.vertices[i];
        ShadedLightVertex& s = shaded_[i - begin_];
        s.sp = shade(context_, context_.accel->interaction(v.hit), v.wo);
        s.continuation = vcm_continuation(s.sp.bsdf, v.wo);
        // The light subpath's wavelengths as they were at the vertex.
        SampledWavelengths light_wl = colours_.wl ? *colours_.wl : SampledWavelengths();
        if (v.terminated) light_wl.terminate_secondary();
        s.bsdf = VcmBsdf(s.sp.bsdf, colours_.wl ? &light_wl : nullptr);
      }
    }
    for (size_t i = begin_; i < end_; ++i) {
      const VcmLightVertex& v = pass_.vertices[i];
      if (v.path_length + c.path_length + 1 > mis_.max_path_length) break;
      const VcmBsdf& lb = shaded_[i - begin_].bsdf;
      const Vec3 d = v.p - p;
      const float dist2 = length_squared(d);
      if (!(dist2 > 0.0f)) continue;
      const float dist = std::sqrt(dist2);
      const Vec3 dir = d / dist;
      const SampledSpectrum fc = bsdf.eval(wo, dir);
      if (is_black(fc)) continue;
      const SampledSpectrum fl = lb.eval(v.wo, -dir) * lb.adjoint_scale(v.wo, -dir);
      if (is_black(fl)) continue;
      const float cos_c = std::fabs(dot(ng, dir)), cos_l = std::fabs(dot(v.ng, dir));
      const float ng_wo = std::fabs(dot(v.ng, v.wo));
      if (!(ng_wo > 1e-9f)) continue;
      const float adjoint = std::fabs(dot(lb.frame().n, v.wo)) / ng_wo;
      const float lc = shaded_[i - begin_].continuation;
      const float cam_dir_pdf = bsdf.pdf(wo, dir) * continuation;
      const float cam_rev_pdf = bsdf.pdf_reverse(wo, dir) * continuation;
      const float light_dir_pdf = lb.pdf(v.wo, -dir) * lc;
      const float light_rev_pdf = lb.pdf_reverse(v.wo, -dir) * lc;
      // Tech. report eqs. 40-42.
      const float w_light =
          cam_dir_pdf * cos_l / dist2 * (mis_.vm_factor + v.dvcm + v.dvc * light_rev_pdf);
      const float w_camera =
          light_dir_pdf * cos_c / dist2 * (mis_.vm_factor + c.dvcm + c.dvc * cam_rev_pdf);
      const float weight = 1.0f / (w_light + 1.0f + w_camera);
      SampledSpectrum value =
          v.throughput * fc * fl *
          (weight * std::fabs(dot(bsdf.frame().n, dir)) * adjoint * cos_l / dist2);
      const float join = colours_.join(c.terminated, v.terminated);
      if (join != 1.0f) value *= join;
      if (is_black(value) || !is_finite(value)) continue;
      if (!vcm_visible(*context_.accel, p, ng, v.p, v.ng)) continue;
      sum += value;
    }
    return sum;
  }

  SampledSpectrum merge(const CameraState& c, const Vec3& p, const Vec3& ng, const Vec3& wo,
                        const VcmBsdf& bsdf, float continuation) const {
    SampledSpectrum sum(0.0f);
    const Vec3 ns = bsdf.frame().n;
    grid_.for_each_within(p, [&](const VcmLightVertex& v) {
      if (v.path_length + c.path_length > mis_.max_path_length) return;
      // Light from either side, as in SPPM's gathering: the BSDF says what reaches `wo` (a
      // translucent or refractive lobe carries what arrives from behind, a diffuse one does
      // not).
      const SampledSpectrum f = bsdf.eval(wo, v.wo);
      if (is_black(f)) return;
      const float ng_wi = std::fabs(dot(ng, v.wo));
      if (!(ng_wi > 1e-9f)) return;
      float weight = 1.0f;
      if (mis_.mode != VcmMode::kPpm) {
        const float cam_dir_pdf = bsdf.pdf(wo, v.wo) * continuation;
        const float cam_rev_pdf = bsdf.pdf_reverse(wo, v.wo) * continuation;
        // Tech. report eqs. 37-39.
        const float w_light = v.dvcm * mis_.vc_factor + v.dvm * cam_dir_pdf;
        const float w_camera = c.dvcm * mis_.vc_factor + c.dvm * cam_rev_pdf;
        weight = 1.0f / (w_light + 1.0f + w_camera);
      }
      // The flux arrived through the geometric cosine; the BSDF's shading cosine replaces it.
      const float join = colours_.join(c.terminated, v.terminated);
      if (join == 1.0f)
        sum += v.throughput * f * (weight * std::fabs(dot(ns, v.wo)) / ng_wi);
      else
        sum += v.throughput * f * (weight * std::fabs(dot(ns, v.wo)) / ng_wi * join);
    });
    return sum * mis_.vm_normalization;
  }

 private:
  const RenderContext& context_;
  const VcmLights& lights_;
  const VcmMis& mis_;
  const VcmColours& colours_;
  const VcmLightPass& pass_;
  const VcmGrid& grid_;
  Sampler& sampler_;
  size_t begin_ = 0, end_ = 0;
  std::vector<ShadedLightVertex> shaded_;
};

}  // namespace

VcmCameraSample trace_vcm_camera_path(const RenderContext& context, const VcmLights& lights,
                                      const VcmCamera& camera, const VcmMis& mis,
                                      const VcmLightPass& pass, uint64_t light_path,
                                      const VcmGrid& grid, int px, int py, Sampler& sampler,
                                      const VcmColours& colours) {
  VcmCameraSample out;
  const Vec2 jitter = camera.filter().sample(sampler.get_2d());
  const Vec2 lens = sampler.get_2d();
  const float inv_w = 1.0f / camera.full_width(), inv_h = 1.0f / camera.full_height();
  Ray ray =
      generate_camera_ray(camera.camera(), (px + jitter.x) * inv_w, (py + jitter.y) * inv_h, lens);
  const float filter_pdf = camera.filter_pdf(jitter.x - 0.5f, jitter.y - 0.5f);
  const float cos_axis = camera.cos_axis(ray.direction);
  if (!(filter_pdf > 0.0f) || !(cos_axis > 0.0f)) return out;
  const float camera_pdf = filter_pdf * camera.raster_to_solid_angle(cos_axis);
  CameraState c;
  if (colours.wl) {
    c.wl = *colours.wl;
    for (int i = 0; i < spectral::kSpectrumSamples; ++i)
      c.throughput[i] = c.wl.active(i) ? 1.0f : 0.0f;
  } else {
    c.throughput = rgb_lanes(Vec3(1.0f));
  }
  // Tech. report eq. 31 for the camera: N light subpaths against the one camera sample.
  c.dvcm = static_cast<float>(mis.light_paths) / camera_pdf;
  CameraPath path(context, lights, mis, colours, pass, light_path, grid, sampler);
  uint32_t mask = kVisibleCamera;
  const float length_scale = context.accel->length_scale();
  SampledSpectrum l(0.0f);  // VcmColours::add's sum
  for (;; ++c.path_length) {
    Hit hit;
    const bool found = context.accel->intersect(ray, mask, &hit);
    if (c.path_length == 1) out.alpha = found ? 1.0f : 0.0f;
    const bool count_emission = mis.use_vc || c.specular_path;
    // Lamps are not in the BVH: every one the segment crosses adds its light (hidden from
    // camera rays, as Blender's lamps are by default).
    if (c.path_length > 1 && count_emission) {
      for (size_t k : lights.lamps()) {
        LightHit h;
        if (!lights.emitter(k).intersect(ray, found ? hit.t : INFINITY, true, &h)) continue;
        const float pick = lights.pick_probability(k);
        const float dvcm = c.dvcm * h.distance * h.distance / h.cos_light;
        const float dvc = c.dvc / h.cos_light;
        colours.add(&l,
                    c.throughput * colours.emitted(lights.emitter(k), h.radiance) *
                        emission_weight(c, h.direct_pdf * pick, h.emission_pdf * pick, dvcm, dvc),
                    c.wl);
      }
    }
    if (!found) {
      if (count_emission)
        for (size_t k : lights.infinite()) {
          LightHit h;
          if (!hit_at_infinity(lights.emitter(k), lights.frame(), ray.direction, &h)) continue;
          const float pick = lights.pick_probability(k);
          colours.add(
              &l,
              c.throughput * colours.emitted(lights.emitter(k), h.radiance) *
                  emission_weight(c, h.direct_pdf * pick, h.emission_pdf * pick, c.dvcm, c.dvc),
              c.wl);
        }
      break;
    }
    const SurfaceInteraction si = context.accel->interaction(hit);
    const Vec3 wo = -ray.direction;
    const ShadingPoint sp = shade(context, si, wo);
    const Vec3 ng = dot(si.ng, wo) >= 0.0f ? si.ng : -si.ng;
    const float cos_in = std::fabs(dot(ng, wo));
    if (!(cos_in > 1e-7f)) break;
    // Tech. report eqs. 34-36.
    c.dvcm *= hit.t * hit.t / cos_in;
    c.dvc /= cos_in;
    c.dvm /= cos_in;
    if (!is_black(sp.emission) && count_emission) {
      LightHit h;
      float weight = c.path_length == 1 ? 1.0f : 0.0f;
      if (c.path_length > 1 && lights.surface() >= 0 &&
          lights.emitter(lights.surface())
              .surface_hit(hit.instance, hit.primitive, hit.t, cos_in, true, &h)) {
        const float pick = lights.pick_probability(lights.surface());
        weight = emission_weight(c, h.direct_pdf * pick, h.emission_pdf * pick, c.dvcm, c.dvc);
      }
      colours.add(&l, c.throughput * colours.surface(sp.emission) * weight, c.wl);
    }
    if (sp.bsdf.empty() || c.path_length >= mis.max_path_length) break;
    const VcmBsdf bsdf(sp.bsdf, colours.wl ? &c.wl : nullptr);
    const float continuation = vcm_continuation(sp.bsdf, wo);
    if (vcm_connectible(sp.bsdf)) {
      if (mis.use_vc) {
        colours.add(&l, c.throughput * path.next_event(c, si.p, ng, wo, bsdf, continuation), c.wl);
        colours.add(&l, c.throughput * path.connect(c, si.p, ng, wo, bsdf, continuation), c.wl);
      }
      if (mis.use_vm) {
        colours.add(&l, c.throughput * path.merge(c, si.p, ng, wo, bsdf, continuation), c.wl);
        if (mis.mode == VcmMode::kPpm) break;  // merging at the first connectible vertex only
      }
    }
    const float u_lobe = sampler.get_1d();
    const Vec2 u = sampler.get_2d();
    const float u_survive = sampler.get_1d();
    VcmBsdfSample bs;
    if (!bsdf.sample(wo, u_lobe, u, &bs) || is_black(bs.weight) || !(bs.pdf > 0.0f)) break;
    if (!(u_survive < continuation)) break;
    const float cos_out = std::fabs(dot(ng, bs.wi));
    const float dir_pdf = bs.pdf * continuation;
    if (bs.is_delta()) {
      c.dvcm = 0.0f;
      c.dvc *= cos_out;
      c.dvm *= cos_out;
    } else {
      const float rev_pdf = bsdf.pdf_reverse(wo, bs.wi) * continuation;
      c.dvc = cos_out / dir_pdf * (c.dvc * rev_pdf + c.dvcm + mis.vm_factor);
      c.dvm = cos_out / dir_pdf * (c.dvm * rev_pdf + c.dvcm * mis.vc_factor + 1.0f);
      c.dvcm = 1.0f / dir_pdf;
      c.specular_path = false;
    }
    c.throughput = c.throughput * bs.weight / continuation;
    if (bs.terminate) {
      c.wl.terminate_secondary();  // the weight is the hero's alone
      c.terminated = true;
    }
    if (is_black(c.throughput)) break;
    mask = visibility_after(bs.flags);
    spawn_ray(si, bs.wi, length_scale, &ray);
  }
  out.radiance = colours.rgb(l);
  return out;
}

}  // namespace photon
