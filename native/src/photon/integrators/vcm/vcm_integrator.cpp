#include "photon/integrators/vcm/vcm_integrator.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "photon/integrators/iterative_frame.h"
#include "photon/integrators/merge_radius.h"
#include "photon/integrators/photon_map/photon_memory.h"
#include "photon/integrators/photon_map/photon_sources.h"
#include "photon/integrators/spectral_path.h"
#include "photon/integrators/vcm/vcm_camera_paths.h"
#include "photon/integrators/vcm/vcm_grid.h"
#include "photon/integrators/vcm/vcm_light_paths.h"

namespace photon {
namespace {

using Clock = std::chrono::steady_clock;
constexpr uint64_t kCameraStream = 0x56434D43414D;      // "VCMCAM"
constexpr uint64_t kWavelengthStream = 0x56434D57564C;  // "VCMWVL"
// Russian roulette ends paths long before this; it bounds chains between perfect mirrors.
constexpr int kMaxPathLength = 64;
// Automatic initial radius, in pixel footprints at the median depth the camera sees.
constexpr float kAutoRadiusPixels = 2.0f;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

const std::atomic<bool>& cancel_flag(const RenderControl& control) {
  static const std::atomic<bool> never{false};
  return control.cancel ? *control.cancel : never;
}

}  // namespace

VcmIntegrator::VcmIntegrator() = default;
VcmIntegrator::~VcmIntegrator() = default;

void VcmIntegrator::prepare(const RenderContext& context, const PrepareControl& control) {
  const PhotonSources sources(context);
  scene_frame_.center = sources.scene_center();
  scene_frame_.radius = sources.scene_radius();
  std::vector<std::string> warnings;
  lights_ = std::make_unique<VcmLights>(context, scene_frame_, &warnings);
  for (const std::string& w : warnings)
    if (control.warn) control.warn(w);
}

IterationStats VcmIntegrator::render_stats() const {
  return use_fallback_ ? fallback_->render_stats() : stats_;
}

float VcmIntegrator::radius(int iteration) const {
  return initial_radius_ * std::pow(static_cast<float>(iteration + 1), 0.5f * (alpha_ - 1.0f));
}

void VcmIntegrator::plan_light_paths(const RenderContext& context, const RenderControl& control) {
  const RenderSettings& s = *context.settings;
  const uint64_t requested = std::max<uint64_t>(s.vcm_light_paths, 1);
  const double budget = kVcmMemoryFraction * static_cast<double>(available_memory_bytes());
  const VcmMis mis = VcmMis::make(s.vcm_mode, radius(0), requested, kMaxPathLength);
  const VcmLightPathPlan plan =
      plan_vcm_light_paths(context, *lights_, *camera_, mis, requested, budget);
  light_paths_ = plan.light_paths;
  if (light_paths_ < requested)
    control.report_warning("vcm_light_paths = " + std::to_string(requested) + " would need about " +
                           bytes_text(plan.requested_bytes) +
                           " for one iteration's light subpaths, more than half of the memory "
                           "available (" +
                           bytes_text(2.0 * budget) + "): " + std::to_string(light_paths_) +
                           " light subpaths per iteration are traced instead");
}

bool VcmIntegrator::iterate(const RenderContext& context, Film& film, uint32_t iteration,
                            const std::atomic<bool>& cancel) {
  const RenderSettings& s = *context.settings;
  const VcmMis mis =
      VcmMis::make(s.vcm_mode, radius(static_cast<int>(iteration)), light_paths_, kMaxPathLength);
  // Spectral mode: one set of wavelengths for the iteration's light and camera subpaths, so
  // connections and merges join them at the same wavelengths; stratified over the iterations.
  SampledWavelengths wavelengths;
  VcmColours colours;
  if (spectral_mode(context)) {
    wavelengths = sample_wavelengths(
        s, Sampler(s.seed, kWavelengthStream, iteration, static_cast<uint32_t>(s.vcm_iterations)));
    colours.wl = &wavelengths;
  }
  auto t0 = Clock::now();
  const VcmLightPass pass =
      trace_vcm_light_paths(context, *lights_, *camera_, mis, iteration, cancel, colours);
  if (pass.cancelled) return false;
  stats_.rays += pass.rays;
  stats_.photons_recorded = pass.vertices.size();
  std::vector<Vec3> light_image(film.pixel_count(), Vec3(0.0f));
  apply_vcm_splats(pass.splats, *camera_, film.frame(), &light_image);
  const VcmGrid grid = mis.use_vm ? VcmGrid(pass.vertices, mis.radius) : VcmGrid();
  stats_.peak_photon_bytes =
      std::max(stats_.peak_photon_bytes, pass.vertices.size() * (sizeof(VcmLightVertex) + 8));
  stats_.photon_seconds += seconds_since(t0);

  t0 = Clock::now();
  std::atomic<uint64_t> non_finite{0};
  film.for_each_pixel(cancel, [&](int col, int row) {
    const size_t i = film.index(col, row);
    const uint64_t pixel_index = film.frame_pixel(col, row);
    Sampler sampler(s.seed, hash_combine(kCameraStream, pixel_index), iteration,
                    static_cast<uint32_t>(s.vcm_iterations));
    const VcmCameraSample c =
        trace_vcm_camera_path(context, *lights_, *camera_, mis, pass, pixel_index % mis.light_paths,
                              grid, film.frame_x(col), film.frame_y(row), sampler, colours);
    // Holdouts are not rendered by VCM: the coverage is the camera ray's alone.
    const Vec3 estimate = c.radiance + light_image[i];
    if (!is_finite(estimate)) {
      non_finite.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    film.add_light(i, estimate, film.coverage(c.alpha, 0.0f));
  });
  stats_.camera_seconds += seconds_since(t0);
  if (cancel.load()) return false;
  stats_.non_finite += non_finite.load();
  film.count_non_finite(non_finite.load());
  stats_.photons_emitted += mis.light_paths;
  ++stats_.iterations;
  return true;
}

int VcmIntegrator::render(const RenderContext& context, Film& film, const RenderControl& control) {
  const RenderSettings& s = *context.settings;
  const std::atomic<bool>& cancel = cancel_flag(control);
  if (control.first_pass == 0) {
    camera_ = std::make_unique<VcmCamera>(film.frame(), film.options());
    use_fallback_ = !camera_->supported();
    if (use_fallback_) {
      control.report_warning(
          "the VCM integrator renders pinhole perspective cameras only (no orthographic camera, "
          "no depth of field): rendering with SPPM instead");
      if (!fallback_) {
        // SPPM with VCM's budget: as many iterations, a photon per light path.
        fallback_settings_ = s;
        fallback_settings_.integrator = IntegratorType::kSppm;
        fallback_settings_.sppm_iterations = s.vcm_iterations;
        fallback_settings_.sppm_photons_per_iteration = s.vcm_light_paths;
        fallback_settings_.sppm_initial_radius = s.vcm_initial_radius;
        fallback_settings_.sppm_alpha = s.vcm_alpha;
        fallback_settings_.sppm_time = s.vcm_time;
        fallback_context_ = context;
        fallback_context_.settings = &fallback_settings_;
        fallback_ = std::make_unique<SppmIntegrator>();
        PrepareControl prepare;
        prepare.cancel = control.cancel;
        prepare.warn = control.warn;
        fallback_->prepare(fallback_context_, prepare);
      }
    }
  }
  if (use_fallback_) return fallback_->render(fallback_context_, film, control);

  const auto t0 = Clock::now();
  if (control.first_pass == 0) {
    if (film.options().light_passes)
      control.report_warning(
          "light passes are not rendered by the VCM integrator yet: they are left at zero");
    if (!start_iterative_film(context, film, control)) return 0;
    stats_ = IterationStats{};
    alpha_ = s.vcm_alpha;
    const float floor_radius = 1e-6f * context.accel->length_scale();
    const float footprint = median_pixel_footprint(context, film.frame());
    const float automatic = kAutoRadiusPixels * footprint;
    initial_radius_ = automatic;
    if (s.vcm_initial_radius > 0.0f) {
      std::string warning;
      initial_radius_ = clamp_radius(
          "vcm_initial_radius", s.vcm_initial_radius,
          meaningful_radius_range(footprint, scene_frame_.radius, automatic), &warning);
      if (!warning.empty()) control.report_warning(warning);
    }
    if (!(initial_radius_ > floor_radius))
      initial_radius_ = std::max(floor_radius, 0.01f * scene_frame_.radius);
    plan_light_paths(context, control);
  }
  return run_iterations(film, control, s.vcm_time, t0,
                        [&](uint32_t pass) { return iterate(context, film, pass, cancel); });
}

IntegratorInfo vcm_integrator_info() {
  IntegratorInfo info;
  info.type = IntegratorType::kVcm;
  info.label = "Vertex Connection and Merging";
  info.description =
      "Bidirectional path tracing and photon merging under one multiple importance sampling "
      "(Georgiev et al. 2012); refines as it renders";
  info.capabilities.name = "VCM";
  info.capabilities.iterative = true;
  info.capabilities.no_bake_reason =
      "the VCM integrator converges per pixel of a view and has no view-independent lighting "
      "solution to bake; bake from the photon maps or the radiosity solution";
  info.make = [] { return std::unique_ptr<Integrator>(new VcmIntegrator); };
  return info;
}

}  // namespace photon
