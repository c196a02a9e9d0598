// Tests of the request of ik (request/kinematics_request.hpp): the branch is three signs, none
// by default, and anything else is refused naming the option.

#include "request/kinematics_request.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/request/request_test_utils.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth::request {
namespace {

TEST(IkRequest, EveryOptionIsWellDescribed) { ExpectWellDescribed(IkOptions()); }

TEST(IkRequest, TheBranchIsThreeSignsOrNone) {
  const Option<IkRequest>& branch = *FindOption(IkOptions(), "branch");
  IkRequest r;
  EXPECT_FALSE(r.branch.has_value());
  Apply(branch, ParseText(branch.info, "1,-1,1", "--branch"), "--branch", &r);
  ASSERT_TRUE(r.branch.has_value());
  EXPECT_EQ(*r.branch, Eigen::Vector3i(1, -1, 1));
  GS_EXPECT_THROW_WITH(Apply(branch, ParseText(branch.info, "1,2,1", "--branch"), "--branch", &r),
                       InputError, "--branch takes three signs GC2,GC4,GC6, each 1 or -1",
                       "'1,2,1'");
  GS_EXPECT_THROW_WITH(ParseText(branch.info, "1,1", "--branch"), InputError,
                       "--branch: '1,1' needs GC2,GC4,GC6 (3 numbers), got 2");
  ApplyConfig(IkOptions(), WriteConfig("ik.json", R"({"branch": [-1, 1, -1]})"), &r);
  EXPECT_EQ(*r.branch, Eigen::Vector3i(-1, 1, -1));
}

}  // namespace
}  // namespace graspsynth::request
