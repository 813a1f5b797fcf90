// compare's default (compare_flags.h): without --scene, the bundled suite (scenes/default-suite.toml)
// at its own size and views, which --size / --views override; --scene builtin, the built-in scene
// alone at 1920x1080 as before; --env without --scene refused, naming the fix. The bundled folder
// found as layouts/ is: $GBL_SCENE_DIR, else the source tree's scenes/.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include "compare_flags.h"
#include "compare_suite.h"
#include "error.h"
#include "scene_suite.h"

namespace fs = std::filesystem;
using namespace gbl;
using namespace gbl::compare;

namespace {

CompareOptions parsed(const std::vector<std::string>& args) {
    const std::optional<CompareOptions> o = parseCompareOptions(args);
    EXPECT_TRUE(o.has_value());
    return o.value_or(CompareOptions{});
}

std::string refusal(const std::vector<std::string>& args) {
    try {
        parseCompareOptions(args);
    } catch (const UserError& e) {
        return e.what();
    }
    return "";
}

// Sets an environment variable for the scope.
struct ScopedEnv {
    std::string name;
    ScopedEnv(std::string n, const std::string& value) : name(std::move(n)) { ::setenv(name.c_str(), value.c_str(), 1); }
    ~ScopedEnv() { ::unsetenv(name.c_str()); }
};

}  // namespace

TEST(CompareFlags, WithoutASceneTheBundledSuiteAtItsSizeAndViews) {
    const CompareOptions o = parsed({});
    ASSERT_EQ(o.sceneArgs.size(), 1u);
    EXPECT_EQ(fs::path(o.sceneArgs[0]), fs::path(GBL_SOURCE_SCENE_DIR) / "default-suite.toml");
    EXPECT_TRUE(comparesSeveralScenes(o));
    EXPECT_EQ(o.width, kDefaultSuiteWidth);
    EXPECT_EQ(o.height, kDefaultSuiteHeight);
    EXPECT_EQ(o.viewCount, kDefaultSuiteViews);
    EXPECT_FALSE(o.layoutsSpec.has_value());  // every layout
    // It names the built-in scene and the bundled assets, every file present.
    const std::vector<SceneSpec> scenes = resolveScenes(o.sceneArgs, o.envPath);
    ASSERT_EQ(scenes.size(), 3u);
    EXPECT_EQ(scenes[0].name, "builtin");
    EXPECT_TRUE(scenes[0].gltfPath.empty());
    EXPECT_EQ(scenes[1].name, "FlightHelmet");
    EXPECT_EQ(scenes[2].name, "WaterBottle");
    for (size_t i = 1; i < 3; ++i) {
        EXPECT_TRUE(fs::is_regular_file(scenes[i].gltfPath)) << scenes[i].gltfPath;
        EXPECT_EQ(fs::path(scenes[i].envPath).filename(), "empty_warehouse_01_1k.hdr");
        EXPECT_TRUE(fs::is_regular_file(scenes[i].envPath)) << scenes[i].envPath;
    }
}

TEST(CompareFlags, SizeAndViewsOverrideTheSuitesDefaults) {
    const CompareOptions o = parsed({"--size", "64x36", "--views", "1", "--layouts", "ue4"});
    EXPECT_TRUE(comparesSeveralScenes(o));
    EXPECT_EQ(o.width, 64u);
    EXPECT_EQ(o.height, 36u);
    EXPECT_EQ(o.viewCount, 1);
}

TEST(CompareFlags, SceneBuiltinIsTheSingleSceneRunOfBefore) {
    const CompareOptions o = parsed({"--scene", "builtin"});
    EXPECT_EQ(o.sceneArgs, std::vector<std::string>{"builtin"});
    EXPECT_TRUE(o.scenePath.empty());
    EXPECT_FALSE(comparesSeveralScenes(o));
    EXPECT_EQ(o.width, 1920u);
    EXPECT_EQ(o.height, 1080u);
    EXPECT_EQ(o.viewCount, 3);
    // A scene of one's own: the same 1080p default.
    const CompareOptions g = parsed({"--scene", "a.gltf", "--env", "sky.hdr"});
    EXPECT_EQ(g.width, 1920u);
    EXPECT_EQ(g.envPath, "sky.hdr");
}

TEST(CompareFlags, AnEnvironmentWithoutASceneIsRefused) {
    const std::string why = refusal({"--env", "sky.hdr"});
    EXPECT_NE(why.find("--env without --scene"), std::string::npos) << why;
    EXPECT_NE(why.find("--scene builtin"), std::string::npos) << why;
}

TEST(CompareFlags, TheBundledFolderComesFromTheEnvironmentWhenSet) {
    const fs::path dir = fs::temp_directory_path() / ("gbl_compare_flags_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    {
        ScopedEnv env("GBL_SCENE_DIR", dir.string());
        EXPECT_EQ(bundledSceneDirectory(), dir);
        EXPECT_EQ(parsed({}).sceneArgs, std::vector<std::string>{(dir / "default-suite.toml").string()});
    }
    {
        ScopedEnv env("GBL_SCENE_DIR", (dir / "missing").string());
        const std::string why = refusal({});
        EXPECT_NE(why.find("GBL_SCENE_DIR"), std::string::npos) << why;
        EXPECT_NO_THROW(parseCompareOptions({"--scene", "builtin"}));  // no bundled scene needed
    }
    fs::remove_all(dir);
}
