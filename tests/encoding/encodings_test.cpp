// Tests for the normal encodings (src/encoding/encodings.h, mirror of shaders/normal_encodings.glsl).
// Exhaustive over every code up to 16 bits, millions of fixed-seed random inputs, and
// references written independently here in double arithmetic.
#include "encodings_test_support.h"

namespace {

using namespace gbl::enc;
using namespace gbl::enc_test;

// ---------------------------------------------------------------------------------------------
// Normals
// ---------------------------------------------------------------------------------------------

struct NormalCodec {
    const char* name;
    glm::vec3 (*roundTrip)(glm::vec3, uint);
};

glm::vec3 rtXyz(glm::vec3 n, uint b) { return decodeNormalXyz(encodeNormalXyz(n, b), b); }
glm::vec3 rtBestFit(glm::vec3 n, uint) { return decodeNormalBestFit(encodeNormalBestFit(n)); }
glm::vec3 rtBestFitSearch(glm::vec3 n, uint) { return decodeNormalBestFit(encodeNormalBestFitSearch(n)); }
glm::vec3 rtXyZSign(glm::vec3 n, uint b) { return decodeNormalXyZSign(encodeNormalXyZSign(n, b), b); }
glm::vec3 rtSpheremap(glm::vec3 n, uint b) { return decodeNormalSpheremap(encodeNormalSpheremap(n, b), b); }
glm::vec3 rtStereo(glm::vec3 n, uint b) { return decodeNormalStereographic(encodeNormalStereographic(n, b), b); }
glm::vec3 rtOct(glm::vec3 n, uint b) { return decodeNormalOctahedral(encodeNormalOctahedral(n, b), b); }
glm::vec3 rtOctP(glm::vec3 n, uint b) {
    return decodeNormalOctahedralPrecise(encodeNormalOctahedralPrecise(n, b), b);
}

struct AngleStats {
    double mean = 0.0, max = 0.0;
};

AngleStats measureNormals(glm::vec3 (*rt)(glm::vec3, uint), uint bits, int samples, std::uint64_t seed,
                          double minZ = -2.0) {
    Rng rng(seed);
    AngleStats s;
    int used = 0;
    for (int i = 0; i < samples; ++i) {
        glm::dvec3 n = randomUnit(rng);
        if (n.z < minZ) continue;
        glm::vec3 d = rt(glm::vec3(n), bits);
        EXPECT_NEAR(glm::length(glm::dvec3(d)), 1.0, 1e-6);
        double a = angleDeg(n, glm::dvec3(d));
        s.mean += a;
        s.max = std::max(s.max, a);
        ++used;
    }
    s.mean /= used;
    return s;
}

// Documented bounds (degrees), measured over 1M (here 400k) uniform directions with margin.
TEST(Normals, RandomDirectionsWithinDocumentedBounds) {
    struct Bound {
        const char* name;
        glm::vec3 (*rt)(glm::vec3, uint);
        uint bits;
        double maxDeg, meanDeg, minZ;
    };
    const Bound bounds[] = {
        {"normal_xyz", rtXyz, 8, 0.40, 0.18, -2.0},
        {"normal_xyz", rtXyz, 10, 0.10, 0.045, -2.0},
        {"normal_xyz", rtXyz, 16, 0.0016, 0.0007, -2.0},
        {"normal_bestfit", rtBestFit, 8, 0.32, 0.034, -2.0},
        {"normal_bestfit (search)", rtBestFitSearch, 8, 0.32, 0.029, -2.0},
        {"normal_xy_zsign", rtXyZSign, 8, 6.0, 0.48, -2.0},
        {"normal_xy_zsign", rtXyZSign, 16, 0.36, 0.0031, -2.0},
        {"normal_spheremap", rtSpheremap, 8, 12.0, 0.50, -2.0},
        {"normal_spheremap", rtSpheremap, 16, 0.55, 0.0020, -2.0},
        {"normal_stereographic (z >= 0)", rtStereo, 8, 1.2, 0.48, 0.0},
        {"normal_stereographic (z >= 0)", rtStereo, 16, 0.0046, 0.0019, 0.0},
        {"normal_octahedral", rtOct, 8, 0.95, 0.34, -2.0},
        {"normal_octahedral", rtOct, 10, 0.24, 0.085, -2.0},
        {"normal_octahedral", rtOct, 16, 0.0037, 0.0014, -2.0},
        {"normal_octahedral_precise", rtOctP, 8, 0.64, 0.32, -2.0},
        {"normal_octahedral_precise", rtOctP, 16, 0.0025, 0.00125, -2.0},
    };
    for (const Bound& b : bounds) {
        AngleStats s = measureNormals(b.rt, b.bits, 400000, 21, b.minZ);
        std::printf("[measured] %-30s %2u bits: mean %.5f deg, max %.5f deg\n", b.name, b.bits, s.mean, s.max);
        EXPECT_LE(s.max, b.maxDeg) << b.name << " " << b.bits;
        EXPECT_LE(s.mean, b.meanDeg) << b.name << " " << b.bits;
    }
}

TEST(Normals, KnownCodes) {
    EXPECT_EQ(encodeNormalOctahedral(glm::vec3(0, 0, 1), 8), uvec2(0, 0));
    EXPECT_EQ(encodeNormalOctahedral(glm::vec3(0, 0, -1), 8), uvec2(127, 127));
    EXPECT_EQ(encodeNormalOctahedral(glm::vec3(1, 0, 0), 8), uvec2(127, 0));
    EXPECT_EQ(encodeNormalOctahedral(glm::vec3(-1, 0, 0), 8), uvec2(0x81, 0));
    EXPECT_EQ(encodeNormalBestFit(glm::vec3(0, 0, 1)), uvec3(128, 128, 255));
    EXPECT_EQ(encodeNormalXyz(glm::vec3(0, 0, -1), 8), uvec3(128, 128, 0));
    EXPECT_EQ(encodeNormalXyZSign(glm::vec3(0.6f, 0, -0.8f), 8).z, 1u);
    EXPECT_EQ(encodeNormalXyZSign(glm::vec3(0.6f, 0, 0.8f), 8).z, 0u);
    EXPECT_EQ(encodeNormalSpheremap(glm::vec3(0, 0, 1), 8), uvec2(128, 128));
    EXPECT_EQ(encodeNormalSpheremap(glm::vec3(0, 0, -1), 8), uvec2(255, 128));
    EXPECT_GT(angleDeg(glm::dvec3(0, 0, -1), glm::dvec3(rtSpheremap(glm::vec3(0, 0, -1), 8))), -1.0);
    EXPECT_LT(angleDeg(glm::dvec3(0, 0, -1), glm::dvec3(rtSpheremap(glm::vec3(0, 0, -1), 8))), 1e-3);
    // 2^b - 1 levels have no exact centre: +z decodes 1.13 deg off at 8 bits (its worst case).
    EXPECT_LT(angleDeg(glm::dvec3(0, 0, 1), glm::dvec3(rtStereo(glm::vec3(0, 0, 1), 8))), 1.2);
}

// decode(code) re-encodes to the same code, for every code of the 16-bit (2 x 8) encodings,
// apart from the listed degenerate codes.
TEST(Normals, EveryTwoByEightBitCodeReencodes) {
    int octChanged = 0, octPChanged = 0, sphChanged = 0, sphInside = 0, stereoChanged = 0, zsChanged = 0, zsValid = 0;
    for (uint x = 0; x < 256; ++x)
        for (uint y = 0; y < 256; ++y) {
            uvec2 c(x, y);
            // Octahedral: x or y = 0x80 (-128) are never produced. The square's edges are mirror
            // images ((1, t) and (1, -t) are one direction), so edge codes may re-encode as their
            // twin: allowed there only, and only to the same direction.
            bool octValid = x != 0x80 && y != 0x80;
            bool onEdge = x == 0x7f || x == 0x81 || y == 0x7f || y == 0x81;
            glm::vec3 d = decodeNormalOctahedral(c, 8);
            for (uvec2 again : {encodeNormalOctahedral(d, 8), encodeNormalOctahedralPrecise(d, 8)}) {
                if (!octValid || again == c) continue;
                ASSERT_TRUE(onEdge) << x << " " << y;
                ASSERT_LT(angleDeg(glm::dvec3(d), glm::dvec3(decodeNormalOctahedral(again, 8))), 1e-3) << x << " " << y;
            }
            if (octValid && encodeNormalOctahedral(d, 8) != c) ++octChanged;
            if (octValid && encodeNormalOctahedralPrecise(d, 8) != c) ++octPChanged;
            // Spheremap: codes inside the disc.
            glm::vec2 e = glm::vec2(dequantizeUnorm(x, 8), dequantizeUnorm(y, 8)) * 4.0f - 2.0f;
            if (glm::dot(e, e) < 3.99f) {
                ++sphInside;
                if (encodeNormalSpheremap(decodeNormalSpheremap(c, 8), 8) != c) ++sphChanged;
            }
            if (encodeNormalStereographic(decodeNormalStereographic(c, 8), 8) != c) ++stereoChanged;
            for (uint s = 0; s < 2; ++s) {
                uvec3 cz(x, y, s);
                float fx = dequantizeUnorm(x, 8) * 2.0f - 1.0f, fy = dequantizeUnorm(y, 8) * 2.0f - 1.0f;
                if (fx * fx + fy * fy >= 0.98f) continue;  // off the disc or at the equator: z ~ 0
                ++zsValid;
                if (encodeNormalXyZSign(decodeNormalXyZSign(cz, 8), 8) != cz) ++zsChanged;
            }
        }
    std::printf("[measured] re-encode changes: oct %d, octP %d, spheremap %d/%d, stereo %d/65536, xy_zsign %d/%d\n",
                octChanged, octPChanged, sphChanged, sphInside, stereoChanged, zsChanged, zsValid);
    EXPECT_LE(octChanged, 4 * 127);  // at most one of each mirrored pair on the 4 edges
    EXPECT_LE(octPChanged, 4 * 127);
    EXPECT_EQ(sphChanged, 0);
    EXPECT_EQ(stereoChanged, 0);
    EXPECT_EQ(zsChanged, 0);
}

TEST(Normals, BestFitReencodesToSameDirection) {
    Rng rng(5);
    for (int i = 0; i < 30000; ++i) {
        uvec3 c(rng.bits32() & 255u, rng.bits32() & 255u, rng.bits32() & 255u);
        glm::vec3 d = decodeNormalBestFit(c);
        glm::vec3 again = decodeNormalBestFit(encodeNormalBestFitSearch(d));
        ASSERT_LT(angleDeg(glm::dvec3(d), glm::dvec3(again)), 1e-3) << c.x << " " << c.y << " " << c.z;
    }
}

TEST(Normals, BestFitBeatsPlainXyzByALargeFactor) {
    AngleStats bf = measureNormals(rtBestFit, 8, 300000, 3);
    AngleStats xyz = measureNormals(rtXyz, 8, 300000, 3);
    std::printf("[measured] bestfit mean %.5f max %.5f; xyz8 mean %.5f max %.5f; ratio of means %.2f\n", bf.mean,
                bf.max, xyz.mean, xyz.max, xyz.mean / bf.mean);
    EXPECT_LT(bf.mean * 5.0, xyz.mean);
}

// The table (CryEngine's look-up, best_fit_normals.h) against the search it is generated from:
// the error it adds, stated in shaders/encodings.glsl and layouts/README.md.
TEST(Normals, BestFitTableErrorAgainstSearch) {
    Rng rng(7);
    const int n = 200000;
    std::vector<double> table(n), search(n);
    int same = 0;
    for (int i = 0; i < n; ++i) {
        glm::dvec3 v = randomUnit(rng);
        const uvec3 t = encodeNormalBestFit(glm::vec3(v)), s = encodeNormalBestFitSearch(glm::vec3(v));
        same += t == s;
        table[i] = angleDeg(v, glm::dvec3(decodeNormalBestFit(t)));
        search[i] = angleDeg(v, glm::dvec3(decodeNormalBestFit(s)));
        // The search is optimal (next test): the table can only lose.
        ASSERT_GE(table[i], search[i] - 1e-4) << v.x << " " << v.y << " " << v.z;
    }
    auto stats = [](std::vector<double> e) {
        std::sort(e.begin(), e.end());
        double sum = 0.0;
        for (double x : e) sum += x;
        return glm::dvec3(sum / double(e.size()), e[e.size() * 99 / 100], e.back());
    };
    const glm::dvec3 t = stats(table), s = stats(search);
    std::printf("[measured] bestfit table  mean %.4f p99 %.4f max %.4f deg\n", t.x, t.y, t.z);
    std::printf("[measured] bestfit search mean %.4f p99 %.4f max %.4f deg; same code %.1f %%\n", s.x, s.y, s.z,
                100.0 * same / n);
    EXPECT_LE(t.x, s.x * 1.25);  // 1024^2 texels: 0.032 vs 0.028
    EXPECT_LE(t.y, s.y * 1.10);
    EXPECT_LE(t.z, s.z + 0.01);
    EXPECT_GT(same, n / 2);  // 61 % measured
}

// Each texel holds the search's choice for its centre direction, whatever the thread count.
TEST(Normals, BestFitTableHoldsTheSearchAtTexelCentres) {
    const std::vector<uint32_t>& table = bestFitNormalTable();
    ASSERT_EQ(table.size(), (kBestFitTableEntries + 3) / 4);
    EXPECT_EQ(generateBestFitNormalTable(1), table);
    EXPECT_EQ(generateBestFitNormalTable(3), table);  // pairs of rows split unevenly: the same words
    Rng rng(8);
    for (int s = 0; s < 20000; ++s) {
        const uint32_t i = rng.bits32() % kBestFitTableSize, j = rng.bits32() % (i + 1);
        const glm::vec3 centre = glm::normalize(glm::vec3((float(i) + 0.5f) / float(kBestFitTableSize),
                                                          (float(j) + 0.5f) / float(kBestFitTableSize), 1.0f));
        ASSERT_EQ(encodeNormalBestFit(centre), encodeNormalBestFitSearch(centre)) << "texel " << i << " " << j;
        // Any sign and order of the components: the table covers the sphere by symmetry. The code
        // may differ where two lengths give the same direction (d = (247, 57, -57) and (169, 39, -39) are 19 x and 13 x (13, 3, -3)),
        // which float's rounding of the error breaks either way; the direction may not.
        const glm::vec3 v = rng.bits32() & 1u ? glm::vec3(-centre.y, centre.z, centre.x)
                                              : glm::vec3(centre.z, centre.x, -centre.y);
        const double t = angleDeg(glm::dvec3(v), glm::dvec3(decodeNormalBestFit(encodeNormalBestFit(v))));
        const double r = angleDeg(glm::dvec3(v), glm::dvec3(decodeNormalBestFit(encodeNormalBestFitSearch(v))));
        ASSERT_NEAR(t, r, 1e-4) << "texel " << i << " " << j;
    }
}

// GLSL and C++ read the table at the same place and size.
TEST(Normals, BestFitTableConstantsMatchTheShader) {
    std::ifstream file(std::string(GBL_SOURCE_SHADER_DIR) + "/normal_encodings.glsl");
    ASSERT_TRUE(file);
    std::stringstream text;
    text << file.rdbuf();
    EXPECT_NE(text.str().find("#define GBL_BEST_FIT_TABLE_SIZE " + std::to_string(kBestFitTableSize) + "u\n"),
              std::string::npos);
    EXPECT_NE(text.str().find("#define GBL_BEST_FIT_TABLE_BINDING " + std::to_string(kBestFitTableBinding) + "\n"),
              std::string::npos);
}

// The in-code search is as good as a wider one: every odd max-component k, and +-2 odd steps on
// every component around the ray, scored in double.
TEST(Normals, BestFitSearchIsOptimalInItsNeighbourhood) {
    Rng rng(6);
    for (int i = 0; i < 1500; ++i) {
        glm::dvec3 n = randomUnit(rng);
        uvec3 c = encodeNormalBestFitSearch(glm::vec3(n));
        double ours = angleDeg(n, glm::dvec3(glm::ivec3(c) * 2 - 255));
        double m = std::max(std::fabs(n.x), std::max(std::fabs(n.y), std::fabs(n.z)));
        double best = 1e9;
        for (int k = 1; k <= 255; k += 2) {
            glm::dvec3 t = n / m * double(k);
            glm::ivec3 base(2 * int(std::floor(t.x * 0.5)) + 1, 2 * int(std::floor(t.y * 0.5)) + 1,
                            2 * int(std::floor(t.z * 0.5)) + 1);
            for (int dx = -2; dx <= 2; dx += 2)
                for (int dy = -2; dy <= 2; dy += 2)
                    for (int dz = -2; dz <= 2; dz += 2) {
                        glm::ivec3 d = base + glm::ivec3(dx, dy, dz);
                        if (std::abs(d.x) > 255 || std::abs(d.y) > 255 || std::abs(d.z) > 255) continue;
                        best = std::min(best, angleDeg(n, glm::dvec3(d)));
                    }
        }
        ASSERT_LE(ours, best + 1e-4) << "direction " << n.x << " " << n.y << " " << n.z;
    }
}

TEST(Normals, OctahedralPreciseNeverWorseAndMoreBitsNeverWorse) {
    double prevMax = 1e9, prevMaxP = 1e9;
    for (uint bits = 8; bits <= 16; ++bits) {
        Rng rng(40);
        double maxPlain = 0.0, maxPrecise = 0.0, sumPlain = 0.0, sumPrecise = 0.0;
        const int n = 100000;
        for (int i = 0; i < n; ++i) {
            glm::dvec3 v = randomUnit(rng);
            double a = angleDeg(v, glm::dvec3(rtOct(glm::vec3(v), bits)));
            double p = angleDeg(v, glm::dvec3(rtOctP(glm::vec3(v), bits)));
            // Both are chosen in float from the float-rounded direction (up to 3.4e-6 deg off the
            // double one), so allow that much, plus float's resolution of the distance.
            ASSERT_LE(p, a * (1.0 + 1e-3) + 1e-5) << "bits " << bits << " sample " << i;
            maxPlain = std::max(maxPlain, a);
            maxPrecise = std::max(maxPrecise, p);
            sumPlain += a;
            sumPrecise += p;
        }
        std::printf("[measured] octahedral %2u bits: plain mean %.5f max %.5f, precise mean %.5f max %.5f deg\n", bits,
                    sumPlain / n, maxPlain, sumPrecise / n, maxPrecise);
        EXPECT_LT(sumPrecise, sumPlain);
        EXPECT_LT(maxPrecise, maxPlain);
        EXPECT_LT(maxPlain, prevMax) << bits;
        EXPECT_LT(maxPrecise, prevMaxP) << bits;
        prevMax = maxPlain;
        prevMaxP = maxPrecise;
    }
}

TEST(Normals, MoreBitsNeverWorseForEveryParameterisedEncoding) {
    for (auto rt : {rtXyz, rtXyZSign, rtSpheremap, rtStereo}) {
        double prev = 1e9;
        for (uint bits = 6; bits <= 16; bits += 2) {
            AngleStats s = measureNormals(rt, bits, 50000, 41, rt == rtStereo ? 0.0 : -2.0);
            EXPECT_LE(s.max, prev) << bits;
            prev = s.max;
        }
    }
}

}  // namespace
