#include "photon/integrators/vcm/vcm_params.h"

// Schema entries name only the fields they set (designated initializers); the rest keep
// ParamSpec's defaults, which is what -Wmissing-field-initializers would flag.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace photon {

const ParamSchema<VcmParams>& vcm_schema() {
  using S = VcmParams;
  static const ParamSchema<S> schema{
      "vcm",
      "Vertex Connection and Merging",
      "VCM",
      {
          param(&S::vcm_iterations,
                {.name = "vcm_iterations",
                 .label = "Iterations",
                 .description = "Light and camera passes; the image refines after each one",
                 .min = 1,
                 .max = 1 << 20,
                 .soft_max = 4096,
                 .ui = {.column = 1}}),
          // A light subpath's vertices are stored until the iteration's camera pass has read
          // them: 1e8 paths is tens of GB, so the integrator traces fewer when they do not fit.
          param(&S::vcm_light_paths,
                {.name = "vcm_light_paths",
                 .label = "Light Paths per Iteration",
                 .description = "Light subpaths traced in each iteration, for connections to the "
                                "camera and merging",
                 .min = 1,
                 .max = 1e8,
                 .soft_max = 1e7,
                 .ui = {.column = 1}}),
          param(&S::vcm_time,
                {.name = "vcm_time",
                 .label = "Time Limit",
                 .description = "Stop after the iteration that passes this many seconds "
                                "(0 = run all iterations)",
                 .min = 0,
                 .max = 86400,
                 .soft_max = 3600,
                 .subtype = "TIME_ABSOLUTE",
                 .unit = "TIME",
                 .ui = {.column = 1}}),
          param(&S::vcm_initial_radius,
                {.name = "vcm_initial_radius",
                 .label = "Initial Radius",
                 .description = "Merging radius of the first iteration (0 = automatic: a few "
                                "pixels wide at the median depth the camera sees); it shrinks "
                                "with every iteration",
                 .min = 0,
                 .max = 1e6,
                 .soft_max = 10,
                 .subtype = "DISTANCE",
                 .unit = "LENGTH",
                 .ui = {.column = 2}}),
          param(&S::vcm_alpha,
                {.name = "vcm_alpha",
                 .label = "Alpha",
                 .description = "How fast the merging radius shrinks: r_i = r_1 i^((alpha - 1) / "
                                "2); smaller shrinks faster (less blur, more noise)",
                 .min = 0.01,
                 .max = 0.99,
                 .subtype = "FACTOR",
                 .ui = {.column = 2}}),
          param(
              &S::vcm_mode,
              {.name = "vcm_mode",
               .label = "Strategies",
               .description = "Strategies the VCM integrator combines by multiple importance "
                              "sampling",
               .min = 0,
               .max = 2,
               .items = {{"VCM", "Connection and Merging",
                          "Bidirectional path tracing and photon merging together",
                          static_cast<int>(VcmMode::kVcm)},
                         {"BPT", "Connections Only",
                          "Bidirectional path tracing: vertex connections only",
                          static_cast<int>(VcmMode::kBpt)},
                         {"PPM", "Merging Only", "Progressive photon mapping: vertex merging only",
                          static_cast<int>(VcmMode::kPpm)}},
               .ui = {.column = 2}}),
      }};
  return schema;
}

}  // namespace photon
