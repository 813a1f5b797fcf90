// GBL_EVAL_PROFILE's summary (src/evaluate/eval_profile.h): the kinds that ran, slowest first,
// with their calls, totals, means and shares as worked out here by hand.
#include <gtest/gtest.h>

#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "eval_profile.h"

namespace gbl::evaluate {
namespace {

std::vector<std::string> lines(const std::string& s) {
    std::vector<std::string> out;
    std::istringstream in(s);
    for (std::string l; std::getline(in, l);) out.push_back(l);
    return out;
}

TEST(EvalProfile, SummaryListsKindsSlowestFirstWithTheirShares) {
    EvalProfile p({"A", "B", "C"}, "dev");
    p.add(0, 0.010);  // A: 2 calls, 30 ms
    p.add(0, 0.020);
    p.add(2, 0.090);  // C: 1 call, 90 ms; B never ran
    const std::vector<std::string> l = lines(p.summary());
    ASSERT_EQ(l.size(), 5u);  // title, header, C, A, total
    EXPECT_NE(l[0].find("'dev'"), std::string::npos);
    std::istringstream c(l[2]), a(l[3]), all(l[4]);
    std::string name, share;
    unsigned calls = 0;
    double total = 0, mean = 0;
    c >> name >> calls >> total >> mean >> share;
    EXPECT_EQ(name, "C");
    EXPECT_EQ(calls, 1u);
    EXPECT_DOUBLE_EQ(total, 90.0);
    EXPECT_EQ(share, "75.0%");  // 90 of 120 ms
    a >> name >> calls >> total >> mean >> share;
    EXPECT_EQ(name, "A");
    EXPECT_EQ(calls, 2u);
    EXPECT_DOUBLE_EQ(total, 30.0);
    EXPECT_DOUBLE_EQ(mean, 15.0);
    EXPECT_EQ(share, "25.0%");
    all >> name >> total;
    EXPECT_EQ(name, "all");
    EXPECT_DOUBLE_EQ(total, 120.0);
}

TEST(EvalProfile, WantedOnlyWhenSetToSomethingButZero) {
    ::unsetenv("GBL_EVAL_PROFILE");
    EXPECT_FALSE(EvalProfile::wanted());
    ::setenv("GBL_EVAL_PROFILE", "0", 1);
    EXPECT_FALSE(EvalProfile::wanted());
    ::setenv("GBL_EVAL_PROFILE", "", 1);
    EXPECT_FALSE(EvalProfile::wanted());
    ::setenv("GBL_EVAL_PROFILE", "1", 1);
    EXPECT_TRUE(EvalProfile::wanted());
    ::unsetenv("GBL_EVAL_PROFILE");
}

}  // namespace
}  // namespace gbl::evaluate
