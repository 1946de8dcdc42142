// The interface every rendering algorithm implements (after Nori): prepare once per render,
// then answer radiance queries for camera rays from any thread.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "photon/accel.h"
#include "photon/lights.h"
#include "photon/math.h"
#include "photon/rng.h"
#include "photon/scene.h"

namespace photon {

enum class IntegratorType : uint8_t { kRayTrace };

struct RenderSettings {
  int full_width = 64, full_height = 64;  // whole frame in pixels
  // Pixel rectangle to render (Blender's render border), [x0, x1) x [y0, y1), y downwards.
  int x0 = 0, y0 = 0, x1 = 64, y1 = 64;
  int samples = 16;    // camera samples per pixel
  int max_depth = 8;   // specular bounces after the camera ray
  uint64_t seed = 0;
  int threads = 0;     // 0 = all cores
  int tile_size = 64;
  bool transparent_background = false;
  IntegratorType integrator = IntegratorType::kRayTrace;
};

// Read-only state shared by all threads during a render.
struct RenderContext {
  const Scene* scene = nullptr;
  const Accel* accel = nullptr;
  const LightSet* lights = nullptr;
  const RenderSettings* settings = nullptr;
};

struct RadianceSample {
  Vec3 radiance;
  float alpha = 0.0f;  // 1 when the camera ray hit something that is not background
};

// The first intersection of a camera ray, traced beforehand together with its neighbours.
struct CameraHit {
  bool found = false;
  Hit hit;
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  // Runs once before pixels are rendered (photon tracing, radiosity solve, ...). Long
  // preparations poll `cancel` and return early when it is set.
  virtual void prepare(const RenderContext& context, const std::atomic<bool>& cancel) {
    (void)context;
    (void)cancel;
  }
  // Radiance arriving along a camera ray whose first hit is already known (the renderer traces
  // camera rays in coherent batches). Must be thread-safe and deterministic in `sampler`.
  virtual RadianceSample radiance_from_hit(const RenderContext& context, const Ray& camera_ray,
                                           const CameraHit& first, Sampler& sampler) const = 0;

};

std::unique_ptr<Integrator> make_integrator(IntegratorType type);

}  // namespace photon
