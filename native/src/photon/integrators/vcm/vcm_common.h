// What every part of the VCM integrator shares (Georgiev, Krivanek, Davidovic & Slusallek 2012,
// "Light transport simulation with vertex connection and merging"; the recursive MIS quantities
// dVCM, dVC, dVM of Davidovic et al. 2012, "Implementing vertex connection and merging", which
// make every strategy's weight O(1) per vertex). Weights use the balance heuristic.
//
// Conventions: every cosine in a MIS quantity is to the geometric normal (densities converted
// between solid angle and area); path contributions use the shading normal in the BSDF's cosine
// and, on light subpaths, Veach's adjoint correction (1997, sec. 5.3, eq. 5.17) so light and
// camera subpaths estimate the same integral.
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "photon/base/distribution.h"
#include "photon/integrators/integrator.h"
#include "photon/lights/emitter.h"
#include "photon/render/accel.h"
#include "photon/render/bsdf.h"
#include "photon/render/spectral_bsdf.h"

namespace photon {

// Georgiev et al. 2012 sec. 5: the strategies' densities relative to each other. With N light
// subpaths per iteration and merging radius r, eta = pi r^2 N (eq. 20 with one camera path per
// pixel); vertex connection is off (vc_factor 0) in PPM mode, merging (vm_factor 0) in BPT mode.
struct VcmMis {
  VcmMode mode = VcmMode::kVcm;
  bool use_vc = true, use_vm = true;
  float vm_factor = 0.0f;  // eta
  float vc_factor = 0.0f;  // 1 / eta
  float radius = 0.0f;
  float vm_normalization = 0.0f;  // 1 / (pi r^2 N)
  uint64_t light_paths = 1;
  int max_path_length = 64;  // segments from the camera to the light

  static VcmMis make(VcmMode mode, float radius, uint64_t light_paths, int max_path_length);
};

// Survival probability at a vertex (Russian roulette): the BSDF's albedo seen from `wo`,
// independent of the path, so the reverse density of the vertex uses it too (SmallVCM's
// continuation probability).
inline float vcm_continuation(const Bsdf& bsdf, const Vec3& wo) {
  return std::clamp(max_component(bsdf.albedo(wo)), 0.0f, 1.0f);
}

// Colours along VCM's subpaths are SampledSpectrum: in RGB mode R, G, B in lanes 0-2 and 0 in
// lane 3 (the arithmetic is RGB's, lane by lane, so the image is the RGB renderer's), in
// spectral mode the iteration's wavelengths, shared by every subpath of the iteration so that
// light and camera subpaths meet at the same wavelengths. A subpath through a dispersive
// refraction keeps only the hero (lane 0): its wavelengths' pdfs are terminated
// (SampledWavelengths), and a light vertex remembers it (VcmLightVertex::terminated).
inline SampledSpectrum rgb_lanes(const Vec3& c) {
  SampledSpectrum s(0.0f);
  s[0] = c.x, s[1] = c.y, s[2] = c.z;
  return s;
}

struct VcmColours {
  const SampledWavelengths* wl = nullptr;  // the iteration's; null in RGB mode

  SampledSpectrum emitted(const Emitter& e, const Vec3& rgb) const {
    return wl ? e.spectrum(rgb, *wl) : rgb_lanes(rgb);
  }
  SampledSpectrum surface(const Vec3& rgb) const {
    return wl ? spectral::illuminant_at(rgb, *wl) : rgb_lanes(rgb);
  }
  // Adds light `l` a subpath gathered to `sum`: in RGB mode as it is, in spectral mode over
  // the subpath's wavelength pdfs (`path_wl`: a copy of wl, maybe terminated since).
  void add(SampledSpectrum* sum, const SampledSpectrum& l,
           const SampledWavelengths& path_wl) const {
    if (wl)
      *sum += l.safe_div(path_wl.pdf());
    else
      *sum += l;
  }
  // Such a sum in Rec.709.
  Vec3 rgb(const SampledSpectrum& sum) const;
  // The factor of a connection or merge between a camera subpath and a light vertex: a light
  // subpath that kept only the hero weighs it by the wavelengths in use, unless the camera
  // subpath (whose pdfs convert the result) terminated too.
  float join(bool camera_terminated, bool light_terminated) const {
    return wl && light_terminated && !camera_terminated ? static_cast<float>(wl->active_count())
                                                        : 1.0f;
  }
};

struct VcmBsdfSample {
  Vec3 wi;
  SampledSpectrum weight{0.0f};
  float pdf = 0.0f;
  uint8_t flags = 0;
  bool terminate = false;
  bool transparent = false;  // a Transparent lobe: straight through
  bool is_delta() const { return (flags & kLobeSpecular) != 0; }
};

// A vertex's BSDF in VCM's colours: the RGB BSDF in lanes, or the BSDF at the wavelengths.
class VcmBsdf {
 public:
  VcmBsdf() = default;
  // `bsdf` must outlive this object.
  VcmBsdf(const Bsdf& bsdf, const SampledWavelengths* wl) : rgb_(&bsdf) {
    if (wl) spectral_.emplace(bsdf, *wl);
  }
  const Bsdf& rgb() const { return *rgb_; }
  const Frame& frame() const { return rgb_->frame(); }
  SampledSpectrum eval(const Vec3& wo, const Vec3& wi) const {
    return spectral_ ? spectral_->eval(wo, wi) : rgb_lanes(rgb_->eval(wo, wi));
  }
  float pdf(const Vec3& wo, const Vec3& wi) const {
    return spectral_ ? spectral_->pdf(wo, wi) : rgb_->pdf(wo, wi);
  }
  // Bsdf::pdf_reverse at VCM's colours: the density of sampling wo from wi's side.
  float pdf_reverse(const Vec3& wo, const Vec3& wi) const;
  bool sample(const Vec3& wo, float u_lobe, Vec2 u, VcmBsdfSample* out) const;
  // Bsdf::adjoint_scale: what light subpaths take besides f from wo's side to wi's.
  SampledSpectrum adjoint_scale(const Vec3& wo, const Vec3& wi) const {
    return spectral_ ? spectral_->adjoint_scale(wo, wi)
                     : SampledSpectrum(rgb_->adjoint_scale(wo, wi));
  }

