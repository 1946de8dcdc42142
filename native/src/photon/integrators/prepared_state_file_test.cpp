// The prepared-state file's framing (blocks, checksum, bounded counts, atomic rename) and the
// fingerprint: it follows the scene and the settings prepare() depends on, not the render
// border, threads or tile size.
#include "photon/integrators/prepared_state_file.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <future>
#include <string>
#include <vector>

#include "photon/integrators/prepared_state_fingerprint.h"
#include "photon/shading/textures.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace prepared_state_file_test {
namespace {

namespace fs = std::filesystem;

std::string temp_path(const std::string& name) {
  return (fs::temp_directory_path() /
          ("photon_state_file_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

TEST(PreparedStateFile, RoundTripAcrossBlocks) {
  const std::string path = temp_path("round_trip.bin");
  // More than two 1 MiB blocks, so values straddle block boundaries.
  std::vector<uint32_t> big(700000);
  for (size_t i = 0; i < big.size(); ++i) big[i] = static_cast<uint32_t>(i * 2654435761u);
  {
    PreparedStateWriter w(path, IntegratorType::kPhotonMap, 42);
    w.value<uint8_t>(7);
    w.vector(big);
    w.value(3.5f);
    std::string error;
    ASSERT_TRUE(w.finish(&error)) << error;
  }
  // Nothing but the file is left (the temporary was renamed).
  int files = 0;
  for (const auto& e : fs::directory_iterator(fs::temp_directory_path()))
    files += e.path().string().rfind(path, 0) == 0;
  EXPECT_EQ(files, 1);

  PreparedStateReader r;
  std::string error;
  ASSERT_TRUE(r.open(path, IntegratorType::kPhotonMap, 42, &error)) << error;
  uint8_t a = 0;
  std::vector<uint32_t> read;
  float c = 0.0f;
  EXPECT_TRUE(r.value(&a) && r.vector(&read) && r.value(&c));
  EXPECT_TRUE(r.finish(&error)) << error;
  EXPECT_EQ(a, 7);
  EXPECT_EQ(read, big);
  EXPECT_EQ(c, 3.5f);

  PreparedStateReader other;
  EXPECT_FALSE(other.open(path, IntegratorType::kPhotonMap, 43, &error));
  EXPECT_NE(error.find("fingerprint"), std::string::npos) << error;
  EXPECT_FALSE(other.open(path, IntegratorType::kRadiosity, 42, &error));
  EXPECT_NE(error.find("another integrator"), std::string::npos) << error;
  fs::remove(path);
}

TEST(PreparedStateFile, CountsBeyondTheFileAndUnreadBytesAreRefused) {
  const std::string path = temp_path("counts.bin");
  {
    PreparedStateWriter w(path, IntegratorType::kPhotonMap, 1);
    w.value<uint64_t>(uint64_t{1} << 60);  // a count no file of this size can hold
    w.value<uint32_t>(5);
    ASSERT_TRUE(w.finish(nullptr));
  }
  PreparedStateReader r;
  ASSERT_TRUE(r.open(path, IntegratorType::kPhotonMap, 1, nullptr));
  std::vector<double> huge;
  EXPECT_FALSE(r.vector(&huge));  // refused before anything is allocated
  EXPECT_TRUE(huge.empty());
  std::string error;
  EXPECT_FALSE(r.finish(&error));
  EXPECT_NE(error.find("exceeds"), std::string::npos) << error;

  PreparedStateReader partial;
  ASSERT_TRUE(partial.open(path, IntegratorType::kPhotonMap, 1, nullptr));
  uint64_t first = 0;
  ASSERT_TRUE(partial.value(&first));
  EXPECT_FALSE(partial.finish(&error));
  EXPECT_NE(error.find("did not read"), std::string::npos) << error;
  fs::remove(path);
}

TEST(PreparedStateFile, UnfinishedWriterLeavesNoFile) {
  const std::string path = temp_path("unfinished.bin");
  {
    PreparedStateWriter w(path, IntegratorType::kPhotonMap, 1);
    w.value<uint64_t>(1);
  }
  EXPECT_FALSE(fs::exists(path));
  for (const auto& e : fs::directory_iterator(fs::temp_directory_path()))
    EXPECT_NE(e.path().string().rfind(path, 0), 0u) << e.path();
}

// A path that is a FIFO, a folder or a link is not replaced by a saved state (as root, a device
// such as the null device would be destroyed), and loading from a FIFO with no writer returns at
// once with a reason instead of blocking for ever.
TEST(PreparedStateFile, NonRegularPathsAreRefusedWithoutBlocking) {
  const std::string fifo = temp_path("state.fifo");
  const std::string folder = temp_path("state_folder");
  const std::string link = temp_path("state.link");
  std::remove(fifo.c_str());
  fs::remove_all(folder);
  std::remove(link.c_str());
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  fs::create_directory(folder);
  fs::create_symlink("/dev/null", link);
  for (const std::string& path : {fifo, folder, link}) {
    PreparedStateWriter w(path, IntegratorType::kPhotonMap, 1);
    w.value<uint32_t>(5);
    std::string error;
    EXPECT_FALSE(w.finish(&error)) << path;
    EXPECT_NE(error.find("not a regular file"), std::string::npos) << error;
  }
  struct stat st;
  ASSERT_EQ(::lstat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  ASSERT_EQ(::lstat(folder.c_str(), &st), 0);
  EXPECT_TRUE(S_ISDIR(st.st_mode));
  ASSERT_EQ(::lstat(link.c_str(), &st), 0);
  EXPECT_TRUE(S_ISLNK(st.st_mode));

  auto load = std::async(std::launch::async, [&] {
    PreparedStateReader r;
    std::string error;
    const bool ok = r.open(fifo, IntegratorType::kPhotonMap, 1, &error);
    return std::make_pair(ok, error);
  });
  if (load.wait_for(std::chrono::seconds(5)) != std::future_status::ready) {
    // Blocked in open(): give it a writer so the test can end, and fail.
    const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
    if (fd >= 0) ::close(fd);
    ADD_FAILURE() << "loading a FIFO with no writer blocked";
  }
  const auto [ok, error] = load.get();
  EXPECT_FALSE(ok);
  EXPECT_NE(error.find("not a regular file"), std::string::npos) << error;
  PreparedStateReader dir_reader;
  std::string dir_error;
  EXPECT_FALSE(dir_reader.open(folder, IntegratorType::kPhotonMap, 1, &dir_error));
  EXPECT_NE(dir_error.find("not a regular file"), std::string::npos) << dir_error;
  std::remove(fifo.c_str());
  fs::remove_all(folder);
  std::remove(link.c_str());
}

TEST(PreparedStateFingerprint, FollowsSceneAndSettingsButNotTheBorder) {
  const TextureSet no_textures;
  RenderSettings base;
  base.full_width = 64, base.full_height = 48;
  base.x0 = 0, base.y0 = 0, base.x1 = 64, base.y1 = 48;
  const Scene scene = make_cornell_box();
  auto fingerprint = [&](const Scene& sc, const RenderSettings& s) {
    uint64_t f = 0;
    std::string why;
    EXPECT_TRUE(prepared_state_fingerprint(sc, s, no_textures, &f, &why)) << why;
    return f;
  };
  const uint64_t reference = fingerprint(scene, base);

  // Settings that change nothing prepare() computes.
  RenderSettings same = base;
  same.x0 = 3, same.y0 = 10, same.x1 = 50, same.y1 = 20;
  same.threads = 7;
  same.tile_size = 13;
  same.preview_samples = 3;
  EXPECT_EQ(fingerprint(scene, same), reference);

  const std::vector<std::pair<const char*, std::function<void(RenderSettings*)>>> settings = {
      {"seed", [](RenderSettings* s) { s->seed = 1; }},
      {"seed beyond 2^53", [](RenderSettings* s) { s->seed = (uint64_t{1} << 60) + 1; }},
      {"full width", [](RenderSettings* s) { s->full_width = 65; }},
      {"full height", [](RenderSettings* s) { s->full_height = 47; }},
      {"photons", [](RenderSettings* s) { s->photons += 1; }},
      {"gather radius", [](RenderSettings* s) { s->gather_radius = 0.1f; }},
      {"final gather rays", [](RenderSettings* s) { s->final_gather_rays = 3; }},
      {"irradiance cache", [](RenderSettings* s) { s->irradiance_cache = false; }},
      {"max depth", [](RenderSettings* s) { s->max_depth = 3; }},
      {"spectral", [](RenderSettings* s) { s->spectral = true; }},
  };
  for (const auto& [what, change] : settings) {
    RenderSettings s = base;
    if (std::string(what) == "seed beyond 2^53") s.seed = uint64_t{1} << 60;
    const uint64_t before = fingerprint(scene, s);
    change(&s);
    EXPECT_NE(fingerprint(scene, s), before) << what;
  }

  const std::vector<std::pair<const char*, std::function<void(Scene*)>>> edits = {
      {"vertex", [](Scene* sc) { sc->meshes[0].positions[0].x += 1e-6f; }},
      {"instance transform", [](Scene* sc) { sc->instances[1].object_to_world.m[0][3] += 0.01f; }},
      {"material colour",
       [](Scene* sc) { sc->materials[0].closures[0][Param::kColor].value.y += 0.01f; }},
      {"light power", [](Scene* sc) { sc->lights[0].power *= 2.0f; }},
      {"light spectrum", [](Scene* sc) { sc->lights[0].spectrum = LightSpectrum::kBlackbody; }},
      {"IES profile", [](Scene* sc) { sc->lights[0].has_ies = true; }},
      {"portal", [](Scene* sc) { sc->portals.push_back(Portal{}); }},
      {"abbe number", [](Scene* sc) { sc->materials[0].closures[0].abbe = 30.0f; }},
      {"camera", [](Scene* sc) { sc->camera.camera_to_world.m[2][3] += 0.1f; }},
      {"world colour", [](Scene* sc) { sc->world.color = Vec3(0.1f); }},
      {"visibility", [](Scene* sc) { sc->instances[0].visibility &= ~kVisibleDiffuse; }},
  };
  for (const auto& [what, edit] : edits) {
    Scene edited = scene;
    edit(&edited);
    EXPECT_NE(fingerprint(edited, base), reference) << what;
  }

  Scene callback_world = scene;
  callback_world.world.radiance = [](const Vec3&) { return Vec3(1.0f); };
  uint64_t f = 0;
  std::string why;
  EXPECT_FALSE(prepared_state_fingerprint(callback_world, base, no_textures, &f, &why));
  EXPECT_FALSE(why.empty());
}

}  // namespace
}  // namespace prepared_state_file_test
}  // namespace photon
