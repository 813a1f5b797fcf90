// Messages that said something other than what was wrong, each now naming the real problem;
// all are refusals before any device work, run as the real executable.
#include <gtest/gtest.h>

#include <regex>

#include <filesystem>
#include <fstream>

#include "cli_runner.h"
#include "test_paths.h"

namespace fs = std::filesystem;

namespace {

using namespace gbl::test;

const CliScratch scratch("gbl_messages_test_");

RunResult run(const std::string& args) { return scratch.run(args); }

void expectAbsent(const RunResult& r, const std::string& text) {
    EXPECT_EQ(r.err.find(text), std::string::npos) << "'" << text << "' in: " << r.err;
}

}  // namespace

// search --budget 4 ran a whole search and ended "0 layouts on the front"; only its report said why.
TEST(Messages, SearchRefusesABudgetNoLayoutFits) {
    const RunResult r = run("search --budget 4 --out s4");
    expectOneLineError(r, {"--budget 4", "no layout fits", "smallest", "or more"});
    EXPECT_FALSE(fs::exists(scratch() / "s4"));
}

// search has no --force; its refusal of a used folder named one.
TEST(Messages, SearchNamesWhatItHasForAUsedFolder) {
    fs::create_directories(scratch() / "used");
    { std::ofstream(scratch() / "used" / "notes.txt") << "x"; }
    const RunResult r = run("search --budget 12 --out used");
    expectOneLineError(r, {"used", "search-journal.tsv", "resume"});
    expectAbsent(r, "--force");
}

// 1e-300 is positive; a float cannot hold it.
TEST(Messages, AFloatFlagSaysTooSmallOrTooLarge) {
    const RunResult small = run("compare --scene builtin --gt-noise 1e-300 --out gt");
    expectOneLineError(small, {"--gt-noise", "1e-300", "too small"});
    expectAbsent(small, "positive");
    expectOneLineError(run("compare --scene builtin --gt-noise 1e39 --out gt"), {"--gt-noise", "too large"});
    expectOneLineError(run("compare --scene builtin --gt-noise -1 --out gt"), {"--gt-noise", "positive"});
}

// 99992 is a multiple of 8; what is wrong is its size.
TEST(Messages, BandRowsSaysTheLimitItBreaks) {
    const RunResult r = run("compare --scene builtin --band-rows 99992 --out br");
    expectOneLineError(r, {"--band-rows", "99992", "at most 65536"});
    expectAbsent(r, "multiple of 8");
    expectOneLineError(run("compare --scene builtin --band-rows 99999999999 --out br"), {"at most 65536"});
    expectOneLineError(run("compare --scene builtin --band-rows 12 --out br"), {"multiple of 8"});
}

// A symbolic link that loops is not a missing file.
TEST(Messages, ALayoutSymlinkLoopIsNamedAsOne) {
    fs::create_symlink("loop_b.toml", scratch() / "loop_a.toml");
    fs::create_symlink("loop_a.toml", scratch() / "loop_b.toml");
    const RunResult r = run("layouts show loop_a.toml");
    expectOneLineError(r, {"loop_a.toml", "loops"});
    expectAbsent(r, "no such");
    expectOneLineError(run("compare --scene builtin --layouts loop_a.toml --out lp"), {"loop_a.toml", "loops"});
}

// layouts glsl PATH said "generated from layouts/ue4.toml" for a file elsewhere.
TEST(Messages, LayoutsGlslNamesTheFileItRead) {
    fs::create_directories(scratch() / "elsewhere-\xc3\xbc");
    fs::copy_file(fs::path(GBL_SOURCE_LAYOUT_DIR) / "ue4.toml", scratch() / "elsewhere-\xc3\xbc" / "ue4.toml",
                  fs::copy_options::overwrite_existing);
    const RunResult r = run("layouts glsl elsewhere-\xc3\xbc/ue4.toml");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.out.rfind("// file: elsewhere-\xc3\xbc/ue4.toml\n", 0), 0u) << r.out.substr(0, 200);
    EXPECT_EQ(r.out.find("layouts/"), std::string::npos);
    EXPECT_NE(r.out.find("generated from the layout 'ue4'"), std::string::npos);
}

// Paths in UTF-8 printed as \xc3\xbc escapes; they print as themselves.
TEST(Messages, UnicodePathsPrintAsUtf8) {
    fs::create_directories(scratch() / "\xc3\xbc");
    fs::copy_file(fs::path(GBL_SOURCE_LAYOUT_DIR) / "ue4.toml", scratch() / "\xc3\xbc" / "\xc3\xbc" "ber.toml",
                  fs::copy_options::overwrite_existing);
    const RunResult r = run("layouts show \xc3\xbc/\xc3\xbc" "ber.toml");
    EXPECT_EQ(r.exitCode, 1);
    // The place is ue4.toml's `name` line, wherever the file has it.
    const std::regex said("\xc3\xbc/\xc3\xbc" "ber\\.toml:[0-9]+:8: layout name 'ue4' differs from the file name '\xc3\xbc" "ber'");
    EXPECT_TRUE(std::regex_search(r.err, said)) << r.err;
    EXPECT_EQ(r.err.find("\\x"), std::string::npos) << r.err;
}

