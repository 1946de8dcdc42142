// Lighting bakes: the view-independent radiance of given surface points, computed
// once by an integrator that has such a solution (photon maps, radiosity) and written by the
// add-on into Blender data (colour attributes, lightmaps) for real-time viewing.
// A BakeSession runs it on a background thread (a Job, like RenderSession): prepare the integrator
// once (progress, cancel, stop early), then shade every point in parallel. Results do not depend on
// the thread count: point i always draws from the sampler streams (seed, 3i + {0, 1, 2}).
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "photon/integrators/integrator.h"
#include "photon/scene/scene.h"
#include "photon/session/job.h"

namespace photon {

// A surface point addressed as the caller numbers things: Scene::instances index, triangle in
// the order given to the mesh (before invalid triangles were dropped), and barycentrics as
// Embree's: p = (1-u-v) p0 + u p1 + v p2.
struct BakePoint {
  uint32_t instance = 0;
  uint32_t triangle = 0;
  float u = 0.0f, v = 0.0f;
};

struct BakeOptions {
  // A colour attribute or lightmap holds one value per point, but a surface has two sides. With
  // this set both sides are estimated with a few samples and the back side is baked when it is
  // clearly (2x) brighter (a room modelled with outward normals is still baked on its lit
  // inside); otherwise the side the normal faces.
  bool brighter_side = true;
};

enum BakeStatus : uint8_t {
  kBakeOk = 0,
  kBakeInvalidPoint = 1,  // no such instance/triangle (or it was dropped as degenerate)
  kBakeUnsupported = 2,   // the integrator has no view-independent radiance there (mirror, glass)
  kBakeNonFinite = 3,     // the estimate was NaN or infinite
  kBakeNotDone = 4,       // cancelled before this point was shaded
};

struct BakeResult {
  std::vector<Vec3> radiance;  // per point; 0 unless status is kBakeOk
  std::vector<Vec3> position;  // world-space point (0 for invalid points)
  std::vector<Vec3> normal;    // shading normal of the baked side (the side that was kept)
  std::vector<uint8_t> status;
  std::vector<std::string> warnings;
  // Set when nothing could be baked because the integrator cannot bake at all.
  std::string error;
  bool cancelled = false;
  double build_seconds = 0.0, prepare_seconds = 0.0, bake_seconds = 0.0;
  double locate_seconds = 0.0;  // resolving points and choosing their side
  double share_seconds = 0.0;   // Integrator::prepare_bake (irradiance cache among the points)
  int threads = 0;
  PrepareStats integrator_stats;
};

// The bake itself, synchronous. `settings.samples` is the number of samples per point (direct
// light and final gathering); the camera and image size are ignored. `control.cancel` also
// stops the shading of points; `on_prepared` (optional) runs when shading starts, and
// `points_done` (optional) counts shaded points.
BakeResult bake_points(const Scene& scene, const RenderSettings& settings,
                       const BakeOptions& options, const std::vector<BakePoint>& points,
                       const PrepareControl& control,
                       const std::function<void()>& on_prepared = nullptr,
                       std::atomic<size_t>* points_done = nullptr);

class BakeSession : public Job {
 public:
  BakeSession(std::shared_ptr<const Scene> scene, const RenderSettings& settings,
              const BakeOptions& options, std::vector<BakePoint> points);
  ~BakeSession() override;  // cancels and waits

  // start(), wait(), cancel(), stop_preparation() (end photon tracing early and bake with what
  // was traced), progress (of the preparation, then of the points shaded) and status come
  // from Job.

  // The result; valid once finished() (empty before). A failure of the work is its error.
  BakeResult result() const;

 private:
  void run() override;

  std::shared_ptr<const Scene> scene_;
  RenderSettings settings_;
  BakeOptions options_;
  std::vector<BakePoint> points_;
  mutable std::mutex mutex_;  // result_
  BakeResult result_;
};

}  // namespace photon
