#include "common/orientation_list.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth {
namespace {

using ::testing::ElementsAre;

TEST(ParseOrientationList, NumbersAndInclusiveRanges) {
  EXPECT_THAT(ParseOrientationList("40,45", "--orientations"), ElementsAre(40.0, 45.0));
  EXPECT_THAT(ParseOrientationList("20:40:10", "--orientations"), ElementsAre(20.0, 30.0, 40.0));
  EXPECT_THAT(ParseOrientationList("0:2:1,100:110:5,-7.5", "--orientations"),
              ElementsAre(0.0, 1.0, 2.0, 100.0, 105.0, 110.0, -7.5));
  // a range whose step does not divide it stops at the last value inside it.
  EXPECT_THAT(ParseOrientationList("20:45:10", "--orientations"), ElementsAre(20.0, 30.0, 40.0));
  EXPECT_THAT(ParseOrientationList("30:30:1", "--orientations"), ElementsAre(30.0));
}

TEST(ParseOrientationList, BadItemsNameTheOptionTheItemAndTheText) {
  GS_EXPECT_THROW_WITH(ParseOrientationList("20,abc", "--orientations"), InputError,
                       "--orientations: 'abc' is not a finite number of degrees (in '20,abc')");
  GS_EXPECT_THROW_WITH(ParseOrientationList("20,inf", "--thetas"), InputError, "--thetas", "'inf'");
  GS_EXPECT_THROW_WITH(ParseOrientationList("40:20:5", "--orientations"), InputError,
                       "needs FROM <= TO and STEP > 0");
  GS_EXPECT_THROW_WITH(ParseOrientationList("20:40:0", "--orientations"), InputError,
                       "needs FROM <= TO and STEP > 0");
  GS_EXPECT_THROW_WITH(ParseOrientationList("20:x:5", "--orientations"), InputError,
                       "is not a range FROM:TO:STEP of finite numbers");
  GS_EXPECT_THROW_WITH(ParseOrientationList("20:40", "--orientations"), InputError,
                       "is neither a number nor a range FROM:TO:STEP");
  GS_EXPECT_THROW_WITH(ParseOrientationList("0:1000000:1", "--orientations"), InputError,
                       "more than 100000 orientations");
  // found by fuzz/text_fuzz.cpp: a count beyond an int, and a width beyond a double.
  GS_EXPECT_THROW_WITH(ParseOrientationList("20,3:020210113001:002,350,0", "--orientations"),
                       InputError, "'3:020210113001:002'", "more than 100000 orientations");
  GS_EXPECT_THROW_WITH(ParseOrientationList("-1e308:1e308:1e-300", "--orientations"), InputError,
                       "more than 100000 orientations");
  GS_EXPECT_THROW_WITH(ParseOrientationList("0:60000:1,0:60000:1", "--orientations"), InputError,
                       "more than 100000 orientations in all");
  GS_EXPECT_THROW_WITH(ParseOrientationList("", "--orientations"), InputError,
                       "--orientations: no orientation in ''");
}

}  // namespace
}  // namespace graspsynth
