#include "photon/integrators/sppm/sppm_params.h"

// Schema entries name only the fields they set (designated initializers); the rest keep
// ParamSpec's defaults, which is what -Wmissing-field-initializers would flag.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace photon {

const ParamSchema<SppmParams>& sppm_schema() {
  using S = SppmParams;
  static const ParamSchema<S> schema{
      "sppm",
      "Progressive Photon Mapping",
      "SPPM",
      {
          param(&S::sppm_iterations,
                {.name = "sppm_iterations",
                 .label = "Iterations",
                 .description = "Camera and photon passes; the image refines after each one",
                 .min = 1,
                 .max = 1 << 20,
                 .soft_max = 4096,
                 .ui = {.column = 1}}),
          // The photons of one iteration are stored until its camera pass has read them
          // (about 40 bytes per stored bounce): 1e8 is already several GB.
          param(&S::sppm_photons_per_iteration,
                {.name = "sppm_photons_per_iteration",
                 .label = "Photons per Iteration",
                 .description = "Photon paths emitted in each iteration",
                 .min = 1,
                 .max = 1e8,
                 .soft_max = 1e7,
                 .ui = {.column = 1}}),
          param(&S::sppm_time,
                {.name = "sppm_time",
                 .label = "Time Limit",
                 .description = "Stop after the iteration that passes this many seconds "
                                "(0 = run all iterations)",
                 .min = 0,
                 .max = 86400,
                 .soft_max = 3600,
                 .subtype = "TIME_ABSOLUTE",
                 .unit = "TIME",
                 .ui = {.column = 1}}),
          param(&S::sppm_initial_radius,
                {.name = "sppm_initial_radius",
                 .label = "Initial Radius",
                 .description = "Photon gathering radius of the first iteration (0 = automatic: "
                                "a few pixels wide at each pixel's surface); it shrinks as "
                                "photons arrive",
                 .min = 0,
                 .max = 1e6,
                 .soft_max = 10,
                 .subtype = "DISTANCE",
                 .unit = "LENGTH",
                 .ui = {.column = 2}}),
          param(&S::sppm_alpha,
                {.name = "sppm_alpha",
                 .label = "Alpha",
                 .description = "Fraction of each iteration's photons kept when the radius "
                                "shrinks: smaller shrinks faster (less blur, more noise)",
                 .min = 0.01,
                 .max = 0.99,
                 .subtype = "FACTOR",
                 .ui = {.column = 2}}),
      }};
  return schema;
}

}  // namespace photon
