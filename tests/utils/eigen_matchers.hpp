#pragma once

/// @file
/// Test helpers shared by the suite: matrix comparison and exception-message checks.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>

namespace graspsynth::testing {

/// Succeeds when a and b have the same shape and max |a - b| <= tol.
template <typename A, typename B>
::testing::AssertionResult MatricesNear(const Eigen::MatrixBase<A>& a,
                                        const Eigen::MatrixBase<B>& b, double tol) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) {
    return ::testing::AssertionFailure() << "shapes differ";
  }
  const double err = (a - b).cwiseAbs().maxCoeff();
  if (err <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "max |a - b| = " << err << " > " << tol << "\n a = ["
                                       << a.transpose() << "]\n b = [" << b.transpose() << "]";
}

/// Succeeds when two poses agree to `tol` in translation (m) and rotation matrix entries.
inline ::testing::AssertionResult PosesNear(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b,
                                            double tol) {
  const double dp = (a.translation() - b.translation()).norm();
  const double dr = (a.linear() - b.linear()).cwiseAbs().maxCoeff();
  if (dp <= tol && dr <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "poses differ: position " << dp << " m, rotation "
                                       << dr << " (tol " << tol << ")";
}

}  // namespace graspsynth::testing

/// Expects `statement` to throw `exception_type` whose what() contains every given substring.
#define GS_EXPECT_THROW_WITH(statement, exception_type, ...)                              \
  do {                                                                                    \
    try {                                                                                 \
      statement;                                                                          \
      ADD_FAILURE() << "expected " #exception_type " from: " #statement;                  \
    } catch (const exception_type& e) {                                                   \
      for (const std::string& part : std::initializer_list<std::string>{__VA_ARGS__}) {   \
        EXPECT_THAT(e.what(), ::testing::HasSubstr(part));                                \
      }                                                                                   \
    }                                                                                     \
  } while (false)
