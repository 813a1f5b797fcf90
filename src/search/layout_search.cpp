#include "layout_search.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <map>
#include <memory>
#include <numeric>
#include <unordered_set>

#include "error.h"
#include "layout.h"
#include "layout_packer.h"
#include "parallel_for.h"
#include "search_journal.h"
#include "search_metrics.h"

namespace gbl::search {

namespace {

constexpr int kRandomRounds = 2;         // rounds of random genomes before mutation starts
constexpr double kRandomChance = 0.15;   // afterwards, a fresh genome instead of a mutation
constexpr int kPoolPerBytes = 3;         // parents: the best few at each byte count
constexpr int kAttemptsPerCandidate = 2000;

bool better(const Candidate& a, const Candidate& b) {
    if (a.eval.error != b.eval.error) return a.eval.error < b.eval.error;
    return a.index < b.index;
}

// Parents: the front's best few at each byte count, in the objective's order.
std::vector<int> parentPool(const std::vector<Candidate>& cands, const std::vector<int>& front) {
    std::map<int, std::vector<int>> byBytes;
    for (int i : front) {
        auto& v = byBytes[cands[size_t(i)].bytes];
        v.push_back(i);
        std::sort(v.begin(), v.end(), [&](int a, int b) { return better(cands[size_t(a)], cands[size_t(b)]); });
        if (v.size() > size_t(kPoolPerBytes)) v.pop_back();
    }
    std::vector<int> pool;
    for (const auto& [bytes, v] : byBytes) pool.insert(pool.end(), v.begin(), v.end());
    return pool;
}

// a precedes b in the front's partial order: no worse on bytes and every metric, and better on
// one, or equal on all and earlier (of identical scores the earlier candidate stays).
bool precedes(const Candidate& a, const Candidate& b) {
    if (a.bytes > b.bytes || !noWorseOnAll(a.eval, b.eval)) return false;
    return dominates(a.bytes, a.eval, b.bytes, b.eval) || a.index < b.index;
}

// Adds candidate i to the archive `front` (the members no other candidate precedes). The order
// is transitive, so a candidate preceded by anyone is preceded by a member: comparing with the
// members is enough, and the archive ends the same whatever the insertion order.
void insertIntoFront(const std::vector<Candidate>& cands, std::vector<int>& front, int i) {
    const Candidate& c = cands[size_t(i)];
    for (int f : front)
        if (precedes(cands[size_t(f)], c)) return;
    front.erase(std::remove_if(front.begin(), front.end(), [&](int f) { return precedes(c, cands[size_t(f)]); }),
                front.end());
    front.push_back(i);
}

// A random genome is drawn for a random size: its byte target uniform over [smallest, budget],
// and shrinking moves (drop occlusion, metallic or the specular term, a two-code or luma colour,
// a bit less somewhere) applied until it packs into the target. Uniform genomes alone almost
// never pack small: with the engine constraints, 600 of them at --budget 16 held none under
// 12 B/px, and --budget 8 found none in 16,000 draws, though 8 B/px layouts exist.
void shrinkToFit(Genome& g, int targetBytes, SplitMix64& rng, const EngineConstraints& c) {
    constexpr int kMoves = 40;
    for (int move = 0; move < kMoves; ++move) {
        const PackResult p = packGenome(g, targetBytes);
        if (p.ok) return;
        // With layers (a scene that carries them) two moves more: put them under a selector (one
        // shared target), or drop one. Without, the same draws as before.
        const bool layers = g.coatBits || g.sheenBits || g.anisotropyBits;
        const int pick = layers ? rng.below(11) : rng.below(9);
        if (pick == 9) {
            g.layerSelector = true;
        } else if (pick == 10) {
            int& drop = g.coatNormalBits ? g.coatNormalBits : g.anisotropyBits ? g.anisotropyBits
                                                            : g.sheenBits      ? g.sheenBits
                                                                               : g.coatBits;
            drop = 0;
        }
        switch (pick >= 9 ? -1 : pick) {
            case -1: break;
            case 0: g.occlusionBits = 0; break;
            case 1: g.metallicBits = 0; break;
            case 2: g.specularMode = SpecularMode::FromMetallic; break;
            case 3: g.workflow = Workflow::Metallic; break;
            case 4: g.colourEncoding = rng.chance(0.5) ? int(colourEncodings().size()) - 3 : int(colourEncodings().size()) - 1; break;  // YCbCr checkerboard or luma
            case 5: g.normalBits -= 1 + rng.below(2); break;
            case 6: g.roughnessBits -= 1 + rng.below(2); break;
            case 7: g.colourBits -= 1 + rng.below(2); break;
            default: g.specularColourBits -= 1 + rng.below(2); break;
        }
        clampGenome(g);
        constrainGenome(g, c);
    }
}

void sortFront(const std::vector<Candidate>& cands, std::vector<int>& front) {
    std::sort(front.begin(), front.end(), [&](int a, int b) {
        const Candidate &x = cands[size_t(a)], &y = cands[size_t(b)];
        if (x.bytes != y.bytes) return x.bytes < y.bytes;
        return better(x, y);
    });
}

}  // namespace

std::vector<int> paretoFront(const std::vector<Candidate>& cands) {
    std::vector<int> front;
    for (size_t i = 0; i < cands.size(); ++i) insertIntoFront(cands, front, int(i));
    sortFront(cands, front);
    return front;
}

double spearman(const std::vector<double>& a, const std::vector<double>& b) {
    auto ranks = [](const std::vector<double>& v) {
        std::vector<size_t> o(v.size());
        std::iota(o.begin(), o.end(), size_t(0));
        std::stable_sort(o.begin(), o.end(), [&](size_t i, size_t j) { return v[i] < v[j]; });
        std::vector<double> r(v.size());
        for (size_t i = 0; i < o.size();) {
            size_t j = i;
            while (j + 1 < o.size() && v[o[j + 1]] == v[o[i]]) ++j;
            for (size_t k = i; k <= j; ++k) r[o[k]] = 0.5 * double(i + j) + 1.0;
            i = j + 1;
        }
        return r;
    };
    const std::vector<double> ra = ranks(a), rb = ranks(b);
    const double n = double(a.size());
    if (a.size() < 2) return 0.0;
    double ma = 0, mb = 0;
    for (size_t i = 0; i < a.size(); ++i) ma += ra[i], mb += rb[i];
    ma /= n, mb /= n;
    double sab = 0, saa = 0, sbb = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        sab += (ra[i] - ma) * (rb[i] - mb);
        saa += (ra[i] - ma) * (ra[i] - ma);
        sbb += (rb[i] - mb) * (rb[i] - mb);
    }
    return saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : 0.0;
}

