// The bundled scenes (scenes/): real CC0 assets, each folder with its licence and provenance, every
// file the provenance lists present at the size it states and no file it does not list; the
// default suite parses and names only bundled files. Nothing here renders.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "scene_suite.h"

namespace fs = std::filesystem;
using namespace gbl::compare;

namespace {

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// "1,234,567" as PROVENANCE.md writes a size.
std::string withCommas(uintmax_t n) {
    std::string digits = std::to_string(n), out;
    for (size_t i = 0; i < digits.size(); ++i) {
        if (i && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

const fs::path kScenes = GBL_SOURCE_SCENE_DIR;

}  // namespace

TEST(BundledScenes, EveryFolderCarriesItsLicenceAndProvenance) {
    for (const char* folder : {"FlightHelmet", "WaterBottle", "envmaps"}) {
        SCOPED_TRACE(folder);
        const fs::path dir = kScenes / folder;
        ASSERT_TRUE(fs::is_directory(dir));
        const std::string licence = slurp(dir / "LICENSE.md"), provenance = slurp(dir / "PROVENANCE.md");
        EXPECT_NE(licence.find("CC0 1.0 Universal"), std::string::npos);
        EXPECT_NE(licence.find("Statement of Purpose"), std::string::npos);  // the legal code in full
        EXPECT_NE(provenance.find("commit"), std::string::npos);
        // Every asset file is listed with its size and a SHA-256; nothing unlisted.
        std::set<std::string> files;
        for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
            const std::string name = e.path().filename().string();
            if (name == "LICENSE.md" || name == "PROVENANCE.md") continue;
            files.insert(name);
            const std::string row = "| `" + name + "` | " + withCommas(fs::file_size(e.path())) + " | `";
            EXPECT_NE(provenance.find(row), std::string::npos) << name << " is not listed as " << row;
        }
        size_t listed = 0;
        for (size_t at = provenance.find("\n| `"); at != std::string::npos; at = provenance.find("\n| `", at + 1)) ++listed;
        EXPECT_EQ(listed, files.size());
        EXPECT_FALSE(files.empty());
    }
}

TEST(BundledScenes, TheDefaultSuiteNamesTheBuiltInSceneAndTheBundledAssets) {
    EXPECT_EQ(defaultSuitePath(), kScenes / "default-suite.toml");
    const std::vector<SceneSpec> scenes = loadSceneSuite(defaultSuitePath());
    ASSERT_EQ(scenes.size(), 3u);
    EXPECT_TRUE(scenes[0].gltfPath.empty());
    EXPECT_TRUE(scenes[0].envPath.empty());  // the built-in sky
    for (const SceneSpec& s : scenes) {
        EXPECT_FALSE(s.exposure.has_value()) << s.name;  // metered, as UE4's auto-exposure
        EXPECT_TRUE(s.cameras.empty()) << s.name;        // --views placed and fitted
        for (const std::string& file : {s.gltfPath, s.envPath})
            if (!file.empty()) {
                const fs::path relative = fs::path(file).lexically_relative(kScenes);
                EXPECT_FALSE(relative.empty() || *relative.begin() == "..") << file << " is not bundled";
            }
    }
}
