#include "photon/base/check.h"

#include <gtest/gtest.h>

namespace photon {
namespace check_test {
namespace {

int evaluations = 0;
bool counted(bool value) {
  ++evaluations;
  return value;
}

TEST(Check, FailureThrowsWithTheConditionAndItsPlace) {
  EXPECT_NO_THROW(CHECK(1 + 1 == 2));
  try {
    CHECK_LT(3, 2);
    FAIL() << "CHECK_LT(3, 2) passed";
  } catch (const CheckFailure& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("(3) < (2)"), std::string::npos) << what;
    EXPECT_NE(what.find("photon/base/check_test.cpp:"), std::string::npos) << what;
  }
}

TEST(Check, DcheckRunsExactlyInBuildsWithoutNdebug) {
  evaluations = 0;
#ifdef NDEBUG
  EXPECT_NO_THROW(DCHECK(counted(false)));
  EXPECT_EQ(evaluations, 0);  // not even evaluated
#else
  EXPECT_THROW(DCHECK(counted(false)), CheckFailure);
  EXPECT_EQ(evaluations, 1);
#endif
}

}  // namespace
}  // namespace check_test
}  // namespace photon
