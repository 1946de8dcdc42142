// The frame loop of the integrators that refine every pixel of the film once per pass (SPPM,
// VCM; pbrt-v4's SPPMIntegrator::Render loop): a fresh film with its data passes when the render
// starts, then passes in order with status, progress (by passes, or by time under a time limit)
// and the whole film reported after each.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>

#include "photon/film/film.h"
#include "photon/integrators/integrator.h"
#include "photon/render/render_context.h"

namespace photon {

// For control.first_pass == 0: clears the film and renders its data passes (from the camera
// rays of the Sampling panel's samples, as the tiled integrators do; they do not change from
// pass to pass). False when stopped during them.
bool start_iterative_film(const RenderContext& context, Film& film, const RenderControl& control);

// Runs passes [control.first_pass, control.end_pass): `iterate(pass)` refines the film for that
// pass and returns false when cancelled during it (the film is then not reported). Stops early
// when the control is stopped or, with `time_limit` > 0, once `time_limit` seconds have passed
// since `start`. Returns the passes done (counting control.first_pass's predecessors).
int run_iterations(const Film& film, const RenderControl& control, double time_limit,
                   std::chrono::steady_clock::time_point start,
                   const std::function<bool(uint32_t pass)>& iterate);

}  // namespace photon
