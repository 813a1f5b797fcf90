// compare's scenes (scene_suite.h): --scene arguments and scene-suite files, every problem refused
// before anything is rendered with one line naming the file, line and column, as layout files are.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "error.h"
#include "scene_suite.h"
#include "test_paths.h"

namespace fs = std::filesystem;
using namespace gbl;
using namespace gbl::compare;

namespace {

fs::path folder() {
    static const fs::path d = [] {
        const fs::path p = fs::temp_directory_path() / ("gbl_scene_suite_test_" + std::to_string(::getpid()));
        fs::remove_all(p);
        fs::create_directories(p / "models");
        std::ofstream(p / "models" / "box.gltf") << "{}";
        std::ofstream(p / "sky.hdr") << "x";
        return p;
    }();
    return d;
}

std::string errorOf(const std::string& text) {
    try {
        parseSceneSuite(text, (folder() / "suite.toml").string());
    } catch (const UserError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(SceneSuite, ReadsScenesWithTheirEnvironmentsCamerasAndExposure) {
    const std::vector<SceneSpec> s = parseSceneSuite(R"(
[[scene]]
gltf = "builtin"

[[scene]]
name = "box-in-sky"
gltf = "models/box.gltf"
environment = "sky.hdr"
exposure = 0.5
[[scene.camera]]
position = [0, 1, 3]
target = [0, 0.5, 0]
fov_y_degrees = 30
[[scene.camera]]
position = [3, 1, 0]
target = [0, 0.5, 0]
)",
                                                     (folder() / "suite.toml").string());
    ASSERT_EQ(s.size(), 2u);
    EXPECT_EQ(s[0].name, "builtin");
    EXPECT_EQ(s[0].gltfPath, "");
    EXPECT_EQ(s[0].envPath, "");
    EXPECT_FALSE(s[0].exposure);
    EXPECT_EQ(s[1].name, "box-in-sky");
    EXPECT_EQ(s[1].gltfPath, (folder() / "models" / "box.gltf").string());
    EXPECT_EQ(s[1].envPath, (folder() / "sky.hdr").string());
    EXPECT_FLOAT_EQ(*s[1].exposure, 0.5f);
    ASSERT_EQ(s[1].cameras.size(), 2u);
    EXPECT_NEAR(s[1].cameras[0].yFovRadians, 30.0 * M_PI / 180.0, 1e-6);
    EXPECT_FLOAT_EQ(s[1].cameras[1].position.x, 3.0f);
}

TEST(SceneSuite, ProblemsAreOneLineWithTheirPlace) {
    const std::string file = (folder() / "suite.toml").string();
    struct Case {
        const char* text;
        const char* place;
        const char* words;
    };
    const Case cases[] = {
        {"[[scene]]\ngltf = \"models/missing.gltf\"\n", ":2:8:", "no such file"},
        {"[[scene]]\ngltf = \"builtin\"\nenvironment = \"nosky.hdr\"\n", ":3:15:", "no such file"},
        {"[[scene]]\ngltf = \"builtin\"\n[[scene]]\ngltf = \"builtin\"\n", ":3:1:", "given twice"},
        {"[[scene]]\nname = \"a\"\ngltf = \"builtin\"\n[[scene]]\nname = \"a\"\ngltf = \"models/box.gltf\"\n", ":4:1:",
         "another 'name'"},
        {"# nothing here\n", ":1:1:", "no scene"},
        {"", ":1:1:", "no scene"},
        {"[[scene]]\ngltf = \"builtin\"\ncolour = 3\n", ":3:1:", "unknown key 'colour'"},
        {"[[scene]]\ngltf = \"builtin\"\nexposure = -1\n", ":3:12:", "outside"},
        {"[[scene]]\ngltf = \"builtin\"\n[[scene.camera]]\nposition = [0, 0]\ntarget = [0, 0, 0]\n", ":4:12:",
         "3 numbers"},
        {"[[scene]]\ngltf = \"builtin\"\n[[scene.camera]]\nposition = [0, 1, 0]\ntarget = [0, 0, 0]\n", ":3:1:",
         "'up'"},
        {"[[scene]\n", ":1:", "TOML syntax error"},
        {"[[scene]]\nname = \"../x\"\ngltf = \"builtin\"\n", ":2:8:", "letters, digits"},
    };
    for (const Case& c : cases) {
        const std::string e = errorOf(c.text);
        EXPECT_EQ(e.find('\n'), std::string::npos) << c.text << "\n" << e;
        EXPECT_EQ(e.rfind(file, 0), 0u) << e;
        EXPECT_NE(e.find(c.place), std::string::npos) << c.text << "\n" << e;
        EXPECT_NE(e.find(c.words), std::string::npos) << c.text << "\n" << e;
    }
}

TEST(SceneSuite, SceneFlagsExpandAndRefuseRepeats) {
    const std::string box = (folder() / "models" / "box.gltf").string();
    const std::vector<SceneSpec> s = resolveScenes({"builtin", box}, "");
    ASSERT_EQ(s.size(), 2u);
    EXPECT_EQ(s[0].name, "builtin");
    EXPECT_EQ(s[1].name, "box");
    EXPECT_EQ(resolveScenes({}, "").size(), 1u) << "no --scene: the built-in scene";
    auto refused = [](const std::vector<std::string>& args, const std::string& env) {
        try {
            resolveScenes(args, env);
        } catch (const UserError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(refused({"builtin", "builtin"}, "").find("given twice"), std::string::npos);
    EXPECT_NE(refused({box, box}, "").find("given twice"), std::string::npos);
    EXPECT_NE(refused({"builtin", "missing.gltf"}, "").find("missing.gltf': no such file"), std::string::npos);
    EXPECT_NE(refused({"builtin", box}, "nosky.hdr").find("--env"), std::string::npos);
    // A suite given with --scene expands into its scenes, and a repeat across them is refused.
    const fs::path suite = folder() / "two.toml";
    std::ofstream(suite) << "[[scene]]\ngltf = \"models/box.gltf\"\n[[scene]]\ngltf = \"builtin\"\n";
    EXPECT_EQ(resolveScenes({suite.string()}, "").size(), 2u);
    EXPECT_NE(refused({suite.string(), "builtin"}, "").find("given twice"), std::string::npos);
}

// Two entries that reach one glTF through a relative and an absolute path, or through a linked
// folder, were two scenes (the text differed): the same scene is the same file.
TEST(SceneSuite, TheSameFileByAnotherPathIsTheSameScene) {
    fs::create_directories(folder() / "linked");
    if (!fs::exists(folder() / "linked" / "models")) fs::create_directory_symlink(folder() / "models", folder() / "linked" / "models");
    const std::string absolute = (folder() / "models" / "box.gltf").string();
    const std::string cases[] = {
        "[[scene]]\nname = \"a\"\ngltf = \"models/box.gltf\"\n[[scene]]\nname = \"b\"\ngltf = \"" + absolute + "\"\n",
        "[[scene]]\nname = \"a\"\ngltf = \"models/box.gltf\"\n[[scene]]\nname = \"b\"\ngltf = \"linked/models/box.gltf\"\n",
        "[[scene]]\nname = \"a\"\ngltf = \"models/box.gltf\"\nenvironment = \"sky.hdr\"\n[[scene]]\nname = \"b\"\n"
        "gltf = \"./models/../models/box.gltf\"\nenvironment = \"" + (folder() / "sky.hdr").string() + "\"\n",
    };
    for (const std::string& text : cases) {
        const std::string e = errorOf(text);
        EXPECT_NE(e.find("given twice"), std::string::npos) << text << "\n" << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    }
    // Under another environment it is another scene.
    EXPECT_EQ(errorOf("[[scene]]\nname = \"a\"\ngltf = \"models/box.gltf\"\n[[scene]]\nname = \"b\"\ngltf = \"" +
                      absolute + "\"\nenvironment = \"sky.hdr\"\n"),
              "");
    // On the command line too.
    const fs::path cwd = fs::current_path();
    fs::current_path(folder());
    std::string refused;
    try {
        resolveScenes({"models/box.gltf", absolute}, "");
    } catch (const UserError& e) {
        refused = e.what();
    }
    fs::current_path(cwd);
    EXPECT_NE(refused.find("given twice"), std::string::npos) << refused;
}

// A suite's `gltf` naming a suite failed at load time as a glTF that is not JSON; it is refused
// for what it is, as is an environment map given as a glTF and the other way round.
TEST(SceneSuite, AFileOfTheWrongKindIsNamedForWhatItIs) {
    std::ofstream(folder() / "inner.toml") << "[[scene]]\ngltf = \"builtin\"\n";
    struct Case {
        std::string text, place, words;
    };
    const Case cases[] = {
        {"[[scene]]\ngltf = \"inner.toml\"\n", ":2:8:", "is a scene suite"},
        {"[[scene]]\ngltf = \"sky.hdr\"\n", ":2:8:", "is an environment map, not a glTF scene"},
        {"[[scene]]\ngltf = \"builtin\"\nenvironment = \"models/box.gltf\"\n", ":3:15:", "is a glTF scene, not an environment map"},
    };
    for (const Case& c : cases) {
        const std::string e = errorOf(c.text);
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
        EXPECT_NE(e.find(c.place), std::string::npos) << c.text << "\n" << e;
        EXPECT_NE(e.find(c.words), std::string::npos) << c.text << "\n" << e;
    }
}

// --exposure and a suite's `exposure` accept the same range (the suite stopped at 1e6 and took no
// value below it but 0; --exposure takes what a float holds at full precision).
TEST(SceneSuite, ExposureTakesTheRangeOfTheFlag) {
    for (const char* good : {"1e30", "1e-30", "2", "0.001", "3e38"}) {
        const std::string text = std::string("[[scene]]\ngltf = \"builtin\"\nexposure = ") + good + "\n";
        std::vector<SceneSpec> s;
        ASSERT_NO_THROW(s = parseSceneSuite(text, (folder() / "suite.toml").string())) << good;
        EXPECT_FLOAT_EQ(*s[0].exposure, float(std::stod(good)));
    }
    for (const char* bad : {"0", "-1", "1e39", "1e-39", "nan", "inf"}) {
        const std::string e = errorOf(std::string("[[scene]]\ngltf = \"builtin\"\nexposure = ") + bad + "\n");
        EXPECT_NE(e.find("outside the range --exposure accepts"), std::string::npos) << bad << ": " << e;
    }
}
