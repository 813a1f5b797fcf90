// compare's runs are named by layout and IBL mode (runs/<layout>/<mode>/, one row each): two runs
// of one name would overwrite each other's files and leave rows that cannot be told apart. A
// layout given twice, two files with one `name`, or a mode given twice are refused before
// anything is rendered (so no driver is needed), naming both files, with no output folder left.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli_runner.h"

namespace fs = std::filesystem;

namespace {

using namespace gbl::test;

const CliScratch scratch("gbl_run_names_test_");

RunResult compare(const std::string& args) { return scratch.run("compare --scene builtin --size 32x32 --out out " + args); }

}  // namespace

TEST(RunNames, ALayoutGivenTwiceIsRefused) {
    expectOneLineError(compare("--layouts ue4,ue4"), {"'ue4'", "given twice"});
    const std::string file = (fs::path(GBL_SOURCE_LAYOUT_DIR) / "ue4.toml").string();
    expectOneLineError(compare("--layouts ue4," + file), {"'ue4'", "given twice"});
    EXPECT_FALSE(fs::exists(scratch() / "out"));
}

TEST(RunNames, TwoFilesOfOneNameAreRefusedNamingBoth) {
    fs::create_directories(scratch() / "other");
    fs::copy_file(fs::path(GBL_SOURCE_LAYOUT_DIR) / "ue4.toml", scratch() / "other" / "ue4.toml",
                  fs::copy_options::overwrite_existing);
    const RunResult r = compare("--layouts ue4,other/ue4.toml");
    expectOneLineError(r, {"ue4.toml and other/ue4.toml", "both named 'ue4'", "runs/ue4/", "name"});
    // Renamed, the same file is a run of its own.
    std::ifstream in(scratch() / "other" / "ue4.toml");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text.replace(text.find("name = \"ue4\""), 12, "name = \"ue4b\"");
    std::ofstream(scratch() / "other" / "ue4b.toml") << text;
    const RunResult renamed = compare("--layouts ue4,other/ue4b.toml --scene missing.gltf");
    expectOneLineError(renamed, {"missing.gltf"});  // past the names, stopped by the next check
    EXPECT_FALSE(fs::exists(scratch() / "out"));
}

TEST(RunNames, AnIblModeGivenTwiceIsRefused) {
    expectOneLineError(compare("--layouts ue4 --ibl split-sum,split-sum"), {"--ibl", "'split-sum' is given twice"});
    expectOneLineError(compare("--layouts ue4 --ibl bo2,split-sum,bo2"), {"'bo2' is given twice"});
    EXPECT_FALSE(fs::exists(scratch() / "out"));
}
