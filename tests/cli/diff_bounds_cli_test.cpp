// `gbufferlab diff` under hostile input, run as the real executable and measured (its own peak
// resident memory and wall time): pairs too large for the memory budget, a --ppd that would
// widen FLIP's filters without end, exposure spans beyond any use, EXR headers that claim more
// than their files hold, non-finite pixels, and an error map aimed at an input. Every file is
// made here (tests/support/hostile_images.h); none is committed.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <nlohmann/json.hpp>

#include "hostile_images.h"
#include "image_diff.h"
#include "image_io.h"
#include "measured_run.h"
#include "pfm_io.h"

namespace fs = std::filesystem;

namespace {

using namespace gbl::test;

const std::vector<std::pair<std::string, std::string>> kBudget8G = {{"GBL_MEMORY_BUDGET", "8G"}};

const CliScratch scratch("gbl_diff_bounds_test_");

std::string at(const std::string& name) { return (scratch() / name).string(); }

MeasuredRun diff(const std::vector<std::string>& args,
                 const std::vector<std::pair<std::string, std::string>>& env = kBudget8G) {
    std::vector<std::string> all = {"diff"};
    all.insert(all.end(), args.begin(), args.end());
    return runMeasured(scratch(), all, env);
}

// An RGB float EXR of `rows` rows written with OpenEXR itself, `compression` as asked, random
// values (so that compression cannot shrink it below what the test needs).
void writeExrRows(const std::string& path, int width, int rows, Imf::Compression compression) {
    std::vector<float> pixels(size_t(width) * size_t(rows) * 3);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 4.0f);
    for (float& v : pixels) v = u(rng);
    Imf::Header header(width, rows);
    header.compression() = compression;
    Imf::FrameBuffer frame;
    for (int c = 0; c < 3; ++c) {
        const char* name = c == 0 ? "R" : c == 1 ? "G" : "B";
        header.channels().insert(name, Imf::Channel(Imf::FLOAT));
        frame.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(pixels.data() + c), 12, 12 * size_t(width)));
    }
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(rows);
}

}  // namespace

// The generator makes valid PNGs: a small one decodes to black pixels of its size.
TEST(DiffBounds, GeneratedBlackPngsAreValid) {
    writeFile(at("black.png"), blackPng(300, 200));
    const gbl::Image8 img = gbl::readImage8(at("black.png"));
    EXPECT_EQ(img.width, 300);
    EXPECT_EQ(img.height, 200);
    EXPECT_EQ(img.channels, 3);
    EXPECT_EQ(std::count(img.pixels.begin(), img.pixels.end(), 0), 300 * 200 * 3);
}

// Two valid 16384x16384 PNGs (about 1 MB each): refused from their headers, naming both files
// and the fix, before a pixel is decoded (before: 24 GB and killed, exit 137).
TEST(DiffBounds, APairBeyondTheBudgetIsRefusedFromItsHeaders) {
    writeFile(at("huge_a.png"), blackPng(16384, 16384));
    writeFile(at("huge_b.png"), blackPng(16384, 16384));
    const MeasuredRun m = diff({"huge_a.png", "huge_b.png"});
    expectBoundedRefusal(m, {"huge_a.png", "huge_b.png", "16384x16384", "GBL_MEMORY_BUDGET=8G", "crops"});
    std::printf("16384x16384 PNG pair refused: %.1f MiB, %.3f s\n", m.peakMiB, m.seconds);
}

// Where a pair fits, the estimate the refusal uses is an upper bound of what diff really takes.
TEST(DiffBounds, TheEstimateBoundsTheMeasuredPeak) {
    writeFile(at("mid_a.png"), blackPng(2048, 2048));
    gbl::Image8 b = gbl::readImage8(at("mid_a.png"));
    for (size_t i = 0; i < b.pixels.size(); i += 5) b.pixels[i] = 200;
    gbl::writePng(at("mid_b.png"), b);
    const MeasuredRun m = diff({"mid_a.png", "mid_b.png", "--json"});
    ASSERT_EQ(m.result.exitCode, 0) << m.result.err;
    const double estimate =
        gbl::diffMemoryBytes(gbl::probeImageFile(at("mid_a.png")), gbl::probeImageFile(at("mid_b.png")));
    std::printf("2048x2048 LDR pair: peak %.1f MiB, estimate %.1f MiB\n", m.peakMiB, estimate / 1048576.0);
    if (!kSanitized) {
        EXPECT_LT(m.peakMiB * 1048576.0, estimate);
    }
}

