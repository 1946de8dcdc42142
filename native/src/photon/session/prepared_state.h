// A render's preparation through a prepared-state file (integrators/prepared_state_file.h): the
// renders of one frame's bands (a frame split over a render farm) load the photon maps and
// caches one render prepared and saved, instead of each tracing them again.
//
// A file is loaded only when it was written by this format version and integrator for a render
// with the same fingerprint (integrators/prepared_state_fingerprint.h: scene content and every
// setting but the render border, threads and tile size) and its checksum holds; otherwise the
// render says why in a warning and prepares as usual. A file that cannot be written is a
// warning too: the render goes on.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "photon/integrators/integrator.h"

namespace photon {

struct PreparedStateFiles {
  std::string load;           // a file to load instead of preparing ("": prepare)
  std::string save;           // where to save the preparation ("": nowhere)
  bool prepare_only = false;  // end the render once prepared (and saved): no pixels
};

struct PreparedStateStats {
  bool loaded = false;  // the preparation came from PreparedStateFiles::load
  bool saved = false;   // and was written to PreparedStateFiles::save
  uint64_t bytes = 0;   // payload size of the file loaded or saved
  double load_seconds = 0.0, save_seconds = 0.0;
  uint64_t fingerprint = 0;
};

// Prepares `integrator` for `context` (whose textures are `textures`), or loads its preparation
// as `files` says, then saves it when asked. Warnings go to `warnings`.
void prepare_with_state_files(const RenderContext& context, const TextureSet& textures,
                              IntegratorType type, Integrator* integrator,
                              const PrepareControl& control, const PreparedStateFiles& files,
                              PreparedStateStats* stats, std::vector<std::string>* warnings);

}  // namespace photon
