// The engine constraints and the every-metric front: no candidate the search evaluates breaks a
// constraint (checked on the layout text by the test's own reading, not by the code under test),
// --min-bits parses or fails in one line, the Pareto front over bytes and nine metrics equals an
// independent brute force, and the trade text says what changed by how much.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "error.h"
#include "layout.h"
#include "layout_catalog.h"
#include "search_journal.h"
#include "layout_packer.h"
#include "layout_search.h"
#include "search_constraints.h"
#include "search_metrics.h"

namespace gbl::search {
namespace {

// A deterministic stand-in for the fast evaluation: pseudo-metrics from the layout text's hash
// (the constraint tests need candidates, not their quality).
EvaluateFn hashEvaluation() {
    return [](const std::string& text) {
        uint64_t h = textHash(text);
        Evaluation e;
        auto next = [&] {
            h = h * 6364136223846793005ULL + 1442695040888963407ULL;
            return double(h >> 11) / double(1ULL << 53);
        };
        e.flip = next();
        e.psnr = 30.0 + 20.0 * next();
        e.normalDeg = next();
        e.baseColorDe = next();
        e.diffuseColorDe = next();
        e.specularColorDe = next();
        e.roughness = next();
        e.metallic = next();
        e.occlusion = next();
        e.error = e.flip;
        return e;
    };
}

// The test's own reading of a layout's text: the depth format, and per attribute the widest
// code, from the `at` places ("r", "g[0:5]", ["r", "g"]) against the target format's channels.
struct TextFacts {
    std::string depth;
    std::map<std::string, int> widest;
    int stencilFieldBits = 0;
};

int channelBits(const std::string& format, const std::string& channel) {
    // The formats the packer uses (layout_packer.cpp formatsBySize).
    if (format == "R8_UNORM" || format == "R8G8_UNORM" || format == "R8G8B8A8_UNORM") return 8;
    if (format == "R16_UNORM" || format == "R16_UINT" || format == "R16G16_UNORM" || format == "R16G16B16A16_UNORM")
        return 16;
    if (format == "R32_UINT" || format == "R32G32_UINT") return 32;
    if (format == "A2B10G10R10_UNORM_PACK32") return channel == "a" ? 2 : 10;
    ADD_FAILURE() << "unknown format " << format;
    return 0;
}

TextFacts readFacts(const std::string& text) {
    TextFacts f;
    std::smatch m;
    EXPECT_TRUE(std::regex_search(text, m, std::regex("\\[depth\\]\\nformat = \"([A-Z0-9_]+)\""))) << text;
    f.depth = m[1];
    EXPECT_EQ(text.find("stencil"), std::string::npos) << "the packer writes no stencil fields";
    const std::regex format("^format = \"([A-Z0-9_]+)\"");
    const std::regex field("attribute = \"([a-z_]+)\", encoding = \"[a-z0-9_]+\", at = (.*) \\},$");
    const std::regex place("\"([rgba])(?:\\[(\\d+)(?::(\\d+))?\\])?\"");
    std::istringstream lines(text);
    std::string line, targetFormat;
    bool inTarget = false;
    while (std::getline(lines, line)) {
        if (line == "[[target]]") inTarget = true;
        else if (!line.empty() && line[0] == '[') inTarget = false;
        if (inTarget && std::regex_search(line, m, format)) targetFormat = m[1];
        if (!inTarget || !std::regex_search(line, m, field)) continue;
        const std::string attribute = m[1], at = m[2];
        for (std::sregex_iterator p(at.begin(), at.end(), place), end; p != end; ++p) {
            int bits = channelBits(targetFormat, (*p)[1]);
            if ((*p)[2].matched) bits = (*p)[3].matched ? std::stoi((*p)[3]) - std::stoi((*p)[2]) + 1 : 1;
            f.widest[attribute] = std::max(f.widest[attribute], bits);
        }
    }
    EXPECT_FALSE(f.widest.empty()) << text;
    return f;
}

SearchOptions options(const EngineConstraints& c, int candidates, int budget) {
    SearchOptions o;
    o.budgetBytes = budget;
    o.seed = 3;
    o.candidates = candidates;
    o.batch = 8;
    o.threads = 2;
    o.constraints = c;
    return o;
}

TEST(SearchConstraints, NoEvaluatedCandidateBreaksAConstraint) {
    EngineConstraints c;  // the defaults
    const SearchResult r = runSearch(hashEvaluation(), options(c, 400, 16));
    ASSERT_EQ(r.evaluated.size(), 400u);
    EXPECT_EQ(r.rejectedByConstraints, 0);
    std::set<std::string> depths;
    for (const Candidate& cand : r.evaluated) {
        const std::string text = layoutText("candidate", "", cand.body);
        const TextFacts f = readFacts(text);
        depths.insert(f.depth);
        EXPECT_TRUE(f.depth == "D24_UNORM_S8_UINT" || f.depth == "D32_SFLOAT") << f.depth;
        for (const auto& [attribute, bits] : f.widest) {
            const int floor = attribute == "normal" ? 8 : attribute == "roughness" ? 7 : attribute == "occlusion" ? 4 : 8;
            EXPECT_GE(bits, floor) << attribute << " in candidate #" << cand.index << "\n" << text;
        }
        EXPECT_TRUE(constraintViolations(parseLayout(text, "c.toml"), c).empty());
    }
    EXPECT_EQ(depths.size(), 2u);  // both family formats are explored

    // Loosened, the same search does go below: the constraints are what kept it out.
    EngineConstraints loose;
    loose.searchDepth = true;
    for (MinBits& m : loose.minBits) m.bits = 0;
    const SearchResult l = runSearch(hashEvaluation(), options(loose, 400, 16));
    bool d16 = false, oneBitOcclusion = false, thinRoughness = false;
    for (const Candidate& cand : l.evaluated) {
        const TextFacts f = readFacts(layoutText("candidate", "", cand.body));
        d16 = d16 || f.depth == "D16_UNORM";
        oneBitOcclusion = oneBitOcclusion || (f.widest.count("occlusion") && f.widest.at("occlusion") < 4);
        thinRoughness = thinRoughness || (f.widest.count("roughness") && f.widest.at("roughness") < 7);
    }
    EXPECT_TRUE(d16);
    EXPECT_TRUE(oneBitOcclusion);
    EXPECT_TRUE(thinRoughness);
}

TEST(SearchConstraints, ViolationsOfPublishedAndHandWrittenLayouts) {
    const EngineConstraints c;
    // Shipped layouts meet the defaults (they are the defaults' source) ...
    for (const char* name : {"ue4", "crysis3-thin", "compact-octahedral", "granite", "ryse"}) {
        SCOPED_TRACE(name);
        Layout l = loadLayout(name);
        l.depth.stencil.clear();  // their stencil holds the engine's own flags, which is what the rule keeps free
        EXPECT_TRUE(constraintViolations(l, c).empty()) << constraintViolations(l, c).front();
    }
    // ... and D16, a 1-bit occlusion and a stencil with 3 free bits each break one.
    Genome g;
    g.occlusionBits = 1;
    g.depthFormat = 0;  // D16
    ASSERT_STREQ(depthFormats()[0].format, "D16_UNORM");
    const PackResult p = packGenome(g, 64);
    ASSERT_TRUE(p.ok) << p.why;
    const std::vector<std::string> v = constraintViolations(parseLayout(layoutText("x", "", p.body), "x.toml"), c);
    ASSERT_EQ(v.size(), 2u);
    EXPECT_NE(v[0].find("D16_UNORM"), std::string::npos) << v[0];
    EXPECT_NE(v[1].find("occlusion stored in 1 bits"), std::string::npos) << v[1];
    Layout thin = loadLayout("crysis3-thin");  // ambient id s[0:3] + decals s[4:7]: no stencil bit free
    const std::vector<std::string> s = constraintViolations(thin, c);
    ASSERT_EQ(s.size(), 1u);
    EXPECT_NE(s[0].find("0 stencil bits free"), std::string::npos) << s[0];
    // constrainGenome lifts what it can: the same genome, constrained, breaks nothing.
    constrainGenome(g, c);
    const PackResult q = packGenome(g, 64);
    ASSERT_TRUE(q.ok);
    EXPECT_TRUE(constraintViolations(parseLayout(layoutText("x", "", q.body), "x.toml"), c).empty());
    EXPECT_EQ(g.occlusionBits, 4);
    EXPECT_NE(std::string(depthFormats()[size_t(g.depthFormat)].format), "D16_UNORM");
}

TEST(SearchConstraints, MinBitsParsesAndRefusesInOneLine) {
    EngineConstraints c;
    parseMinBits("occlusion=5,roughness=6", c);
    EXPECT_EQ(minBitsOf(c, "occlusion"), 5);
    EXPECT_EQ(minBitsOf(c, "roughness"), 6);
    EXPECT_EQ(minBitsOf(c, "normal"), 8);  // untouched
    parseMinBits("normal=0", c);
    EXPECT_EQ(minBitsOf(c, "normal"), 0);
    const std::pair<const char*, const char*> bad[] = {
        {"", "empty"},
        {"occlusion", "not ATTRIBUTE=BITS"},
        {"occlusion=4,,roughness=6", "not ATTRIBUTE=BITS"},
        {"occlusion=4,", "trailing comma"},
        {"albedo=4", "unknown attribute 'albedo'"},
        {"occlusion=four", "whole number from 0"},
        {"occlusion=-1", "whole number from 0"},
        {"occlusion=9", "to 8"},
        {"roughness=13", "to 12"},
        {"occlusion=", "whole number"},
    };
    for (const auto& [text, needle] : bad) {
        SCOPED_TRACE(text);
        EngineConstraints d;
        try {
            parseMinBits(text, d);
            FAIL() << "expected a UserError";
        } catch (const UserError& e) {
            const std::string m = e.what();
            EXPECT_EQ(m.rfind("--min-bits", 0), 0u) << m;
            EXPECT_NE(m.find(needle), std::string::npos) << m;
            EXPECT_EQ(m.find('\n'), std::string::npos) << m;
        }
    }
}

// Brute force, written here: i is on the front iff no j is at most as costly and no worse on
// every metric while better on one, or equal on everything and earlier.
TEST(SearchMetrics, ParetoFrontOverEveryMetricMatchesBruteForce) {
    SplitMix64 rng(11);
    std::vector<Candidate> cands(300);
    for (size_t i = 0; i < cands.size(); ++i) {
        Candidate& c = cands[i];
        c.index = int(i);
        c.bytes = rng.range(6, 16);
        // Few levels: ties and exact duplicates on purpose.
        auto level = [&] { return double(rng.range(0, 3)) / 4.0; };
        c.eval.flip = level();
        c.eval.psnr = 40.0 + 4.0 * level();
        c.eval.normalDeg = level();
        c.eval.baseColorDe = level();
        c.eval.diffuseColorDe = level();
        c.eval.specularColorDe = level();
        c.eval.roughness = level();
        c.eval.metallic = level();
        c.eval.occlusion = level();
        c.eval.error = c.eval.flip;
        if (i % 37 == 5) c.eval = cands[i - 3].eval, c.bytes = cands[i - 3].bytes;  // a duplicate, later
    }
    auto vec = [](const Candidate& c) {
        return std::vector<double>{double(c.bytes),       c.eval.flip,           -c.eval.psnr,
                                   c.eval.normalDeg,      c.eval.baseColorDe,    c.eval.diffuseColorDe,
                                   c.eval.specularColorDe, c.eval.roughness,      c.eval.metallic,
                                   c.eval.occlusion};
    };
    std::vector<int> expected;
    for (size_t i = 0; i < cands.size(); ++i) {
        bool beaten = false;
        for (size_t j = 0; j < cands.size() && !beaten; ++j) {
            if (i == j) continue;
            const std::vector<double> a = vec(cands[j]), b = vec(cands[i]);
            bool noWorse = true, strictly = false;
            for (size_t k = 0; k < a.size(); ++k) {
                noWorse = noWorse && a[k] <= b[k];
                strictly = strictly || a[k] < b[k];
            }
            beaten = noWorse && (strictly || j < i);
        }
        if (!beaten) expected.push_back(int(i));
    }
    std::vector<int> front = paretoFront(cands);
    // Its order: by bytes, then the objective (error), then index.
    for (size_t k = 1; k < front.size(); ++k) {
        const Candidate &a = cands[size_t(front[k - 1])], &b = cands[size_t(front[k])];
        EXPECT_TRUE(a.bytes < b.bytes || (a.bytes == b.bytes && (a.eval.error < b.eval.error ||
                                                                  (a.eval.error == b.eval.error && a.index < b.index))));
    }
    std::sort(front.begin(), front.end());
    EXPECT_EQ(front, expected);
    EXPECT_GT(expected.size(), 10u);  // nine metrics: a wide front
    EXPECT_LT(expected.size(), cands.size());
}

TEST(SearchMetrics, VerdictAndTradeText) {
    Evaluation pub, found;
    pub.flip = 0.01;
    pub.psnr = 57.2;
    pub.normalDeg = 0.5;
    pub.baseColorDe = 1.0;
    pub.occlusion = 0.0;
    found = pub;
    EXPECT_EQ(verdictOf(found, pub), Verdict::Equal);
    EXPECT_EQ(tradeText(found, pub), "");
    found.flip = 0.007;
    EXPECT_EQ(verdictOf(found, pub), Verdict::Beats);
    EXPECT_EQ(tradeText(found, pub), "FLIP -30 %");
    found.psnr = 44.2;
    EXPECT_EQ(verdictOf(found, pub), Verdict::Trade);
    EXPECT_EQ(tradeText(found, pub), "FLIP -30 %, PSNR -13.0 dB");
    found.occlusion = 0.0312;  // the published one's is 0: an absolute change
    found.normalDeg = 0.52;    // +4 %: one decimal under 10 %
    EXPECT_EQ(tradeText(found, pub), "FLIP -30 %, PSNR -13.0 dB, normal +4.0 %, occlusion +0.0312");
    Evaluation tiny = found;  // a rounding-level error against a real one: absolute, not +1e9 %
    tiny.metallic = 0.014;
    Evaluation roundingOnly = pub;
    roundingOnly.metallic = 7e-12;
    roundingOnly.psnr = 44.25;
    EXPECT_EQ(tradeText(tiny, roundingOnly), "FLIP -30 %, PSNR -0.05 dB, normal +4.0 %, metallic +0.0140, occlusion +0.0312");
    found.flip = 0.01;
    EXPECT_EQ(verdictOf(found, pub), Verdict::Loses);
    EXPECT_TRUE(dominates(12, pub, 12, found));
    EXPECT_FALSE(dominates(12, found, 12, pub));
    EXPECT_TRUE(dominates(8, pub, 12, pub));   // cheaper, equal on every metric
    EXPECT_FALSE(dominates(12, pub, 12, pub));  // equal on all: neither
}

}  // namespace
}  // namespace gbl::search
