#include "photon/scene/mesh_import.h"

#include <gtest/gtest.h>

#include <cmath>

namespace photon {
namespace mesh_import_test {
namespace {

TEST(SnapNormals, NormalsOneUlpApartBecomeIdentical) {
  Mesh a, b;
  for (int i = 0; i < 1000; ++i) {
    const float angle = 0.001f * i + 0.1234f;
    const Vec3 n(std::cos(angle) * 0.6f, std::sin(angle) * 0.6f, 0.8f);
    a.corner_normals.push_back(n);
    b.corner_normals.push_back(Vec3(std::nextafter(n.x, 2.0f), n.y, std::nextafter(n.z, -2.0f)));
  }
  snap_normals(&a);
  snap_normals(&b);
  int equal = 0;
  for (int i = 0; i < 1000; ++i) {
    equal += a.corner_normals[i].x == b.corner_normals[i].x &&
             a.corner_normals[i].z == b.corner_normals[i].z;
    EXPECT_NEAR(a.corner_normals[i].x, std::cos(0.001f * i + 0.1234f) * 0.6f, 1e-5f);
  }
  EXPECT_GE(equal, 995);  // only values at a rounding boundary can still differ
}

}  // namespace
}  // namespace mesh_import_test
}  // namespace photon