 private:
  const Bsdf* rgb_ = nullptr;
  std::optional<SpectralBsdf> spectral_;
};

// Whether a BSDF has a lobe that connections and merging can evaluate.
inline bool vcm_connectible(const Bsdf& bsdf) {
  return (bsdf.flags() & (kLobeDiffuse | kLobeGlossy)) != 0;
}

// Veach 1997 eq. 5.17: a light subpath scattering from `w_prev` (towards the light) to `w_next`
// at a point with shading normal ns and geometric normal ng carries f |ns.w_next| / pdf times
// this, so its contribution is that of the adjoint BSDF.
inline float adjoint_correction(const Vec3& ns, const Vec3& ng, const Vec3& w_prev,
                                const Vec3& w_next) {
  const float den = std::fabs(dot(ng, w_prev)) * std::fabs(dot(ns, w_next));
  if (!(den > 1e-9f)) return 0.0f;
  return std::fabs(dot(ns, w_prev)) * std::fabs(dot(ng, w_next)) / den;
}

// The emitters light subpaths start from and light samples pick, by power (one distribution for
// both, so a camera path that meets an emitter knows how likely each technique was).
// What a ray that left the scene meets of light at infinity `e` (a sun's disc, the world), with
// its bidirectional densities; false when it meets nothing there.
bool hit_at_infinity(const Emitter& e, const PhotonFrame& frame, const Vec3& direction,
                     LightHit* out);

class VcmLights {
 public:
  VcmLights(const RenderContext& context, const PhotonFrame& frame,
            std::vector<std::string>* warnings);
  bool empty() const { return emitters_.empty(); }
  size_t size() const { return emitters_.size(); }
  const Emitter& emitter(size_t i) const { return *emitters_[i]; }
  uint8_t flags(size_t i) const { return flags_[i]; }
  float pick_probability(size_t i) const { return pick_.probability(i); }
  size_t pick(float u, float* remapped) const { return pick_.sample(u, remapped); }
  const PhotonFrame& frame() const { return frame_; }
  // The emissive triangles (-1: none), the lamps a ray can meet, and the lights at infinity.
  long surface() const { return surface_; }
  const std::vector<size_t>& lamps() const { return lamps_; }
  const std::vector<size_t>& infinite() const { return infinite_; }

 private:
  std::vector<const Emitter*> emitters_;
  std::vector<uint8_t> flags_;
  Distribution1D pick_;
  PhotonFrame frame_;
  long surface_ = -1;
  std::vector<size_t> lamps_, infinite_;
};

// A light subpath vertex on a surface with a connectible BSDF.
struct VcmLightVertex {
  Hit hit;  // to shade the point again for connections
  Vec3 p, ng;
  Vec3 wo;                     // towards the previous vertex (the light)
  SampledSpectrum throughput;  // emitted radiance over the subpath's density, to this point
  float dvcm = 0.0f, dvc = 0.0f, dvm = 0.0f;
  int path_length = 0;      // segments from the light
  bool terminated = false;  // spectral: a dispersive refraction left only the hero wavelength
};

// A ray from `p` (geometric normal ng) to `q` (normal nq, zero for a point off the surfaces)
// unblocked, both ends offset off their surfaces.
bool vcm_visible(const Accel& accel, const Vec3& p, const Vec3& ng, const Vec3& q, const Vec3& nq);
// A ray from `p` leaving the scene in direction w unblocked.
bool vcm_visible_at_infinity(const Accel& accel, const Vec3& p, const Vec3& ng, const Vec3& w);

}  // namespace photon
