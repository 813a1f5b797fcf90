// Kendall's tau-b and the swapped pairs (rank_agreement.h).
#include "rank_agreement.h"

#include <cmath>
#include <stdexcept>

namespace gbl {

KendallTau kendallTau(const std::vector<double>& a, const std::vector<double>& b) {
    if (a.size() != b.size()) throw std::invalid_argument("kendallTau: rankings of different lengths");
    KendallTau k;
    const size_t n = a.size();
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 1; j < n; ++j) {
            ++k.pairs;
            const double da = a[i] - a[j], db = b[i] - b[j];
            if (da == 0.0) ++k.tiedA;
            if (db == 0.0) ++k.tiedB;
            if (da == 0.0 || db == 0.0) continue;
            if ((da > 0.0) == (db > 0.0)) {
                ++k.concordant;
            } else {
                ++k.discordant;
                k.swaps.emplace_back(int(i), int(j));
            }
        }
    const double denominator = std::sqrt(double(k.pairs - k.tiedA) * double(k.pairs - k.tiedB));
    k.tau = denominator > 0.0 ? double(k.concordant - k.discordant) / denominator : 1.0;
    return k;
}

}  // namespace gbl