SearchResult runSearch(const EvaluateFn& evaluate, const SearchOptions& options) {
    SearchResult result;
    std::unique_ptr<Journal> journal;
    if (!options.journalPath.empty()) journal = std::make_unique<Journal>(options.journalPath, options.journalKey);
    const std::vector<JournalEntry> recorded = journal ? journal->entries() : std::vector<JournalEntry>{};

    SplitMix64 rng(options.seed);
    std::unordered_set<std::string> seen;
    std::vector<Candidate>& cands = result.evaluated;
    const int total = options.candidates;
    const int threads = options.threads > 0 ? options.threads : hardwareThreads();
    double runSeconds = 0.0;
    int runEvaluated = 0;

    const int smallest = smallestPackedBytes(options.constraints);
    std::vector<int> front;  // the archive, updated in candidate order after each round
    for (int round = 0; int(cands.size()) < total; ++round) {
        if (options.stop && options.stop()) break;
        // Propose a batch from the archive as it stood at the end of the last round.
        sortFront(cands, front);
        const std::vector<int> pool = parentPool(cands, front);
        std::vector<Candidate> batch;
        const int want = std::min(options.batch, total - int(cands.size()));
        for (int attempt = 0; int(batch.size()) < want && attempt < kAttemptsPerCandidate * want; ++attempt) {
            Candidate c;
            if (round < kRandomRounds || pool.empty() || rng.chance(kRandomChance)) {
                c.genome = randomGenome(rng, options.layers);
                constrainGenome(c.genome, options.constraints);
                shrinkToFit(c.genome, rng.range(smallest, std::max(smallest, options.budgetBytes)), rng,
                            options.constraints);
                c.how = "random";
            } else {
                const Candidate& parent = cands[size_t(pool[size_t(rng.below(int(pool.size())))])];
                c.genome = mutateGenome(parent.genome, rng, options.layers);
                c.how = "mutation of #" + std::to_string(parent.index);
            }
            constrainGenome(c.genome, options.constraints);
            const PackResult packed = packGenome(c.genome, options.budgetBytes);
            if (!packed.ok) {
                (packed.bytesPerPixel > options.budgetBytes ? result.overBudget : result.unpackable)++;
                continue;
            }
            if (!seen.insert(packed.body).second) {
                result.duplicates++;
                continue;
            }
            // The real parser and validator: what `gbufferlab layouts check` runs.
            const std::vector<LayoutDiagnostic> diags =
                checkLayout(layoutText("candidate", "", packed.body), "candidate.toml");
            if (!diags.empty()) {
                result.rejectedByValidation++;
                if (result.validationMessages.size() < 5) result.validationMessages.push_back(diags.front().text());
                continue;
            }
            // The engine constraints, checked on the parsed layout (constrainGenome should make
            // this never fire; a candidate breaking them is never evaluated).
            const std::vector<std::string> broken =
                constraintViolations(parseLayout(layoutText("candidate", "", packed.body), "candidate.toml"),
                                     options.constraints);
            if (!broken.empty()) {
                result.rejectedByConstraints++;
                if (result.constraintMessages.size() < 5) result.constraintMessages.push_back(broken.front());
                continue;
            }
            c.body = packed.body;
            c.bytes = packed.bytesPerPixel;
            c.hash = textHash(c.body);
            c.index = int(cands.size() + batch.size());
            batch.push_back(std::move(c));
        }
        if (batch.empty()) break;  // the space under this budget is exhausted

        // Journal entries stand in for evaluations; the rest run in parallel.
        std::vector<size_t> todo;
        for (size_t i = 0; i < batch.size(); ++i) {
            Candidate& c = batch[i];
            if (size_t(c.index) < recorded.size()) {
                const JournalEntry& e = recorded[size_t(c.index)];
                if (e.hash != c.hash || e.bytes != c.bytes)
                    throwUserError(options.journalPath + ":" + std::to_string(c.index + 2) +
                                   ": the journal's candidate differs from the one this search proposes (another "
                                   "version of gbufferlab?); remove the journal or give another --out");
                c.eval = e.eval;
                c.fromJournal = true;
                result.resumed++;
            } else {
                todo.push_back(i);
            }
        }
        const auto start = std::chrono::steady_clock::now();
        const std::clock_t cpuStart = std::clock();
        parallelFor(int64_t(todo.size()), threads, [&](int64_t b, int64_t e) {
            for (int64_t k = b; k < e; ++k) {
                Candidate& c = batch[todo[size_t(k)]];
                c.eval = evaluate(layoutText("candidate", "", c.body));
            }
        });
        runSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        result.cpuSeconds += double(std::clock() - cpuStart) / double(CLOCKS_PER_SEC);
        runEvaluated += int(todo.size());
        for (Candidate& c : batch) {
            if (journal && !c.fromJournal) journal->append({c.index, c.hash, c.bytes, c.eval});
            cands.push_back(std::move(c));
            insertIntoFront(cands, front, int(cands.size()) - 1);
        }
        if (options.progress) {
            SearchProgress p;
            p.evaluated = int(cands.size());
            p.total = total;
            p.resumed = result.resumed;
            p.seconds = runSeconds;
            p.perMinute = runSeconds > 0 ? 60.0 * runEvaluated / runSeconds : 0.0;
            p.etaSeconds = p.perMinute > 0 ? (total - p.evaluated) * 60.0 / p.perMinute : 0.0;
            for (int f : front)
                if (!p.bestAtBudget || better(cands[size_t(f)], *p.bestAtBudget)) p.bestAtBudget = &cands[size_t(f)];
            options.progress(p);
        }
    }
    sortFront(cands, front);
    result.front = front;
    result.seconds = runSeconds;
    return result;
}

}  // namespace gbl::search
