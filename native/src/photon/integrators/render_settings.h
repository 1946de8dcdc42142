// What a render is asked to do: the frame, the passes and every algorithm's parameters.
#pragma once

#include "photon/film/data_pass_settings.h"
#include "photon/film/film.h"
#include "photon/integrators/photon_map/photon_map_params.h"
#include "photon/integrators/radiosity/radiosity_params.h"
#include "photon/integrators/sampling_params.h"
#include "photon/integrators/sppm/sppm_params.h"
#include "photon/integrators/vcm/vcm_params.h"

namespace photon {

// What a render is asked to do: the frame, and each algorithm's parameters (declared once in
// their schemas; render_params.h lists them all and clamps them). The parameter structs are
// bases so every field keeps its flat name (settings.photons), which is also its name in the
// schema, the Blender property and the command line.
struct RenderSettings : SamplingParams,
                        FilmParams,
                        PerformanceParams,
                        PhotonMapParams,
                        RadiosityParams,
                        SppmParams,
                        VcmParams,
                        SpectralParams {
  int full_width = 64, full_height = 64;  // whole frame in pixels
  // Pixel rectangle to render (Blender's render border), [x0, x1) x [y0, y1), y downwards.
  int x0 = 0, y0 = 0, x1 = 64, y1 = 64;
  bool transparent_background = false;  // from the scene's Film > Transparent
  bool light_passes = false;     // also write the Direct / Indirect / Caustics / Photon Map passes
  DataPassSettings data_passes;  // Depth, Mist, Normal, ... (integrators/data_passes.h)
};

// The film of a render of `settings`: its filter, exposure, transparency and passes.
inline FilmOptions film_options(const RenderSettings& settings) {
  FilmOptions o;
  o.filter_type = settings.filter_type;
  o.filter_width = settings.filter_width;
  o.exposure = settings.exposure;
  o.transparent_background = settings.transparent_background;
  o.light_passes = settings.light_passes;
  o.into_gamut = settings.spectral;
  o.data_passes = settings.data_passes;
  return o;
}

}  // namespace photon
