#include "photon/integrators/iterative_frame.h"

#include <algorithm>
#include <string>

#include "photon/integrators/pixel_integrator.h"

namespace photon {

bool start_iterative_film(const RenderContext& context, Film& film, const RenderControl& control) {
  film.clear();
  if (film.data_floats() == 0) return true;
  control.report_status("Data passes");
  return render_data_passes(context, film, control);
}

int run_iterations(const Film& film, const RenderControl& control, double time_limit,
                   std::chrono::steady_clock::time_point start,
                   const std::function<bool(uint32_t pass)>& iterate) {
  int done = control.first_pass;
  while (done < control.end_pass && !control.stopped()) {
    control.report_status("Iteration " + std::to_string(done + 1) + " / " +
                          std::to_string(control.end_pass));
    if (!iterate(static_cast<uint32_t>(done))) return done;
    ++done;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const bool out_of_time = time_limit > 0.0 && elapsed >= time_limit;
    const bool last = done >= control.end_pass || out_of_time;
    if (control.progress) {
      double fraction = static_cast<double>(done - control.first_pass) /
                        std::max(control.end_pass - control.first_pass, 1);
      if (time_limit > 0.0) fraction = std::max(fraction, elapsed / time_limit);
      control.progress(static_cast<float>(std::min(fraction, 1.0)));
    }
    if (control.update) control.update(FilmRect{0, 0, film.width(), film.height()}, done, last);
    if (out_of_time) break;
  }
  return done;
}

}  // namespace photon
