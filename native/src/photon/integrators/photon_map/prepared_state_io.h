// What PhotonMapIntegrator::prepare() leaves behind for the pixels, and its payload in a
// prepared-state file (prepared_state_file.h): the global and caustic photon maps in their
// balanced order, the precomputed radiance records (Christensen 1999) with their grid's cell
// size, the irradiance-cache records (Ward 1988) with their accuracy, the gather radii and the
// secondary-gather distance, and the preparation's statistics. Loading rebuilds the record
// grid and the irradiance cache's hierarchy from the records, which gives exactly the
// structures prepare() built (both depend only on the records' order), so a render that loads
// a state renders the same pixels, bit for bit, as the render that prepared it.
//
// Payload layout (format 1): a section tag and a count before every array; see
// write_photon_map_prepared.
#pragma once

#include "photon/integrators/photon_map/irradiance_cache.h"
#include "photon/integrators/photon_map/photon_map.h"
#include "photon/integrators/photon_map/radiance_cache.h"
#include "photon/integrators/prepare_stats.h"
#include "photon/integrators/prepared_state_file.h"

namespace photon {

struct PhotonMapPrepared {
  PhotonMap global, caustic;
  RadianceCache radiance;      // precomputed at a subset of the global photons
  IrradianceCache irradiance;  // final gathers at camera-visible diffuse points
  float global_radius = 0.0f, caustic_radius = 0.0f;
  // The typical radius of a global-map estimate: final-gather hits nearer than this read a
  // record blurred over more than their distance, so they take one more bounce.
  float secondary_distance = 0.0f;
};

void write_photon_map_prepared(const PhotonMapPrepared& prepared, const PrepareStats& stats,
                               PreparedStateWriter* out);
// Reads what write_photon_map_prepared wrote. `prepared` and `stats` are only changed when the
// whole payload was read and checked (in.finish()); false with `error` otherwise.
bool read_photon_map_prepared(PreparedStateReader* in, PhotonMapPrepared* prepared,
                              PrepareStats* stats, std::string* error);

}  // namespace photon
