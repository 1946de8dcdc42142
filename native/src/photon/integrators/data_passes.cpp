#include "photon/integrators/data_passes.h"

#include <algorithm>
#include <cmath>

#include "photon/base/optics.h"
#include "photon/base/ray_offset.h"
#include "photon/integrators/denoising_features.h"
#include "photon/lights/emitter_set.h"
#include "photon/render/accel.h"
#include "photon/render/bsdf_lobes.h"
#include "photon/render/material_eval.h"
#include "photon/render/shader_globals.h"
#include "photon/render/shadow_ray.h"
#include "photon/render/world_shader.h"

namespace photon {
namespace {

// Cycles' film conversion of a Depth pass nothing was written to (the background).
constexpr float kBackgroundDepth = 1e10f;

// The random stream of the denoising feature paths' bounces, apart from the image's.
constexpr uint64_t kDenoisingFeatureStream = 0x64656e6f69736531ull;

Vec3 camera_position(const Camera& camera) {
  const auto& m = camera.camera_to_world.m;
  return Vec3(m[0][3], m[1][3], m[2][3]);
}

// The camera looks down its local -Z axis.
Vec3 camera_forward(const Camera& camera) {
  const auto& m = camera.camera_to_world.m;
  return -Vec3(m[0][2], m[1][2], m[2][2]);
}

// Cycles' surface_shader_average_normal: the closures' normals weighted by their mean weight,
// the shading normal when there is no BSDF.
Vec3 average_normal(const ShadingPoint& shading, const Vec3& fallback) {
  const Bsdf& bsdf = shading.bsdf;
  Vec3 sum(0.0f);
  for (int i = 0; i < bsdf.lobe_count(); ++i) {
    const Lobe& lobe = bsdf.lobe(i);
    const Vec3 n = length_squared(lobe.normal) > 0.0f ? lobe.normal : bsdf.frame().n;
    sum += n * std::fabs((lobe.weight.x + lobe.weight.y + lobe.weight.z) / 3.0f);
  }
  if (!(length_squared(sum) > 0.0f) || !is_finite(sum)) return fallback;
  return normalize(sum);
}

Vec3 clamp01(const Vec3& v) {
  return Vec3(std::clamp(v.x, 0.0f, 1.0f), std::clamp(v.y, 0.0f, 1.0f),
              std::clamp(v.z, 0.0f, 1.0f));
}

float average(const Vec3& v) {
  return (v.x + v.y + v.z) / 3.0f;
}

// Cycles' mist: clamp((d - start) / depth) shaped by the falloff exponent, with the same
// special cases (so the common falloffs match it exactly).
float mist_amount(float distance, const DataPassSettings& s) {
  const float inv_depth = s.mist_depth > 0.0f ? 1.0f / s.mist_depth : 0.0f;
  float mist = std::clamp((distance - s.mist_start) * inv_depth, 0.0f, 1.0f);
  if (s.mist_falloff == 1.0f) {
  } else if (s.mist_falloff == 2.0f) {
    mist = mist * mist;
  } else if (s.mist_falloff == 0.5f) {
    mist = std::sqrt(mist);
  } else {
    mist = std::pow(mist, s.mist_falloff);
  }
  return mist;
}

// The closure weights of the hit's diffuse, glossy and transmission closures, as Cycles'
// surface_shader_diffuse / _glossy / _transmission sum them (translucent and sheen count as
// diffuse). A glass lobe stands for Cycles' two closures: reflection weighted by the dielectric
// Fresnel of the shading normal, refraction by the rest.
struct ClosureColors {
  Vec3 diffuse{0.0f}, glossy{0.0f}, transmission{0.0f};
};

ClosureColors closure_colors(const Bsdf& bsdf, const Vec3& wo) {
  ClosureColors c;
  for (int i = 0; i < bsdf.lobe_count(); ++i) {
    const Lobe& lobe = bsdf.lobe(i);
    switch (lobe.type) {
      case LobeType::kLambert:
      case LobeType::kBurleyDiffuse:
      case LobeType::kOrenNayar:
      case LobeType::kSheen:
      case LobeType::kTranslucent:
        c.diffuse += lobe.weight;
        break;
      case LobeType::kGgxReflection:
      case LobeType::kVelvet:  // a glossy closure in Cycles
        c.glossy += lobe.weight;
        break;
      case LobeType::kGgxRefraction:
        c.transmission += lobe.weight;
        break;
      case LobeType::kGgxGlass: {
        const Vec3 n = length_squared(lobe.normal) > 0.0f ? lobe.normal : bsdf.frame().n;
        const float eta = bsdf.front_facing() ? lobe.ior : 1.0f / lobe.ior;
        const float f = fresnel_dielectric(std::clamp(dot(wo, n), 0.0f, 1.0f), eta);
        c.glossy += lobe.weight * f;
        c.transmission += lobe.weight * (1.0f - f);
        break;
      }
      case LobeType::kGgxDielectric: {
        // Principled v2's dielectric: reflectance and tinted transmittance at the normal.
        const Vec3 n = length_squared(lobe.normal) > 0.0f ? lobe.normal : bsdf.frame().n;
        const float eta = bsdf.front_facing() ? lobe.ior : 1.0f / lobe.ior;
        Vec3 r, t;
        bsdf_lobes::dielectric_split(lobe, lobe.f0, lobe.tint, std::clamp(dot(wo, n), 0.0f, 1.0f),
                                     eta, &r, &t);
        c.glossy += lobe.weight * r;
        c.transmission += lobe.weight * t;
        break;
      }
      case LobeType::kTransparent:
        break;
    }
  }
  return c;
}

void put3(float* p, const Vec3& v) {
  p[0] = v.x;
  p[1] = v.y;
  p[2] = v.z;
}

void add3(float* p, const Vec3& v) {
  p[0] += v.x;
  p[1] += v.y;
  p[2] += v.z;
}

}  // namespace

DataPassRow::DataPassRow(const RenderContext& context, const DataPassSettings& settings,
                         size_t width)
    : context_(context),
      settings_(settings),
      width_(width),
      floats_(data_pass_floats(settings.mask)),
      sums_(width * floats_),
      mist_(width),
      first_hit_(width),
      pixel_floats_(data_pass_pixel_floats(settings)) {
  for (const CryptoKind& kind : cryptomatte_kinds()) {
    if (!(settings.cryptomatte & kind.bit) || settings.cryptomatte_depth <= 0) continue;
    crypto_kinds_.push_back(kind.bit);
    crypto_rows_.emplace_back(width, settings.cryptomatte_depth);
  }
  for (const ShaderAovPass& aov : settings.aovs) {
    aov_offsets_.push_back(aov_floats_);
    aov_floats_ += aov.color ? 4 : 1;
  }
  if (aov_floats_ > 0 && context.scene) {
    // Each AOV Output node writes the pass of its name and kind (Cycles' get_aov_offset); a
    // node whose name the view layer does not list writes nothing.
    const auto writes_of = [&settings](const std::vector<MaterialAov>& outputs) {
      std::vector<std::pair<int, int>> writes;
      for (size_t k = 0; k < outputs.size(); ++k)
        for (size_t j = 0; j < settings.aovs.size(); ++j)
          if (settings.aovs[j].name == outputs[k].name &&
              settings.aovs[j].color == outputs[k].color)
            writes.emplace_back(static_cast<int>(k), static_cast<int>(j));
      return writes;
    };
    for (const Material& m : context.scene->materials) {
      std::vector<std::pair<int, int>> writes = writes_of(m.aovs);
      if (!writes.empty()) material_aovs_.emplace(&m, std::move(writes));
    }
    if (!context.settings->transparent_background)
      world_aovs_ = writes_of(context.scene->world.aovs);
  }
  aov_sums_.assign(width * aov_floats_, 0.0f);
}

DataPassRow::~DataPassRow() = default;

void DataPassRow::clear() {
  std::fill(sums_.begin(), sums_.end(), 0.0f);
  std::fill(mist_.begin(), mist_.end(), 0.0f);
  std::fill(first_hit_.begin(), first_hit_.end(), 0);
  for (CryptomatteRow& row : crypto_rows_) row.clear();
  std::fill(aov_sums_.begin(), aov_sums_.end(), 0.0f);
}

void DataPassRow::add_denoising_features(float* px, int sample, uint64_t pixel_index,
                                         const Ray& ray, const CameraHit& first) const {
  const RenderSettings& s = *context_.settings;
  Sampler sampler(hash_combine(s.seed, kDenoisingFeatureStream), pixel_index,
                  static_cast<uint32_t>(sample), static_cast<uint32_t>(s.samples));
  const DenoisingFeatures f = trace_denoising_features(context_, ray, first, sampler);
  const uint32_t mask = settings_.mask;
  if (mask & kPassDenoisingNormal)
    add3(px + data_pass_offset(mask, kPassDenoisingNormal), f.normal);
  if (mask & kPassDenoisingAlbedo)
    add3(px + data_pass_offset(mask, kPassDenoisingAlbedo), f.albedo);
  if (mask & kPassDenoisingDepth) px[data_pass_offset(mask, kPassDenoisingDepth)] += f.depth;
}

void DataPassRow::add_cryptomatte(size_t i, const SurfaceInteraction& si, float weight) {
  for (size_t k = 0; k < crypto_kinds_.size(); ++k) {
    float id = 0.0f;
    switch (crypto_kinds_[k]) {
      case kCryptoObject:
        id = si.object ? si.object->cryptomatte_object : 0.0f;
        break;
      case kCryptoMaterial:
        id = si.mat && si.mat != &Scene::default_material()
                 ? si.mat->cryptomatte_material
                 : settings_.cryptomatte_default_material;
        break;
      case kCryptoAsset:
        id = si.object ? si.object->cryptomatte_asset : 0.0f;
        break;
    }
    crypto_rows_[k].add(i, id, weight);
  }
}

namespace {

// An owner's AOV values: on the stack for up to 16 outputs.
class AovValues {
 public:
  explicit AovValues(size_t count) {
    if (count > kStack) heap_.resize(count);
  }
  Vec3* data() { return heap_.empty() ? stack_ : heap_.data(); }

