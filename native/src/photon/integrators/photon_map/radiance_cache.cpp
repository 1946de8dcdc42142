#include "photon/integrators/photon_map/radiance_cache.h"

#include <algorithm>
#include <cmath>

#include "photon/base/cancel_poll.h"
#include "photon/base/rng.h"
#include "photon/integrators/photon_map/photon_map.h"

namespace photon {
namespace {

// Shells of cells searched around a lookup's own cell (a cell is about two record spacings).
constexpr int64_t kSearchRings = 3;

}  // namespace

uint64_t RadianceCache::cell_key(int64_t x, int64_t y, int64_t z) const {
  // 21 bits per axis (cells are clamped into range), then mixed for the open-addressing table.
  const uint64_t mask = (1ull << 21) - 1;
  return ((static_cast<uint64_t>(x) & mask) << 42) | ((static_cast<uint64_t>(y) & mask) << 21) |
         (static_cast<uint64_t>(z) & mask);
}

void RadianceCache::cell_of(const Vec3& p, int64_t* x, int64_t* y, int64_t* z) const {
  auto cell = [&](float v) {
    const float c = std::floor(v * inv_cell_);
    return static_cast<int64_t>(std::clamp(c, -1048575.0f, 1048575.0f));
  };
  *x = cell(p.x);
  *y = cell(p.y);
  *z = cell(p.z);
}

RadianceCache::RadianceCache(std::vector<RadianceRecord> records, float cell_size,
                             const std::atomic<bool>* cancel)
    : cell_size_(cell_size > 0.0f && std::isfinite(cell_size) ? cell_size : 1.0f),
      inv_cell_(1.0f / cell_size_) {
  try {
    build(std::move(records), cancel);
  } catch (const Cancelled&) {
    records_ = std::vector<RadianceRecord>();
    slots_ = std::vector<Slot>();
    slot_mask_ = 0;
  }
}

void RadianceCache::build(std::vector<RadianceRecord> records, const std::atomic<bool>* cancel) {
  CancelPoll poll(cancel);
  std::vector<std::pair<uint64_t, uint32_t>> keyed;
  keyed.reserve(records.size());
  for (uint32_t i = 0; i < records.size(); ++i) {
    poll();
    if (!is_finite(records[i].p)) continue;
    int64_t x, y, z;
    cell_of(records[i].p, &x, &y, &z);
    keyed.push_back({cell_key(x, y, z), i});
  }
  // The (key, index) pairs are unique, so the order is the same for any sort algorithm.
  std::sort(keyed.begin(), keyed.end(), [&poll](const auto& a, const auto& b) {
    poll();
    return a < b;
  });
  records_.reserve(keyed.size());
  for (const auto& [key, i] : keyed) {
    poll();
    records_.push_back(records[i]);
  }

  size_t cells = 0;
  for (size_t i = 0; i < keyed.size(); ++i) {
    poll();
    if (i == 0 || keyed[i].first != keyed[i - 1].first) ++cells;
  }
  size_t table = 16;
  while (table < 2 * cells) table *= 2;
  slots_.assign(table, Slot{});
  slot_mask_ = table - 1;
  for (size_t i = 0; i < keyed.size();) {
    poll();
    size_t j = i;
    while (j < keyed.size() && keyed[j].first == keyed[i].first) ++j;
    uint64_t s = mix64(keyed[i].first) & slot_mask_;
    while (slots_[s].count) s = (s + 1) & slot_mask_;
    slots_[s] = {keyed[i].first, static_cast<uint32_t>(i), static_cast<uint32_t>(j - i)};
    i = j;
  }
}

size_t RadianceCache::memory_bytes() const {
  return records_.capacity() * sizeof(RadianceRecord) + slots_.capacity() * sizeof(Slot);
}

const RadianceCache::Slot* RadianceCache::find(uint64_t key) const {
  for (uint64_t s = mix64(key) & slot_mask_;; s = (s + 1) & slot_mask_) {
    const Slot& slot = slots_[s];
    if (!slot.count) return nullptr;
    if (slot.key == key) return &slot;
  }
}

const RadianceRecord* RadianceCache::nearest(const Vec3& p, const Vec3& n, float min_cos) const {
  if (records_.empty()) return nullptr;
  int64_t cx, cy, cz;
  cell_of(p, &cx, &cy, &cz);
  float best = INFINITY;
  const RadianceRecord* found = nullptr;
  auto scan = [&](int64_t x, int64_t y, int64_t z) {
    const Slot* slot = find(cell_key(x, y, z));
    if (!slot) return;
    for (uint32_t i = slot->begin; i < slot->begin + slot->count; ++i) {
      const RadianceRecord& r = records_[i];
      if (dot(r.n, n) < min_cos) continue;
      const Vec3 offset = r.p - p;
      const float d2 = length_squared(offset);
      // A record of a parallel surface across a gap (the inside of a closed box's bottom, the
      // floor under it) faces the same way but saw other light: keep to records that can lie
      // on p's surface, as the photons of an estimate (photon_map.h).
      if (!on_same_surface(p, n, r.p, r.n, std::sqrt(d2))) continue;
      if (d2 < best) {
        best = d2;
        found = &r;
      }
    }
  };
  scan(cx, cy, cz);
  // Then shells of cells around it, until one holds a record: where the light is dim the photons,
  // and so the records, are sparse.
  for (int64_t ring = 1; !found && ring <= kSearchRings; ++ring)
    for (int64_t dz = -ring; dz <= ring; ++dz)
      for (int64_t dy = -ring; dy <= ring; ++dy) {
        const bool face = std::abs(dz) == ring || std::abs(dy) == ring;
        for (int64_t dx = -ring; dx <= ring; dx += face ? 1 : 2 * ring)
          scan(cx + dx, cy + dy, cz + dz);
      }
  return found;
}

}  // namespace photon
