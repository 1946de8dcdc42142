// A render that loads a saved photon-mapping preparation renders the same bits as the render
// that prepared it, for the whole frame and for a border region; files made for another
// render, or damaged, are refused with a warning and the render prepares itself.
#include "photon/integrators/photon_map/prepared_state_io.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "photon/session/render_session.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace prepared_state_io_test {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 40, kHeight = 32;

RenderSettings caustic_settings(int width = kWidth, int height = kHeight) {
  RenderSettings s;
  s.full_width = width;
  s.full_height = height;
  s.x0 = 0, s.y0 = 0, s.x1 = width, s.y1 = height;
  s.samples = 2;
  s.seed = 5;
  s.photons = 20000;
  s.caustic_photons = 10000;
  s.final_gather_rays = 4;
  s.gather_count = 30;  // the radiance precompute dominates a small frame's time
  s.threads = 2;
  s.tile_size = 16;
  s.light_passes = true;  // the Photon Map pass reads the maps themselves
  return s;
}

std::shared_ptr<const Scene> caustic_box() {
  static const auto scene = std::make_shared<const Scene>(make_caustic_box());
  return scene;
}

// A render's pixels (RGBA and the light passes) placed in a frame of kWidth x kHeight (at
// least the render's region); pixels outside the region stay NaN.
struct Frame {
  std::vector<float> rgba, passes;
  std::vector<std::string> warnings;
  RenderStats stats;
  int tiles = 0;
};

Frame render(const RenderSettings& s, const PreparedStateFiles& files = {},
             std::shared_ptr<const Scene> scene = caustic_box()) {
  RenderSession session(std::move(scene), s);
  session.set_prepared_state(files);
  session.start();
  Frame f;
  f.rgba.assign(static_cast<size_t>(kWidth) * kHeight * 4, NAN);
  f.passes.assign(static_cast<size_t>(kWidth) * kHeight * kPassFloats, NAN);
  for (bool done = false; !done;) {
    done = session.finished();
    for (const Tile& t : session.take_tiles(0.2)) {
      ++f.tiles;
      for (int y = 0; y < t.height; ++y)
        for (int x = 0; x < t.width; ++x) {
          const size_t src = static_cast<size_t>(y) * t.width + x;
          const size_t dst = static_cast<size_t>(s.y0 + t.y + y) * kWidth + (s.x0 + t.x + x);
          std::copy_n(&t.rgba[src * 4], 4, &f.rgba[dst * 4]);
          for (int k = 0; k < kPassCount; ++k)
            if (const PassImage* pass = t.pass(light_pass_names()[k]))
              std::copy_n(&pass->pixels[src * 3], 3, &f.passes[dst * kPassFloats + 3 * k]);
        }
    }
  }
  session.wait();
  f.warnings = session.warnings();
  f.stats = session.stats();
  return f;
}

// Every value of the region's pixels equals, bit for bit, the full frame's.
void expect_same_region(const Frame& full, const Frame& part, const RenderSettings& region) {
  int different = 0;
  for (int y = region.y0; y < region.y1; ++y)
    for (int x = region.x0; x < region.x1; ++x) {
      const size_t i = static_cast<size_t>(y) * kWidth + x;
      for (int k = 0; k < 4; ++k)
        different += std::memcmp(&full.rgba[i * 4 + k], &part.rgba[i * 4 + k], 4) != 0;
      for (int k = 0; k < kPassFloats; ++k)
        different += std::memcmp(&full.passes[i * kPassFloats + k],
                                 &part.passes[i * kPassFloats + k], 4) != 0;
    }
  EXPECT_EQ(different, 0);
}