 private:
  static constexpr size_t kStack = 16;
  Vec3 stack_[kStack];
  std::vector<Vec3> heap_;
};

}  // namespace

void DataPassRow::add_aov_values(size_t i, const std::vector<std::pair<int, int>>& writes,
                                 const Vec3* values) {
  float* px = aov_sums_.data() + i * aov_floats_;
  for (const auto& [k, j] : writes) {
    float* p = px + aov_offsets_[j];
    if (settings_.aovs[j].color) {
      add3(p, values[k]);
      p[3] += 1.0f;  // Cycles writes alpha 1 with the colour
    } else {
      p[0] += values[k].x;
    }
  }
}

void DataPassRow::add_aovs(size_t i, const SurfaceInteraction& si, const Vec3& wo,
                           const ShadeRay& ray) {
  if (!si.mat) return;
  const auto found = material_aovs_.find(si.mat);
  if (found == material_aovs_.end()) return;
  AovValues values(si.mat->aovs.size());
  eval_material_aovs(*si.mat, si, wo, *context_.accel, context_.textures, ray, values.data());
  add_aov_values(i, found->second, values.data());
}

void DataPassRow::add_world_aovs(size_t i, const Vec3& direction) {
  const World& world = context_.scene->world;
  AovValues values(world.aovs.size());
  world_aovs(world, direction, context_.textures, values.data());
  add_aov_values(i, world_aovs_, values.data());
}

void DataPassRow::add_lamps(Ray ray, float t_end, const Vec3& throughput, float* px) const {
  // Lamps the camera sees (Object > Visibility > Camera) go into Emit; Cycles' camera rays
  // pass through a lamp they meet and go on to what lies behind it, each lamp on the way
  // counted once.
  if (!context_.emitters) return;
  const uint32_t mask = settings_.mask;
  float t_lamp;
  Vec3 radiance;
  for (int k = 0;
       k < 16 && context_.emitters->intersect_lamps(ray, t_end, kVisibleCamera, &t_lamp, &radiance);
       ++k) {
    add3(px + data_pass_offset(mask, kPassEmission), throughput * radiance);
    ray.tmin = std::nextafter(t_lamp, INFINITY);
  }
}

void DataPassRow::add(size_t i, int sample, uint64_t pixel_index, const Ray& camera_ray,
                      const CameraHit& first) {
  const uint32_t mask = settings_.mask;
  const bool crypto = !crypto_rows_.empty();
  const bool aovs = !material_aovs_.empty() || !world_aovs_.empty();
  if (!mask && !crypto && !aovs) return;
  // Written once per pixel (first sample) or once per sample, at the first hit opaque enough.
  constexpr uint32_t kFirstSample =
      kPassDepth | kPassPosition | kPassObjectIndex | kPassMaterialIndex;
  constexpr uint32_t kSingle = kFirstSample | kPassNormal | kPassUv;
  // Summed over every hit seen straight through Transparent closures, times the throughput.
  constexpr uint32_t kAlongPath =
      kPassMist | kPassDiffuseColor | kPassGlossyColor | kPassTransmissionColor | kPassEmission;
  const uint32_t single = mask & (sample == 0 ? kSingle : kSingle & ~kFirstSample);
  const Camera& camera = context_.scene->camera;
  float* px = sums_.data() + i * floats_;
  if (mask & (kPassDenoisingNormal | kPassDenoisingAlbedo | kPassDenoisingDepth))
    add_denoising_features(px, sample, pixel_index, camera_ray, first);
  const bool along_path = (mask & kAlongPath) || crypto;

  Ray ray = camera_ray;
  Hit hit = first.hit;
  bool found = first.found;
  bool single_done = single == 0 && !aovs;  // Cycles' PATH_RAY_SINGLE_PASS_DONE
  Vec3 throughput(1.0f);
  float path_length = 0.0f;
  // A camera path's transparent hits count towards its depth, as in the image (path_walker.h).
  const int max_hits = std::max(context_.settings->max_depth, 0) + 1;
  for (int n = 0; n < max_hits; ++n) {
    if (mask & kPassEmission) add_lamps(ray, found ? hit.t : ray.tmax, throughput, px);
    if (!found && !single_done && !world_aovs_.empty()) add_world_aovs(i, ray.direction);
    if (!found || (single_done && !along_path)) break;
    const SurfaceInteraction si = context_.accel->interaction(hit);
    const Vec3 to_point = si.p - camera_position(camera);
    path_length += hit.t;
    ShadeRay shade_ray;
    shade_ray.flags = kRayCamera;
    shade_ray.length = path_length;
    shade_ray.transparent_depth = static_cast<uint16_t>(n);
    const Vec3 wo = normalize(-ray.direction);
    const ShadingPoint shading =
        shade_surface(si, wo, *context_.accel, context_.textures, shade_ray);
    // The surface's alpha is 1 minus it, clamped.
    const Vec3 transparency = transparent_weight(shading.bsdf);
    const Vec3 alpha = clamp01(Vec3(1.0f) - transparency);

    // Cycles' shaders write AOVs at every hit before the single-sample passes are done.
    if (!single_done && aovs) add_aovs(i, si, wo, shade_ray);
    // Cycles writes the single-sample passes at the first hit whose alpha reaches View Layer >
    // Passes > Alpha Threshold (any hit when the threshold is 0).
    if (!single_done &&
        (settings_.alpha_threshold <= 0.0f || average(alpha) >= settings_.alpha_threshold)) {
      single_done = true;
      if (sample == 0) {
        first_hit_[i] = 1;
        // Cycles' camera_z_depth: the distance along the view axis.
        if (mask & kPassDepth)
          px[data_pass_offset(mask, kPassDepth)] = dot(to_point, camera_forward(camera));
        if (mask & kPassPosition)
          put3(px + data_pass_offset(mask, kPassPosition), si.p + settings_.origin);
        if (mask & kPassObjectIndex)
          px[data_pass_offset(mask, kPassObjectIndex)] = si.object ? si.object->pass_index : 0.0f;
        if (mask & kPassMaterialIndex)
          px[data_pass_offset(mask, kPassMaterialIndex)] = si.mat ? si.mat->pass_index : 0.0f;
      }
      if (mask & kPassUv) {
        // Cycles' primitive_uv: (u, v, 1) on a mesh with a UV map, zero without one.
        const bool has_uv = si.mesh && !si.mesh->corner_uvs.empty();
        add3(px + data_pass_offset(mask, kPassUv),
             has_uv ? Vec3(si.uv.x, si.uv.y, 1.0f) : Vec3(0.0f));
      }
      if (mask & kPassNormal) {
        const Vec3 ns = dot(si.ns, wo) < 0.0f ? -si.ns : si.ns;
        add3(px + data_pass_offset(mask, kPassNormal), average_normal(shading, ns));
      }
    }
    if (mask & kPassMist) {
      // Cycles' camera_distance: along the view axis for an orthographic camera.
      const float distance = camera.projection == Projection::kOrthographic
                                 ? std::fabs(dot(to_point, camera_forward(camera)))
                                 : length(to_point);
      mist_[i] += (1.0f - mist_amount(distance, settings_)) * average(throughput * alpha);
    }
    if (mask & (kPassDiffuseColor | kPassGlossyColor | kPassTransmissionColor)) {
      const ClosureColors colors = closure_colors(shading.bsdf, wo);
      if (mask & kPassDiffuseColor)
        add3(px + data_pass_offset(mask, kPassDiffuseColor), throughput * colors.diffuse);
      if (mask & kPassGlossyColor)
        add3(px + data_pass_offset(mask, kPassGlossyColor), throughput * colors.glossy);
      if (mask & kPassTransmissionColor)
        add3(px + data_pass_offset(mask, kPassTransmissionColor), throughput * colors.transmission);
    }
    if (mask & kPassEmission)
      add3(px + data_pass_offset(mask, kPassEmission), throughput * shading.emission);
    if (crypto) add_cryptomatte(i, si, average(throughput) * (1.0f - average(transparency)));

    // On through the Transparent closures (Cycles samples them as a straight-on bounce; their
    // expected contribution is the throughput times their weight).
    throughput = throughput * transparency;
    if (!(std::max({throughput.x, throughput.y, throughput.z}) > 0.0f)) break;
    ray.origin = offset_ray_origin(si.p, si.ng, ray.direction, context_.accel->length_scale());
    ray.tmin = 0.0f;
    ray.tmax = INFINITY;
    found = context_.accel->intersect(ray, kVisibleCamera, &hit);
  }
}

void DataPassRow::finish(int samples, float* out) const {
  const uint32_t mask = settings_.mask;
  const float inv = 1.0f / std::max(samples, 1);
  const int crypto_floats = 4 * cryptomatte_layers(settings_.cryptomatte_depth);
  for (size_t i = 0; i < width_; ++i) {
    const float* src = sums_.data() + i * floats_;
    float* dst = out + i * pixel_floats_;
    std::copy(src, src + floats_, dst);
    if (mask & kPassDepth && !first_hit_[i])
      dst[data_pass_offset(mask, kPassDepth)] = kBackgroundDepth;
    for (uint32_t bit :
         {kPassNormal, kPassUv, kPassDiffuseColor, kPassGlossyColor, kPassTransmissionColor,
          kPassEmission, kPassDenoisingNormal, kPassDenoisingAlbedo}) {
      if (!(mask & bit)) continue;
      // Emit is light: the film's exposure scales it as it scales Combined (Cycles' passes
      // with use_exposure); colours, albedos and geometry are not light.
      const float scale = bit == kPassEmission ? inv * context_.settings->exposure : inv;
      float* p = dst + data_pass_offset(mask, bit);
      for (int c = 0; c < 3; ++c) p[c] *= scale;
    }
    if (mask & kPassMist) dst[data_pass_offset(mask, kPassMist)] = 1.0f - mist_[i] * inv;
    if (mask & kPassDenoisingDepth) dst[data_pass_offset(mask, kPassDenoisingDepth)] *= inv;
    for (size_t k = 0; k < crypto_rows_.size(); ++k)
      crypto_rows_[k].write(i, samples, dst + floats_ + k * crypto_floats);
    // Shader AOVs are not light: averaged without the exposure (as Cycles' AOV passes).
    const float* aov = aov_sums_.data() + i * aov_floats_;
    float* aov_dst = dst + floats_ + crypto_rows_.size() * crypto_floats;
    for (int c = 0; c < aov_floats_; ++c) aov_dst[c] = aov[c] * inv;
  }
}

}  // namespace photon
