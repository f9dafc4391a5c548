// Result<T>, SCANSURF_TRY and SCANSURF_ASSIGN_OR_RETURN.
#include "scansurf/result.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>

namespace scansurf {
namespace {

Result<int> half(int v) {
  if (v % 2) return makeError(Errc::InvalidArgument, "odd: " + std::to_string(v));
  return v / 2;
}

Result<int> quarter(int v) {
  SCANSURF_ASSIGN_OR_RETURN(const int h, half(v));
  SCANSURF_ASSIGN_OR_RETURN(int q, half(h));
  return q;
}

Result<void> check(bool ok) {
  if (!ok) return makeError(Errc::InvalidInput, "not ok");
  return {};
}

int tryCalls = 0;
Result<void> twoChecks(bool first, bool second) {
  SCANSURF_TRY(check(first));
  ++tryCalls;
  SCANSURF_TRY(check(second));
  return {};
}

Result<int> tryInValueFunction(bool ok) {
  SCANSURF_TRY(check(ok));
  return 7;
}

TEST(Result, HoldsValue) {
  Result<int> r = half(8);
  ASSERT_TRUE(r.has_value());
  EXPECT_TRUE(static_cast<bool>(r));
  EXPECT_EQ(*r, 4);
  EXPECT_EQ(r.value(), 4);
  EXPECT_EQ(r.value_or(-1), 4);
}

TEST(Result, HoldsError) {
  Result<int> r = half(3);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, Errc::InvalidArgument);
  EXPECT_EQ(r.error().message, "odd: 3");
  EXPECT_FALSE(r.has_value());
  EXPECT_EQ(r.value_or(-1), -1);
}

TEST(Result, ArrowAndMoveOnlyValue) {
  Result<std::string> s = std::string("abc");
  EXPECT_EQ(s->size(), 3u);
  Result<std::unique_ptr<int>> p = std::make_unique<int>(5);
  std::unique_ptr<int> taken = std::move(p).value();
  EXPECT_EQ(*taken, 5);
}

TEST(Result, VoidResult) {
  EXPECT_TRUE(check(true));
  const Result<void> r = check(false);
  EXPECT_FALSE(r);
  EXPECT_EQ(r.error().code, Errc::InvalidInput);
  EXPECT_EQ(r.error().message, "not ok");
}

TEST(Result, TakeErrorConvertsAcrossTypes) {
  Result<int> r = half(1);
  Result<std::string> s = std::move(r).takeError();
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().message, "odd: 1");
}

TEST(ResultMacros, AssignOrReturnPropagates) {
  EXPECT_EQ(*quarter(8), 2);
  const Result<int> r = quarter(6);  // 6 -> 3 -> odd
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message, "odd: 3");
  EXPECT_EQ(quarter(5).error().message, "odd: 5");
}

TEST(ResultMacros, TryStopsAtFirstError) {
  tryCalls = 0;
  EXPECT_TRUE(twoChecks(true, true));
  EXPECT_EQ(tryCalls, 1);
  EXPECT_FALSE(twoChecks(false, true));
  EXPECT_EQ(tryCalls, 1);
  EXPECT_FALSE(twoChecks(true, false));
  EXPECT_EQ(tryCalls, 2);
}

TEST(ResultMacros, TryInFunctionReturningValue) {
  EXPECT_EQ(*tryInValueFunction(true), 7);
  EXPECT_EQ(tryInValueFunction(false).error().code, Errc::InvalidInput);
}

}  // namespace
}  // namespace scansurf
