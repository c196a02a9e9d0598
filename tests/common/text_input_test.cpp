#include "common/text_input.hpp"

#include <gtest/gtest.h>

namespace graspsynth {
namespace {

TEST(ParseFiniteDouble, AcceptsDecimalAndScientific) {
  EXPECT_EQ(ParseFiniteDouble("1.5"), 1.5);
  EXPECT_EQ(ParseFiniteDouble(" -2e-3 "), -2e-3);
  EXPECT_EQ(ParseFiniteDouble("+4"), 4.0);
}

TEST(ParseFiniteDouble, RejectsPartialNonFiniteAndEmpty) {
  EXPECT_FALSE(ParseFiniteDouble("1.5x"));
  EXPECT_FALSE(ParseFiniteDouble("nan"));
  EXPECT_FALSE(ParseFiniteDouble("inf"));
  EXPECT_FALSE(ParseFiniteDouble(""));
  EXPECT_FALSE(ParseFiniteDouble("1e999"));
}

TEST(ParseNumberList, SplitsOnBlanksAndCommas) {
  const auto values = ParseNumberList("1, 2\t3 ,4", 4, nullptr);
  ASSERT_TRUE(values);
  EXPECT_EQ(*values, (std::vector<double>{1, 2, 3, 4}));
}

TEST(ParseNumberList, NamesTheBadFieldAndTheCount) {
  std::string why;
  EXPECT_FALSE(ParseNumberList("1 2 abc", 3, &why));
  EXPECT_EQ(why, "field 3 is not a finite number: 'abc'");
  EXPECT_FALSE(ParseNumberList("1 2", 3, &why));
  EXPECT_EQ(why, "expected 3 numbers, found 2");
}

TEST(SplitFields, KeepsEmptyFields) {
  const auto fields = SplitFields("a,,b,", ',');
  ASSERT_EQ(fields.size(), 4u);
  EXPECT_EQ(fields[1], "");
  EXPECT_EQ(fields[2], "b");
}

}  // namespace
}  // namespace graspsynth