// --force lets render and compare replace files in --out, never an input kept there.
TEST(Messages, ForceIntoAFolderHoldingAnInputIsRefused) {
    fs::create_directories(scratch() / "kept");
    { std::ofstream(scratch() / "kept" / "sky.hdr") << "the user's sky"; }
    for (const std::string command : {"render --size 32x32", "compare --scene builtin --size 32x32 --layouts ue4", "ibl"}) {
        const RunResult r = run(command + " --env kept/sky.hdr --out kept --force");
        expectOneLineError(r, {"--out kept", "holds the input kept/sky.hdr"});
    }
    EXPECT_EQ(slurp(scratch() / "kept" / "sky.hdr"), "the user's sky");
}

// `layouts export --tables`: an unknown form is one line naming both forms; `arrays` writes the
// tables as const arrays (the default as select trees).
TEST(Messages, ExportTablesNamesItsForms) {
    const RunResult bad = run("layouts export ue4 --lang glsl --tables trees");
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_EQ(lineCount(bad.err), 1u) << bad.err;
    EXPECT_NE(bad.err.find("--tables 'trees'"), std::string::npos) << bad.err;
    EXPECT_NE(bad.err.find("selects"), std::string::npos) << bad.err;
    EXPECT_TRUE(bad.out.empty());
    const RunResult arrays = run("layouts export ue4 --lang hlsl --tables arrays");
    ASSERT_EQ(arrays.exitCode, 0) << arrays.err;
    EXPECT_NE(arrays.out.find("static const float gbl_kSrgbDecode[256] = {"), std::string::npos);
    const RunResult selects = run("layouts export ue4 --lang hlsl");
    ASSERT_EQ(selects.exitCode, 0) << selects.err;
    EXPECT_EQ(selects.out.find("gbl_kSrgbDecode[256]"), std::string::npos);
    EXPECT_NE(selects.out.find("float gbl_kSrgbDecode(uint i)"), std::string::npos);
}

// --min-bits normal=8,normal=10 kept the last; a key given twice is refused, as a flag given twice is.
TEST(Messages, MinBitsRefusesAnAttributeGivenTwice) {
    const RunResult r = run("search --budget 12 --min-bits normal=8,normal=10 --size 32x18 --views 1 --candidates 8 --no-confirm --out mb");
    expectOneLineError(r, {"--min-bits", "normal is given twice (8 and 10)", "once"});
    EXPECT_FALSE(fs::exists(scratch() / "mb"));
    expectOneLineError(run("search --budget 12 --min-bits normal=+8 --out mb"), {"--min-bits", "whole number"});
}

// A suite entry whose gltf is a suite failed later as "not valid JSON"; it says what it is.
TEST(Messages, ASuiteGivenAsAGltfSaysSo) {
    { std::ofstream(scratch() / "inner.toml") << "[[scene]]\ngltf = \"builtin\"\n"; }
    { std::ofstream(scratch() / "outer.toml") << "[[scene]]\ngltf = \"inner.toml\"\n"; }
    const RunResult r = run("compare --scene outer.toml --size 32x32 --layouts ue4 --out nested");
    expectOneLineError(r, {"outer.toml:2:8:", "'inner.toml' is a scene suite"});
    EXPECT_FALSE(fs::exists(scratch() / "nested"));
}

// A scene with materials drawn forward (ToyCar's glass: KHR_materials_transmission) is masked on
// the CPU evaluation, on whole frames: asking for the device evaluator or for bands is refused, in
// one line, before any device work, with what to give instead.
TEST(Messages, ForwardDrawnMaterialsNeedTheCpuEvaluation) {
    const fs::path toyCar = sharedAssets() / "models" / "ToyCar" / "ToyCar.gltf";
    GBL_REQUIRE_FILE(toyCar);
    expectOneLineError(run("compare --scene " + toyCar.string() + " --eval gpu --out fw"),
                       {"ToyCar.gltf", "drawn forward", "KHR_materials_transmission", "--eval cpu or auto"});
    expectOneLineError(run("compare --scene " + toyCar.string() + " --band-rows 64 --out fw"),
                       {"ToyCar.gltf", "drawn forward", "--band-rows 0 or auto"});
}
