#pragma once
// Do two scenes rank the layouts alike? Kendall's tau between two rankings (Kendall 1938; tau-b,
// which corrects for ties: Kendall 1945) and the pairs the two orders swap.
#include <utility>
#include <vector>

namespace gbl {

struct KendallTau {
    double tau = 1.0;     // tau-b in [-1, 1]; 1: the same order (NaN-free: 1 when fewer than 2 items)
    int pairs = 0;        // n (n - 1) / 2
    int concordant = 0;   // ordered alike by both
    int discordant = 0;   // ordered oppositely: the swaps
    int tiedA = 0, tiedB = 0;  // tied in a (in b), whatever the other says
    std::vector<std::pair<int, int>> swaps;  // the discordant pairs (i < j)
};

// a[i], b[i]: item i's score under each ranking (lower = better; only the order matters).
// tau-b = (C - D) / sqrt((n0 - n1)(n0 - n2)), n0 = pairs, n1 / n2 = pairs tied in a / b.
KendallTau kendallTau(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace gbl
