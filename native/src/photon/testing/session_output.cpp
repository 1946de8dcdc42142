#include "photon/testing/session_output.h"

#include <algorithm>

#include "photon/film/pass_layout.h"
#include "photon/session/render_session.h"

namespace photon {

double render_mean(std::shared_ptr<const Scene> scene, const RenderSettings& settings) {
  RenderSession session(std::move(scene), settings);
  session.start();
  session.wait();
  const std::vector<float> rgba = session.image();
  if (rgba.empty()) return 0.0;
  double sum = 0.0;
  for (size_t i = 0; i < rgba.size(); i += 4) sum += (rgba[i] + rgba[i + 1] + rgba[i + 2]) / 3.0;
  return sum / static_cast<double>(rgba.size() / 4);
}

SessionOutput render_whole_session(std::shared_ptr<const Scene> scene, const RenderSettings& s) {
  RenderSession session(std::move(scene), s);
  session.start();
  SessionOutput out;
  const int floats = data_pass_pixel_floats(s.data_passes);
  out.data.assign(static_cast<size_t>(s.full_width) * s.full_height * floats, -9.0f);
  while (true) {
    const bool done = session.finished();
    // Later tiles (a later round, or the whole film after the data passes) replace earlier ones.
    for (const Tile& t : session.take_tiles(0.05))
      for (const DataPassSlot& slot : data_pass_slots(s.data_passes)) {
        const PassImage* pass = t.pass(slot.name);
        if (!pass) continue;
        for (int row = 0; row < t.height; ++row)
          for (int col = 0; col < t.width; ++col)
            std::copy_n(
                &pass->pixels[(static_cast<size_t>(row) * t.width + col) * slot.channels],
                slot.channels,
                &out.data[(static_cast<size_t>(t.y + row) * s.full_width + t.x + col) * floats +
                          slot.offset]);
      }
    if (done) break;
  }
  session.wait();
  out.image = session.image();
  out.warnings = session.warnings();
  out.camera_samples = session.stats().camera_samples;
  return out;
}

}  // namespace photon
