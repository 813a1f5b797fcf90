// Outputs never replace inputs (base/file_io.h): a registered input survives every atomic write
// aimed at it, by its name or through a link, and the checks made before the work name it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "error.h"
#include "file_io.h"
#include "temp_dir.h"

namespace gbl {
namespace {

namespace fs = std::filesystem;

const test::ScratchDir scratch("gbl_output_input_test_");

TEST(OutputOverInput, AWriteOverARegisteredInputIsRefusedAndLeavesItWhole) {
    const fs::path input = scratch() / "scene.gltf";
    { std::ofstream(input) << "the user's scene"; }
    registerInput(input);
    EXPECT_TRUE(isRegisteredInput(input));
    fs::create_symlink(input, scratch() / "link.gltf");
    fs::create_hard_link(input, scratch() / "hard.gltf");
    for (const char* name : {"scene.gltf", "link.gltf", "hard.gltf"}) {
        SCOPED_TRACE(name);
        try {
            writeFileAtomic(scratch() / name, std::string("an output"));
            FAIL() << "expected a UserError";
        } catch (const UserError& e) {
            EXPECT_NE(std::string(e.what()).find("is an input"), std::string::npos) << e.what();
        }
    }
    EXPECT_EQ(test::readFile(input), "the user's scene");
    // No temporary left behind, and other files are written as before.
    size_t files = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(scratch())) ++files;
    EXPECT_EQ(files, 3u);
    writeFileAtomic(scratch() / "report.json", std::string("{}"));
    EXPECT_EQ(test::readFile(scratch() / "report.json"), "{}");
    EXPECT_FALSE(isRegisteredInput(scratch() / "report.json"));
}

TEST(OutputOverInput, ChecksBeforeTheWorkNameTheInput) {
    const fs::path dir = scratch() / "out";
    fs::create_directories(dir / "sub");
    { std::ofstream(dir / "sub" / "sky.hdr") << "sky"; }
    { std::ofstream(scratch() / "elsewhere.hdr") << "sky"; }
    try {
        refuseInputsInsideDirectory(dir, {"", (scratch() / "elsewhere.hdr").string(), (dir / "sub" / "sky.hdr").string()},
                                    "--out");
        FAIL() << "expected a UserError";
    } catch (const UserError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("--out"), std::string::npos) << m;
        EXPECT_NE(m.find("sky.hdr"), std::string::npos) << m;
    }
    EXPECT_NO_THROW(refuseInputsInsideDirectory(dir, {(scratch() / "elsewhere.hdr").string()}, "--out"));
    // A sibling whose name starts like the folder's is not inside it.
    fs::create_directories(scratch() / "out2");
    { std::ofstream(scratch() / "out2" / "a.hdr") << "a"; }
    EXPECT_NO_THROW(refuseInputsInsideDirectory(dir, {(scratch() / "out2" / "a.hdr").string()}, "--out"));
    EXPECT_THROW(refuseOutputOverInput(scratch() / "elsewhere.hdr", {(scratch() / "elsewhere.hdr").string()}, "--out"),
                 UserError);
    EXPECT_NO_THROW(refuseOutputOverInput(scratch() / "new.png", {(scratch() / "elsewhere.hdr").string()}, "--out"));
}

}  // namespace
}  // namespace gbl
