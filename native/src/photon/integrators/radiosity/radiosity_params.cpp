#include "photon/integrators/radiosity/radiosity_params.h"

// Schema entries name only the fields they set (designated initializers); the rest keep
// ParamSpec's defaults, which is what -Wmissing-field-initializers would flag.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace photon {

const ParamSchema<RadiosityParams>& radiosity_schema() {
  using S = RadiosityParams;
  static const ParamSchema<S> schema{
      "radiosity",
      "Radiosity",
      "RADIOSITY",
      {
          param(&S::radiosity_patch_size,
                {.name = "radiosity_patch_size",
                 .label = "Patch Size",
                 .description =
                     "Edge length of the radiosity patches: larger triangles are split into "
                     "patches of this size, much smaller ones are grouped into one patch per "
                     "cell of this size; smaller patches show sharper shadows but need more rays "
                     "(0 = automatic: about 20000 patches, fewer if the rays are too few for "
                     "them, at least 256 rays per patch)",
                 .min = 0,
                 .max = 1e6,
                 .soft_max = 1,
                 .subtype = "DISTANCE",
                 .unit = "LENGTH"}),
          // Fewer than 1e4 rays leave most patches unlit; 1e10 already takes hours.
          param(&S::radiosity_rays,
                {.name = "radiosity_rays",
                 .label = "Rays",
                 .description =
                     "Rays the radiosity solve traces in total, in thousands; the solve time is "
                     "about proportional, and the noise falls as 1 / sqrt(rays). Use more rays "
                     "for more (smaller) patches",
                 .min = 1e4,
                 .max = 1e10,
                 .soft_max = 2e8,
                 .ui_scale = 1000,
                 .ui = {.text = "Rays (thousands)"}}),
          // Below 1e-4 of the emitted power the shooting phase only adds noise: the averaged
          // iterations (Jacobi) correct the distribution from there.
          param(&S::radiosity_threshold,
                {.name = "radiosity_threshold",
                 .label = "Unshot Threshold",
                 .description = "Light is shot on from patch to patch until the power not yet "
                                "shot is below this fraction of the emitted power",
                 .min = kMinRadiosityThreshold,
                 .max = kMaxRadiosityThreshold,
                 .soft_max = 0.1,
                 .precision = 4,
                 .ui = {.column = 1}}),
          param(&S::radiosity_iterations,
                {.name = "radiosity_iterations",
                 .label = "Averaged Iterations",
                 .description = "Jacobi iterations after shooting, each re-estimating the whole "
                                "solution with fresh rays, averaged to reduce noise (0 = "
                                "shooting only)",
                 .min = 0,
                 .max = kMaxRadiosityIterations,
                 .soft_max = 16,
                 .ui = {.column = 1}}),
      }};
  return schema;
}

}  // namespace photon