class TempFile {
 public:
  explicit TempFile(const std::string& name)
      : path_((fs::temp_directory_path() /
               ("photon_prepared_" + std::to_string(::getpid()) + "_" + name))
                  .string()) {
    fs::remove(path_);
  }
  ~TempFile() { fs::remove(path_); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  return out;
}

TEST(PreparedState, LoadedStateRendersTheSameBitsAsPreparing) {
  TempFile file("same_bits.bin");
  const RenderSettings s = caustic_settings();
  const Frame prepared = render(s, {"", file.path(), false});
  ASSERT_TRUE(prepared.warnings.empty()) << joined(prepared.warnings);
  ASSERT_TRUE(prepared.stats.prepared_state.saved);
  ASSERT_TRUE(fs::exists(file.path()));
  // Every part of the state is exercised: both maps, the radiance records, the cache.
  const PrepareStats& p = prepared.stats.integrator;
  ASSERT_TRUE(p.photon_map && p.irradiance_cache);
  EXPECT_GT(p.photon_map->global_photons_stored, 0u);
  EXPECT_GT(p.photon_map->caustic_photons_stored, 0u);
  EXPECT_GT(p.photon_map->radiance_points, 0u);
  EXPECT_GT(p.irradiance_cache->records, 0u);

  // The whole frame, with another thread count and tile size.
  RenderSettings other = s;
  other.threads = 1;
  other.tile_size = 7;
  const Frame loaded = render(other, {file.path(), "", false});
  EXPECT_TRUE(loaded.warnings.empty()) << joined(loaded.warnings);
  EXPECT_TRUE(loaded.stats.prepared_state.loaded);
  EXPECT_EQ(loaded.stats.prepared_state.bytes, prepared.stats.prepared_state.bytes);
  expect_same_region(prepared, loaded, s);
  // The statistics are the preparation's.
  EXPECT_EQ(loaded.stats.integrator.photon_map->global_photons_stored,
            p.photon_map->global_photons_stored);

  // A band of rows (a farm's band) and an off-centre border.
  for (const auto& [x0, y0, x1, y1] :
       {std::array<int, 4>{0, 9, kWidth, 17}, std::array<int, 4>{5, 20, 33, 32}}) {
    RenderSettings border = s;
    border.x0 = x0, border.y0 = y0, border.x1 = x1, border.y1 = y1;
    const Frame band = render(border, {file.path(), "", false});
    EXPECT_TRUE(band.stats.prepared_state.loaded) << joined(band.warnings);
    expect_same_region(prepared, band, border);
  }
}

// Spectral photons (one wavelength each, through a dispersive glass ball) load as spectral
// photons; an RGB render refuses the spectral render's file.
TEST(PreparedState, SpectralStateRendersTheSameBitsAndIsRefusedInRgbMode) {
  TempFile file("spectral.bin");
  Scene dispersive = make_caustic_box();
  dispersive.materials[3].closures[0].abbe = 25.0f;  // the glass ball
  const auto scene = std::make_shared<const Scene>(std::move(dispersive));
  RenderSettings s = caustic_settings();
  s.spectral = true;
  const Frame prepared = render(s, {"", file.path(), false}, scene);
  ASSERT_TRUE(prepared.stats.prepared_state.saved) << joined(prepared.warnings);
  RenderSettings band = s;
  band.y0 = 9, band.y1 = 17;
  const Frame loaded = render(band, {file.path(), "", false}, scene);
  EXPECT_TRUE(loaded.stats.prepared_state.loaded) << joined(loaded.warnings);
  expect_same_region(prepared, loaded, band);

  RenderSettings rgb = band;
  rgb.spectral = false;
  const Frame refused = render(rgb, {file.path(), "", false}, scene);
  EXPECT_FALSE(refused.stats.prepared_state.loaded);
  EXPECT_FALSE(refused.warnings.empty());
}

TEST(PreparedState, PrepareOnlySavesWithoutRendering) {
  TempFile file("prepare_only.bin");
  RenderSettings s = caustic_settings();
  s.y0 = 10, s.y1 = 11;  // the border does not enter the state
  const Frame only = render(s, {"", file.path(), true});
  EXPECT_EQ(only.tiles, 0);
  EXPECT_TRUE(only.stats.prepared_state.saved) << joined(only.warnings);
  EXPECT_EQ(only.stats.camera_samples, 0u);

  const RenderSettings full = caustic_settings();
  const Frame loaded = render(full, {file.path(), "", false});
  EXPECT_TRUE(loaded.stats.prepared_state.loaded) << joined(loaded.warnings);
  expect_same_region(render(full), loaded, full);
}

// Rewrites byte `offset` of a file (from the end when negative).
void poke(const std::string& path, long offset, char value) {
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(offset, offset < 0 ? std::ios::end : std::ios::beg);
  f.put(value);
}

TEST(PreparedState, MismatchedOrDamagedFilesAreRefusedAndTheRenderPrepares) {
  TempFile file("stale.bin");
  // A small frame: each case prepares again.
  const RenderSettings s = caustic_settings(20, 16);
  ASSERT_TRUE(render(s, {"", file.path(), false}).stats.prepared_state.saved);
  const std::vector<char> good = [&] {
    std::ifstream in(file.path(), std::ios::binary);
    return std::vector<char>(std::istreambuf_iterator<char>(in), {});
  }();
  auto restore = [&] {
    std::ofstream out(file.path(), std::ios::binary | std::ios::trunc);
    out.write(good.data(), static_cast<std::streamsize>(good.size()));
  };

  // Another seed (another frame of an animation would differ in its camera or objects).
  RenderSettings reseeded = s;
  reseeded.seed = 6;
  RenderSettings wider = s;
  wider.full_width = s.full_width + 1;  // the region stays the same columns
  struct Case {
    std::string what;
    std::function<void()> damage;
    RenderSettings settings;
    std::string reason;
  };
  const std::vector<Case> cases = {
      {"other seed", [] {}, reseeded, "another scene or other render settings"},
      {"other frame size", [] {}, wider, "another scene or other render settings"},
      {"flipped payload byte", [&] { poke(file.path(), -40, good[good.size() - 40] ^ 0x10); }, s,
       "checksum"},
      {"truncated", [&] { fs::resize_file(file.path(), good.size() - 7); }, s, "truncated"},
      {"format version", [&] { poke(file.path(), 8, 99); }, s, "format version 99"},
      {"not a state file", [&] { poke(file.path(), 0, 'X'); }, s, "not a prepared-state file"},
      {"missing", [&] { fs::remove(file.path()); }, s, "cannot open"},
  };
  std::map<std::pair<uint64_t, int>, Frame> unloaded;  // renders given no file, by settings
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    restore();
    c.damage();
    const Frame refused = render(c.settings, {file.path(), "", false});
    EXPECT_FALSE(refused.stats.prepared_state.loaded);
    ASSERT_EQ(refused.warnings.size(), 1u) << joined(refused.warnings);
    EXPECT_NE(refused.warnings[0].find("prepared state refused"), std::string::npos)
        << refused.warnings[0];
    EXPECT_NE(refused.warnings[0].find(c.reason), std::string::npos) << refused.warnings[0];
    // The render prepared itself: its pixels are those of a render given no file.
    const auto key = std::make_pair(c.settings.seed, c.settings.full_width);
    if (!unloaded.count(key)) unloaded.emplace(key, render(c.settings));
    expect_same_region(unloaded.at(key), refused, c.settings);
  }
}

TEST(PreparedState, OtherIntegratorsIgnoreTheFilesWithAWarning) {
  TempFile file("ray_trace.bin");
  RenderSettings s = caustic_settings();
  s.integrator = IntegratorType::kRayTrace;
  const Frame f = render(s, {"", file.path(), false});
  EXPECT_FALSE(f.stats.prepared_state.saved);
  EXPECT_FALSE(fs::exists(file.path()));
  ASSERT_EQ(f.warnings.size(), 1u) << joined(f.warnings);
  EXPECT_NE(f.warnings[0].find("PHOTON_MAP integrator only"), std::string::npos);
}

TEST(PreparedState, UnwritablePathWarnsAndRenders) {
  const RenderSettings s = caustic_settings();
  const Frame f = render(s, {"", "/nonexistent-folder/state.bin", false});
  EXPECT_FALSE(f.stats.prepared_state.saved);
  ASSERT_EQ(f.warnings.size(), 1u) << joined(f.warnings);
  EXPECT_NE(f.warnings[0].find("prepared state not saved"), std::string::npos);
  EXPECT_EQ(f.stats.camera_samples, static_cast<uint64_t>(kWidth) * kHeight * s.samples);
}

}  // namespace
}  // namespace prepared_state_io_test
}  // namespace photon
