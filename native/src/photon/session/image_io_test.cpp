#include "photon/session/image_io.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

namespace photon {
namespace image_io_test {
namespace {

namespace fs = std::filesystem;

fs::path scratch_folder() {
  const fs::path dir = fs::temp_directory_path() / ("photon_image_io_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename());
  return names;
}

TEST(ImageIo, WritesTheImageUnderItsNameAndNothingElse) {
  const fs::path dir = scratch_folder();
  const std::vector<float> rgba = {0.25f, 2.0f, -1.0f, 1.0f, 1e6f, 0.0f, 0.5f, 0.5f};
  std::string error;
  ASSERT_TRUE(write_rgba_image((dir / "a.exr").string(), rgba, 2, 1, &error)) << error;
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"a.exr"});
  auto in = OIIO::ImageInput::open((dir / "a.exr").string());
  ASSERT_TRUE(in);
  std::vector<float> back(8);
  ASSERT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, back.data()));
  EXPECT_EQ(back, rgba);
  fs::remove_all(dir);
}

TEST(ImageIo, FailuresLeaveNothingBehindAndSayWhy) {
  const fs::path dir = scratch_folder();
  const std::vector<float> rgba(4 * 4, 0.5f);
  std::string error;
  // A folder where the image should go: refused, the folder untouched.
  fs::create_directory(dir / "folder.exr");
  EXPECT_FALSE(write_rgba_image((dir / "folder.exr").string(), rgba, 2, 2, &error));
  EXPECT_NE(error.find("is not a regular file"), std::string::npos) << error;
  EXPECT_TRUE(fs::is_directory(dir / "folder.exr"));
  // A folder that does not exist: an error, no temporary file anywhere in `dir`.
  error.clear();
  EXPECT_FALSE(write_rgba_image((dir / "missing" / "a.exr").string(), rgba, 2, 2, &error));
  EXPECT_FALSE(error.empty());
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"folder.exr"});
  fs::remove_all(dir);
}

}  // namespace
}  // namespace image_io_test
}  // namespace photon
