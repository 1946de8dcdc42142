#include "photon/integrators/photon_map/prepared_state_io.h"

#include <optional>

namespace photon {
namespace {

// Arrays are written as they lie in memory: their types must have no padding, whose bytes
// would be undefined, and a change of layout must bump the file format.
static_assert(sizeof(Photon) == 20);
static_assert(sizeof(RadianceRecord) == 9 * sizeof(float) + kGuideCells);
static_assert(sizeof(IrradianceRecord) == 10 * sizeof(float));
// The statistics are plain 8-byte fields; a new field changes the size (bump the format).
static_assert(sizeof(PhotonMapStats) == 13 * 8);
static_assert(sizeof(PhotonMemoryStats) == 2 * 8);
static_assert(sizeof(IrradianceCacheStats) == 5 * 8);

// Section tags: a payload read out of step fails at the next tag, not somewhere in the pixels.
constexpr uint32_t kTagGlobal = 0x50414D47;      // "GMAP"
constexpr uint32_t kTagCaustic = 0x50414D43;     // "CMAP"
constexpr uint32_t kTagRadiance = 0x44415252;    // "RRAD"
constexpr uint32_t kTagIrradiance = 0x52524949;  // "IIRR"
constexpr uint32_t kTagRadii = 0x49444152;       // "RADI"
constexpr uint32_t kTagStats = 0x54415453;       // "STAT"

template <class T>
void write_optional(PreparedStateWriter* out, const std::optional<T>& v) {
  out->value<uint8_t>(v ? 1 : 0);
  if (v) out->value(*v);
}

template <class T>
bool read_optional(PreparedStateReader* in, std::optional<T>* v) {
  uint8_t present = 0;
  if (!in->value(&present)) return false;
  if (present > 1) return in->fail("a statistics flag is neither 0 nor 1");
  if (!present) {
    v->reset();
    return true;
  }
  T value;
  if (!in->value(&value)) return false;
  *v = value;
  return true;
}

bool expect_tag(PreparedStateReader* in, uint32_t tag) {
  uint32_t found = 0;
  if (!in->value(&found)) return false;
  return found == tag || in->fail("a section of the payload is missing or out of place");
}

// A map: its tag, whether its photons are spectral (one wavelength each), its photons.
void write_map(PreparedStateWriter* out, uint32_t tag, const PhotonMap& map) {
  out->value(tag);
  out->value<uint8_t>(map.spectral() ? 1 : 0);
  out->vector(map.photons());
}

bool read_map(PreparedStateReader* in, uint32_t tag, PhotonMap* map) {
  std::vector<Photon> photons;
  uint8_t spectral = 0;
  if (!expect_tag(in, tag) || !in->value(&spectral)) return false;
  if (spectral > 1) return in->fail("a photon map's spectral flag is neither 0 nor 1");
  if (!in->vector(&photons)) return false;
  return PhotonMap::from_balanced(std::move(photons), spectral == 1, map) ||
         in->fail("a photon has an invalid kd-tree split axis");
}

}  // namespace

void write_photon_map_prepared(const PhotonMapPrepared& prepared, const PrepareStats& stats,
                               PreparedStateWriter* out) {
  write_map(out, kTagGlobal, prepared.global);
  write_map(out, kTagCaustic, prepared.caustic);
  out->value(kTagRadiance);
  out->value(prepared.radiance.cell_size());
  out->vector(prepared.radiance.records());
  out->value(kTagIrradiance);
  out->value(prepared.irradiance.accuracy());
  out->vector(prepared.irradiance.records());
  out->value(kTagRadii);
  out->value(prepared.global_radius);
  out->value(prepared.caustic_radius);
  out->value(prepared.secondary_distance);
  out->value(kTagStats);
  write_optional(out, stats.photon_map);
  write_optional(out, stats.photon_memory);
  write_optional(out, stats.irradiance_cache);
}

bool read_photon_map_prepared(PreparedStateReader* in, PhotonMapPrepared* prepared,
                              PrepareStats* stats, std::string* error) {
  PhotonMapPrepared read;
  PrepareStats read_stats;
  float cell_size = 0.0f, accuracy = 0.0f;
  std::vector<RadianceRecord> radiance;
  std::vector<IrradianceRecord> irradiance;
  const bool parsed =
      read_map(in, kTagGlobal, &read.global) && read_map(in, kTagCaustic, &read.caustic) &&
      expect_tag(in, kTagRadiance) && in->value(&cell_size) && in->vector(&radiance) &&
      expect_tag(in, kTagIrradiance) && in->value(&accuracy) && in->vector(&irradiance) &&
      expect_tag(in, kTagRadii) && in->value(&read.global_radius) &&
      in->value(&read.caustic_radius) && in->value(&read.secondary_distance) &&
      expect_tag(in, kTagStats) && read_optional(in, &read_stats.photon_map) &&
      read_optional(in, &read_stats.photon_memory) &&
      read_optional(in, &read_stats.irradiance_cache);
  // The checksum is known once every block was read: nothing is built from a damaged file.
  // (A failed read has set the reader's error, which finish() reports.)
  if (!in->finish(error) || !parsed) return false;
  // An empty cache was built with no records at all (its default cell size is then kept).
  if (!radiance.empty()) read.radiance = RadianceCache(std::move(radiance), cell_size);
  if (!irradiance.empty()) read.irradiance = IrradianceCache(std::move(irradiance), accuracy);
  *prepared = std::move(read);
  *stats = read_stats;
  return true;
}

}  // namespace photon
