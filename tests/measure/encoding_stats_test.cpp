// Tests for the encoding registry and the `gbufferlab encodings` measurement.
#include <gtest/gtest.h>

#include <cctype>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "encoding_registry.h"
#include "encoding_stats.h"
#include "error.h"

namespace {

using namespace gbl;

TEST(EncodingRegistry, NamesAreUniqueSnakeCaseAndRangesValid) {
    std::set<std::string> names;
    for (const EncodingInfo& e : listEncodings()) {
        EXPECT_TRUE(names.insert(e.name).second) << "duplicate " << e.name;
        for (char c : e.name) EXPECT_TRUE(std::islower(static_cast<unsigned char>(c)) || std::isdigit(c) || c == '_') << e.name;
        EXPECT_GE(e.codeCount, 1) << e.name;
        EXPECT_LE(e.minBits, e.defaultBits) << e.name;
        EXPECT_LE(e.defaultBits, e.maxBits) << e.name;
        EXPECT_GE(e.minBits, 1) << e.name;
        EXPECT_LE(e.maxBits, 32) << e.name;
        EXPECT_TRUE(encodingBitsValid(e, e.defaultBits)) << e.name;
        EXPECT_FALSE(encodingBitsValid(e, e.maxBits + 1)) << e.name;
        EXPECT_FALSE(e.description.empty()) << e.name;
        EXPECT_FALSE(e.source.empty()) << e.name;
        EXPECT_EQ(findEncoding(e.name), &e);
        EXPECT_NE(knownEncodingNames().find(e.name), std::string::npos);
    }
    for (const char* required : {"unorm", "snorm", "float16", "float11", "float10", "float32", "srgb8", "normal_xyz",
                                 "normal_bestfit", "normal_xy_zsign", "normal_spheremap", "normal_stereographic",
                                 "normal_octahedral", "normal_octahedral_precise", "ycbcr", "ycbcr_sqrt", "ycocg",
                                 "luma"})
        EXPECT_NE(findEncoding(required), nullptr) << required;
    EXPECT_EQ(findEncoding("octt"), nullptr);
    EXPECT_EQ(encodingTotalBits(*findEncoding("normal_xy_zsign"), 8), 17);
    EXPECT_EQ(encodingTotalBits(*findEncoding("normal_octahedral"), 12), 24);
    EXPECT_EQ(encodingTotalBits(*findEncoding("srgb8"), 8), 24);
    EXPECT_STREQ(attributeKindName(findEncoding("ycocg")->kind), "color");
}

TEST(EncodingStats, DeltaE2000MatchesSharmaTestData) {
    // Sharma, Wu, Dalal (2005), table 1 (pairs 1, 2, 3, 4, 7, 8, 9, 11, 17, 18, 19, 20, 21, 25).
    struct Pair {
        double l1, a1, b1, l2, a2, b2, de;
    };
    const Pair pairs[] = {
        {50.0, 2.6772, -79.7751, 50.0, 0.0, -82.7485, 2.0425},
        {50.0, 3.1571, -77.2803, 50.0, 0.0, -82.7485, 2.8615},
        {50.0, 2.8361, -74.0200, 50.0, 0.0, -82.7485, 3.4412},
        {50.0, -1.3802, -84.2814, 50.0, 0.0, -82.7485, 1.0000},
        {50.0, 0.0, 0.0, 50.0, -1.0, 2.0, 2.3669},
        {50.0, -1.0, 2.0, 50.0, 0.0, 0.0, 2.3669},
        {50.0, 2.4900, -0.0010, 50.0, -2.4900, 0.0009, 7.1792},
        {50.0, 2.4900, -0.0010, 50.0, -2.4900, 0.0011, 7.2195},
        {50.0, 2.5, 0.0, 73.0, 25.0, -18.0, 27.1492},
        {50.0, 2.5, 0.0, 61.0, -5.0, 29.0, 22.8977},
        {50.0, 2.5, 0.0, 56.0, -27.0, -3.0, 31.9030},
        {50.0, 2.5, 0.0, 58.0, 24.0, 15.0, 19.4535},
        {50.0, 2.5, 0.0, 50.0, 3.1736, 0.5854, 1.0000},
        {60.2574, -34.0099, 36.2677, 60.4626, -34.1751, 39.4387, 1.2644},
    };
    for (const Pair& p : pairs)
        EXPECT_NEAR(deltaE2000({p.l1, p.a1, p.b1}, {p.l2, p.a2, p.b2}), p.de, 1e-4) << p.l1 << " " << p.a1 << " " << p.b1;
    EXPECT_EQ(deltaE2000({40, 10, -5}, {40, 10, -5}), 0.0);
}

TEST(EncodingStats, LabOfWhiteAndBlack) {
    glm::dvec3 w = linearSrgbToLab({1, 1, 1});
    EXPECT_NEAR(w.x, 100.0, 1e-3);
    EXPECT_NEAR(w.y, 0.0, 1e-2);
    EXPECT_NEAR(w.z, 0.0, 1e-2);
    glm::dvec3 k = linearSrgbToLab({0, 0, 0});
    EXPECT_NEAR(k.x, 0.0, 1e-9);
    glm::dvec3 mid = linearSrgbToLab({0.18, 0.18, 0.18});
    EXPECT_NEAR(mid.x, 49.5, 0.1);  // 18% grey is L* ~ 49.5
}

TEST(EncodingStats, UniformSphereIsUnitAndCentred) {
    glm::dvec3 sum(0.0);
    for (int i = 0; i < 64; ++i)
        for (int j = 0; j < 64; ++j) {
            glm::dvec3 n = uniformSphere((i + 0.5) / 64.0, (j + 0.5) / 64.0);
            EXPECT_NEAR(glm::length(n), 1.0, 1e-12);
            sum += n;
        }
    EXPECT_LT(glm::length(sum) / 4096.0, 1e-3);
    EXPECT_NEAR(angleDegrees({1, 0, 0}, {0, 1, 0}), 90.0, 1e-12);
    EXPECT_NEAR(angleDegrees({1, 0, 0}, {-1, 0, 0}), 180.0, 1e-12);
}

TEST(EncodingStats, EveryRegisteredEncodingMeasures) {
    std::vector<EncodingStats> all = measureAllEncodings(4096, 3);
    ASSERT_EQ(all.size(), listEncodings().size());
    for (const EncodingStats& s : all) {
        EXPECT_EQ(s.samples, 4096) << s.encoding;
        EXPECT_GE(s.maxError, s.p99Error) << s.encoding;
        EXPECT_GE(s.p99Error, 0.0) << s.encoding;
        EXPECT_GE(s.maxError, s.meanError) << s.encoding;
        EXPECT_EQ(s.hasDeltaE, s.kind == AttributeKind::Color) << s.encoding;
        EXPECT_FALSE(s.domain.empty()) << s.encoding;
    }
    std::string table = formatEncodingStatsTable(all);
    EXPECT_NE(table.find("encoding"), std::string::npos);
    EXPECT_NE(table.find("normal_octahedral_precise"), std::string::npos);
    nlohmann::json j = encodingStatsToJson(all);
    ASSERT_TRUE(j.is_array());
    ASSERT_EQ(j.size(), all.size());
    EXPECT_TRUE(j[0].contains("mean"));
    EXPECT_TRUE(j[0].contains("p99"));
    EXPECT_TRUE(j[0].contains("max"));
}

TEST(EncodingStats, FiguresMatchTheDocumentedBounds) {
    EncodingStats u = measureEncoding("unorm", 8, 100000, 1);
    EXPECT_LE(u.maxError, 0.5 / 255.0 + 1e-7);
    EXPECT_NEAR(u.meanError, 0.25 / 255.0, 0.02 / 255.0);  // uniform error in +-half step
    EncodingStats f32 = measureEncoding("float32", 32, 10000, 1);
    EXPECT_EQ(f32.maxError, 0.0);
    EncodingStats oct = measureEncoding("normal_octahedral", 12, 100000, 1);
    EXPECT_EQ(oct.unit, "deg");
    EXPECT_EQ(oct.totalBits, 24);
    EXPECT_LT(oct.maxError, 0.06);
    EncodingStats bf = measureEncoding("normal_bestfit", 8, 50000, 1);
    EncodingStats xyz = measureEncoding("normal_xyz", 8, 50000, 1);
    EXPECT_LT(bf.meanError * 5.0, xyz.meanError);
    EncodingStats s8 = measureEncoding("srgb8", 8, 100000, 1);
    EXPECT_LT(s8.maxDeltaE, 1.0);  // exact sRGB 8 bits: below one just-noticeable difference
    EncodingStats y = measureEncoding("ycbcr", 8, 100000, 1);
    EncodingStats ys = measureEncoding("ycbcr_sqrt", 8, 100000, 1);
    EXPECT_LT(ys.maxDeltaE, y.maxDeltaE);  // the sqrt pre-transform helps the darks
}

TEST(EncodingStats, IsDeterministicForASeed) {
    EncodingStats a = measureEncoding("normal_spheremap", 10, 20000, 9);
    EncodingStats b = measureEncoding("normal_spheremap", 10, 20000, 9);
    EXPECT_EQ(a.meanError, b.meanError);
    EXPECT_EQ(a.maxError, b.maxError);
}

TEST(EncodingStats, BadInputSaysWhatIsKnown) {
    try {
        measureEncoding("octt", 8);
        FAIL() << "no error";
    } catch (const UserError& e) {
        std::string m = e.what();
        EXPECT_NE(m.find("unknown encoding 'octt'"), std::string::npos) << m;
        EXPECT_NE(m.find("normal_octahedral"), std::string::npos) << m;
    }
    EXPECT_THROW(measureEncoding("normal_octahedral", 17), UserError);
    EXPECT_THROW(measureEncoding("normal_bestfit", 10), UserError);
    EXPECT_THROW(measureEncoding("unorm", 8, 0), UserError);
    EXPECT_THROW(roundTripColor("normal_xyz", 8, glm::vec3(0.5f)), UserError);
    EXPECT_THROW(roundTripColor("ycocg_checkerboard", 8, glm::vec3(0.5f)), UserError);
}

}  // namespace
