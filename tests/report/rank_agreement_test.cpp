// Kendall's tau between scenes' rankings (rank_agreement.h) against examples computed by hand,
// and the tied ranks of rank_significance.h on units whose differences are clear or nil.
#include <gtest/gtest.h>

#include <cmath>

#include "rank_agreement.h"
#include "rank_significance.h"

using namespace gbl;

// Five layouts; scene A orders them 1 2 3 4 5, scene B 3 4 1 2 5 (scores = positions).
// Of the 10 pairs, (1,3) (1,4) (2,3) (2,4) are ordered oppositely: C = 6, D = 4,
// tau = (6 - 4) / 10 = 0.2.
TEST(RankAgreement, KendallTauOfAHandWorkedExample) {
    const KendallTau k = kendallTau({1, 2, 3, 4, 5}, {3, 4, 1, 2, 5});
    EXPECT_EQ(k.pairs, 10);
    EXPECT_EQ(k.concordant, 6);
    EXPECT_EQ(k.discordant, 4);
    EXPECT_DOUBLE_EQ(k.tau, 0.2);
    ASSERT_EQ(k.swaps.size(), 4u);
    EXPECT_EQ(k.swaps[0], std::make_pair(0, 2));
    EXPECT_EQ(k.swaps[3], std::make_pair(1, 3));
    EXPECT_DOUBLE_EQ(kendallTau({1, 2, 3}, {3, 2, 1}).tau, -1.0);
    EXPECT_DOUBLE_EQ(kendallTau({0.1, 0.2, 0.3}, {5, 6, 7}).tau, 1.0);
}

// With ties, tau-b: a = (1, 2, 2, 3), b = (1, 3, 2, 4). Pairs: 6; tied in a: (2,3) -> n1 = 1;
// tied in b: none. Untied in a: (1,2) C, (1,3) C, (1,4) C, (2,4) C, (3,4) C -> C = 5, D = 0;
// tau-b = 5 / sqrt(5 x 6) = 0.9129.
TEST(RankAgreement, TauBWithTies) {
    const KendallTau k = kendallTau({1, 2, 2, 3}, {1, 3, 2, 4});
    EXPECT_EQ(k.concordant, 5);
    EXPECT_EQ(k.discordant, 0);
    EXPECT_EQ(k.tiedA, 1);
    EXPECT_NEAR(k.tau, 5.0 / std::sqrt(30.0), 1e-12);
}

// Three layouts: a and b differ by noise only (the signs of their differences alternate), c is
// clearly worse on every unit. Ranks: a, b share 1-2; c is 3.
TEST(RankAgreement, TiedRanksFromSignificance) {
    std::vector<double> a, b, c;
    for (int u = 0; u < 40; ++u) {
        a.push_back(0.010 + 0.001 * (u % 5));
        b.push_back(a.back() + (u % 2 ? 0.0004 : -0.0003));
        c.push_back(a.back() + 0.005);
    }
    const SignificanceReport r = rankWithSignificance(std::vector<LayoutUnits>{
        {"c", "split-sum", 0.017, {c}}, {"a", "split-sum", 0.012, {a}}, {"b", "split-sum", 0.01205, {b}}});
    ASSERT_EQ(r.ranks.size(), 3u);
    EXPECT_EQ(r.find("a", "split-sum")->text(), "1-2");
    EXPECT_EQ(r.find("b", "split-sum")->text(), "1-2");
    EXPECT_EQ(r.find("c", "split-sum")->text(), "3");
    ASSERT_EQ(r.pairs.size(), 3u);
    for (const PairSignificance& p : r.pairs) EXPECT_EQ(p.significant, p.worse == "c") << p.better << " " << p.worse;
}
