#include "photon/render/camera_clip_check.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "photon/testing/test_scenes.h"

namespace photon {
namespace camera_clip_check_test {
namespace {

// A floor 2 * scale wide and a camera `height` * scale above its centre, looking down.
std::string warning_for(float scale, float height, float clip_start) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.5f), "grey"));
  add_mesh_instance(
      &scene, make_quad(Vec3(-1, -1, 0) * scale, Vec3(2, 0, 0) * scale, Vec3(0, 2, 0) * scale), 0);
  Accel accel(scene, nullptr);
  Camera camera = make_look_at_camera(Vec3(0.1f, 0.0f, height) * scale, Vec3(0.0f), 0.6f, 1.0f);
  camera.clip_start = clip_start;
  camera.clip_end = 1e3f;
  return camera_clip_warning(camera, accel);
}

TEST(CameraClipCheck, WarnsWhenBlendersSmallestClipStartHidesATinyScene) {
  const std::string w = warning_for(1e-7f, 5.0f, kBlenderMinClipStart);
  EXPECT_NE(w.find("clip start"), std::string::npos) << w;
  // The same camera with the scene far enough away, or a normal scene: nothing to say.
  EXPECT_EQ(warning_for(1e-7f, 50.0f, kBlenderMinClipStart), "");
  EXPECT_EQ(warning_for(1.0f, 5.0f, kBlenderMinClipStart), "");
  EXPECT_EQ(warning_for(1.0f, 5.0f, 0.1f), "");
  // A clip start above Blender's minimum that hides geometry is a cutaway, not a mistake.
  EXPECT_EQ(warning_for(1.0f, 5.0f, 10.0f), "");
}

}  // namespace
}  // namespace camera_clip_check_test
}  // namespace photon
