#include "photon/integrators/photon_map/photon_map_params.h"

// Schema entries name only the fields they set (designated initializers); the rest keep
// ParamSpec's defaults, which is what -Wmissing-field-initializers would flag.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace photon {

const ParamSchema<PhotonMapParams>& photon_map_schema() {
  using S = PhotonMapParams;
  // ~20-60 bytes are stored per emitted photon: 1e8 photons is already several GB.
  constexpr double kMaxPhotons = 1e8;
  static const ParamSchema<S> schema{
      "photon_map",
      "Photon Mapping",
      "PHOTON_MAP",
      {
          param(&S::photons,
                {.name = "photons",
                 .label = "Photons",
                 .description = "Photons emitted for the global photon map (indirect light)",
                 .min = 0,
                 .max = kMaxPhotons,
                 .soft_max = 1e7,
                 .ui = {.column = 1}}),
          param(&S::caustic_photons,
                {.name = "caustic_photons",
                 .label = "Caustic Photons",
                 .description = "Photons aimed at mirrors and glass for the caustic photon map",
                 .min = 0,
                 .max = kMaxPhotons,
                 .soft_max = 1e7,
                 .ui = {.column = 1}}),
          param(&S::photon_time,
                {.name = "photon_time",
                 .label = "Photon Time",
                 .description = "Trace photons for this many seconds instead of a fixed count "
                                "(0 = use the counts). Esc during photon tracing renders with the "
                                "photons traced so far",
                 .min = 0,
                 .max = 86400,
                 .soft_max = 600,
                 .subtype = "TIME_ABSOLUTE",
                 .unit = "TIME"}),
          // Below 1e-4 of the memory no useful photon map fits; the slider starts at 1%.
          param(&S::memory_limit,
                {.name = "memory_limit",
                 .label = "Memory Limit",
                 .description = "Fraction of the memory available when a render starts that the "
                                "photon maps may use at their peak (estimated before tracing); "
                                "larger photon counts are scaled down to fit, with a warning",
                 .min = 1e-4,
                 .max = 1,
                 .soft_min = 0.01,
                 .subtype = "FACTOR"}),
          param(&S::gather_count,
                {.name = "gather_count",
                 .label = "Gather Count",
                 .description = "Nearest photons used in a global photon map estimate",
                 .min = 1,
                 .max = 1000,
                 .soft_max = 500,
                 .ui = {.column = 2}}),
          param(&S::caustic_gather_count,
                {.name = "caustic_gather_count",
                 .label = "Caustic Gather Count",
                 .description = "Nearest photons used in a caustic estimate",
                 .min = 1,
                 .max = 1000,
                 .soft_max = 500,
                 .ui = {.column = 2}}),
          param(&S::gather_radius,
                {.name = "gather_radius",
                 .label = "Gather Radius",
                 .description =
                     "Largest distance searched for photons (0 = automatic from the scene size)",
                 .min = 0,
                 .max = 1e6,
                 .soft_max = 10,
                 .subtype = "DISTANCE",
                 .unit = "LENGTH",
                 .ui = {.column = 2}}),
          param(&S::final_gather_rays,
                {.name = "final_gather_rays",
                 .label = "Final Gather Rays",
                 .description = "Rays gathering indirect light per camera sample (0 = read the "
                                "global photon map directly: fast, blotchy preview)",
                 .min = 0,
                 .max = 4096,
                 .soft_max = 256}),
          param(&S::irradiance_cache,
                {.name = "irradiance_cache",
                 .label = "Irradiance Cache",
                 .description = "Compute the final gather carefully (64 times Final Gather Rays) "
                                "at sparse points the camera sees before rendering, and "
                                "interpolate between them (Ward 1988): smooth indirect light at a "
                                "fraction of the cost. Points the cache does not cover are "
                                "gathered per sample",
                 .min = 0,
                 .max = 1,
                 .ui = {.active_if = "final_gather_rays"}}),
      }};
  return schema;
}

}  // namespace photon