// --ppd sets FLIP's filter radius (0.135 px per pixel per degree): --ppd 1e9 asked for 12 GB of
// kernels on a 64x64 pair. Now at most 1000, said in one line.
TEST(DiffBounds, PixelsPerDegreeIsBounded) {
    writeFile(at("small.png"), blackPng(64, 64));
    expectBoundedRefusal(diff({"small.png", "small.png", "--ppd", "1e9"}), {"--ppd", "1e9", "1000"});
    expectBoundedRefusal(diff({"small.png", "small.png", "--ppd", "0"}), {"--ppd", "1000"});
    expectBoundedRefusal(diff({"small.png", "small.png", "--ppd", "nan"}), {"--ppd", "1000"});
    const MeasuredRun ok = diff({"small.png", "small.png", "--ppd", "1000", "--json"});
    EXPECT_EQ(ok.result.exitCode, 0) << ok.result.err;
}

// HDR-FLIP runs one LDR-FLIP per exposure: a span of 2e30 stops is refused, not counted into an
// int; a value beyond a float is refused, not turned into infinity.
TEST(DiffBounds, ExposureSpansAreBounded) {
    gbl::writeExr(at("e.exr"), gbl::Image(16, 16, 3, 0.5f));
    expectBoundedRefusal(diff({"e.exr", "e.exr", "--start-exposure", "-1e30", "--stop-exposure", "1e30"}),
                         {"--start-exposure", "1000", "--num-exposures"});
    expectBoundedRefusal(diff({"e.exr", "e.exr", "--start-exposure", "-1e39", "--stop-exposure", "1"}),
                         {"--start-exposure", "float"});
    const MeasuredRun given = diff({"e.exr", "e.exr", "--start-exposure", "-1e30", "--stop-exposure", "1e30",
                                    "--num-exposures", "3", "--json"});
    EXPECT_EQ(given.result.exitCode, 0) << given.result.err;
}

// The issue's file: 480 KB, uncompressed, one scanline of 40000 pixels, a header claiming
// 40000x40000 (before: 18.7 GB allocated before the read failed).
TEST(DiffBounds, AnExrHeaderClaimingMoreThanItsFileIsRefused) {
    writeExrRows(at("lie.exr"), 40000, 1, Imf::NO_COMPRESSION);
    claimExrHeight(at("lie.exr"), 40000);
    const MeasuredRun m = diff({"lie.exr", "lie.exr"}, {});  // the machine's own budget: the lie is caught first
    expectBoundedRefusal(m, {"lie.exr", "40000x40000", "truncated"});
    std::printf("40000x40000 EXR claim refused: %.1f MiB, %.3f s\n", m.peakMiB, m.seconds);

    // Compressed, the file's size cannot show the lie; a claim within the budget is read band by
    // band, and fails at the first chunk that is not there, having touched only that band.
    writeExrRows(at("rle_lie.exr"), 4000, 120, Imf::RLE_COMPRESSION);
    claimExrHeight(at("rle_lie.exr"), 4000);
    expectBoundedRefusal(diff({"rle_lie.exr", "rle_lie.exr"}), {"rle_lie.exr"});
}

// Headers that claim a frame beyond the budget, in each format a reader decodes with stb_image.
TEST(DiffBounds, JpegAndRadianceHeadersAreCheckedBeforeDecoding) {
    writeFile(at("claim.jpg"), jpegHeaderClaiming(65000, 65000));
    expectBoundedRefusal(diff({"claim.jpg", "claim.jpg"}), {"claim.jpg", "65000x65000", "GBL_MEMORY_BUDGET"});
    writeFile(at("claim.hdr"), "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 60000 +X 60000\n" + std::string(64, '\x02'));
    expectBoundedRefusal(diff({"claim.hdr", "claim.hdr"}), {"claim.hdr"});
}

