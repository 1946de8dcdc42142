// The far-from-origin warnings of Accel (ray_offset.h): the scene as a whole far from the origin
// relative to its extent, and, for a scene near the origin, objects too small for floats where
// they lie (a 2e7 m scene whose metre-sized objects sit 1e7 m out).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "photon/base/ray_offset.h"
#include "photon/render/accel.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace far_from_origin_test {
namespace {

// 1 m quads at the given offsets.
Scene quads_at(const std::vector<Vec3>& offsets) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.5f), "grey"));
  for (const Vec3& offset : offsets)
    add_mesh_instance(&scene, make_quad(Vec3(-0.5f, -0.5f, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)), 0,
                      Transform::translation(offset));
  return scene;
}

std::vector<std::string> warnings_of(const Scene& scene) {
  std::vector<std::string> warnings;
  Accel accel(scene, &warnings);
  return warnings;
}

TEST(FarFromOrigin, ObjectsTooSmallForWhereTheyLieWarnOnce) {
  // The scene's centre is at the origin, but each metre object lies 1e7 m out (1 m floats).
  const auto warnings =
      warnings_of(quads_at({Vec3(-1e7f, 0, 0), Vec3(1e7f, 0, 0), Vec3(0.0f, 0.0f, 0.0f)}));
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("2 object(s)"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("from the origin"), std::string::npos) << warnings[0];
}

TEST(FarFromOrigin, SceneFarAwayGivesTheSceneWarningOnly) {
  const auto warnings = warnings_of(quads_at({Vec3(1e7f, 1e7f, 0), Vec3(1e7f + 4, 1e7f, 0)}));
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("The scene spans"), std::string::npos) << warnings[0];
}

TEST(FarFromOrigin, ScatteredSmallObjectsAndRebasedScenesDoNotWarn) {
  // Metre objects 1 km apart (a thousand sizes out) and a scene moved near the origin.
  EXPECT_TRUE(
      warnings_of(quads_at({Vec3(-1000, 0, 0), Vec3(1000, 0, 0), Vec3(0, 1000, 0)})).empty());
  EXPECT_TRUE(warnings_of(quads_at({Vec3(0, 0, 0), Vec3(4, 0, 0)})).empty());
}

}  // namespace
}  // namespace far_from_origin_test
}  // namespace photon
