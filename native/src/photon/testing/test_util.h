// Assertions shared by the unit tests.
#pragma once

#include <gtest/gtest.h>

#include "photon/base/math.h"

namespace photon {

// Passes when |a - b| <= tol (absolute distance), printing both vectors otherwise.
inline ::testing::AssertionResult VecNear(const Vec3& a, const Vec3& b, float tol) {
  const float d = length(a - b);
  if (d <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "(" << a.x << ", " << a.y << ", " << a.z << ") vs ("
                                       << b.x << ", " << b.y << ", " << b.z << "), distance " << d;
}

}  // namespace photon