// The PFM a glTF Sample Viewer render writes (tools/gltf-viewer): a header claiming more than
// the file holds, and a frame beyond the budget, are refused from the header; an RGBA EXR
// reference against an RGB PFM compares.
TEST(DiffBounds, PfmHeadersAreCheckedBeforeReading) {
    writeFile(at("claim.pfm"), "PF\n60000 60000\n-1.0\n" + std::string(64, '\0'));
    const MeasuredRun lie = diff({"claim.pfm", "claim.pfm"}, {});
    expectBoundedRefusal(lie, {"claim.pfm", "truncated PFM", "60000x60000x3"});
    std::printf("60000x60000 PFM claim refused: %.1f MiB, %.3f s\n", lie.peakMiB, lie.seconds);
    gbl::writePfm(at("wide.pfm"), gbl::Image(2048, 1024, 3, 0.25f));
    expectBoundedRefusal(diff({"wide.pfm", "wide.pfm"}, {{"GBL_MEMORY_BUDGET", "64M"}}),
                         {"wide.pfm", "2048x1024", "GBL_MEMORY_BUDGET=64M"});
    gbl::writeExr(at("ref_rgba.exr"), gbl::Image(64, 32, 4, 0.5f));
    gbl::writePfm(at("viewer.pfm"), gbl::Image(64, 32, 3, 0.5f));
    const MeasuredRun same = diff({"ref_rgba.exr", "viewer.pfm", "--json"});
    ASSERT_EQ(same.result.exitCode, 0) << same.result.err;
    const auto j = nlohmann::json::parse(same.result.out);
    EXPECT_EQ(j["kind"], "hdr");
    EXPECT_EQ(j["max_abs"], 0.0);
}

// One NaN in the test image: refused, naming the file, the pixel, the channel and the count
// (before: dropped from max |difference|, NaN RMSE and PSNR, a number for FLIP).
TEST(DiffBounds, NonFinitePixelsAreRefusedNamingTheFirst) {
    gbl::Image a(8, 6, 3, 0.25f), b = a;
    b.at(3, 2, 1) = std::nanf("");
    b.at(5, 4, 0) = INFINITY;
    gbl::writeExr(at("fin.exr"), a);
    gbl::writeExr(at("nan.exr"), b);
    expectBoundedRefusal(diff({"fin.exr", "nan.exr", "--json"}),
                         {"nan.exr", "pixel (3, 2) channel G is NaN", "2 non-finite values"});
    expectBoundedRefusal(diff({"nan.exr", "fin.exr"}), {"nan.exr", "(3, 2)"});
    // Finite pairs: every number a JSON number, but PSNR of an identical pair, "inf" as
    // report.json writes it (docs/report-schema.md).
    const MeasuredRun same = diff({"fin.exr", "fin.exr", "--json"});
    ASSERT_EQ(same.result.exitCode, 0) << same.result.err;
    const auto j = nlohmann::json::parse(same.result.out);
    EXPECT_EQ(j["psnr_db"], "inf");
    for (const char* key : {"rmse", "max_abs", "flip_mean", "flip_max", "psnr_peak"})
        EXPECT_TRUE(j[key].is_number()) << key;
}

// The error map never replaces an input, with or without --force, by name or through a link
// (before: `--out in_b.png --force` replaced the input; without --force it said "file exists").
TEST(DiffBounds, TheErrorMapNeverReplacesAnInput) {
    gbl::writePng(at("in_a.png"), gbl::Image8{8, 8, 3, std::vector<unsigned char>(192, 10)});
    gbl::writePng(at("in_b.png"), gbl::Image8{8, 8, 3, std::vector<unsigned char>(192, 40)});
    const std::string before = slurp(at("in_b.png"));
    for (const bool force : {false, true}) {
        std::vector<std::string> args = {"in_a.png", "in_b.png", "--out", "in_b.png"};
        if (force) args.push_back("--force");
        expectBoundedRefusal(diff(args), {"--out", "in_b.png", "is the input"});
    }
    fs::create_symlink("in_a.png", at("link.png"));
    expectBoundedRefusal(diff({"in_a.png", "in_b.png", "--out", "link.png", "--force"}), {"link.png", "is the input"});
    fs::create_hard_link(at("in_b.png"), at("hard.png"));
    expectBoundedRefusal(diff({"in_a.png", "in_b.png", "--out", "hard.png", "--force"}), {"hard.png", "is the input"});
    EXPECT_EQ(slurp(at("in_b.png")), before);
    // Another existing file is still replaced with --force, and refused without it.
    writeFile(at("old_map.png"), "user data");
    expectBoundedRefusal(diff({"in_a.png", "in_b.png", "--out", "old_map.png"}), {"old_map.png", "--force"});
    EXPECT_EQ(diff({"in_a.png", "in_b.png", "--out", "old_map.png", "--force"}).result.exitCode, 0);
}

// A path in UTF-8 is printed as it is, not as \xc3\xbc escapes.
TEST(DiffBounds, UnicodePathsPrintAsUtf8) {
    const MeasuredRun m = diff({"\xc3\xbc" "ber.png", "missing.png"});
    expectBoundedRefusal(m, {"\xc3\xbc" "ber.png"});
    EXPECT_EQ(m.result.err.find("\\x"), std::string::npos) << m.result.err;
}
