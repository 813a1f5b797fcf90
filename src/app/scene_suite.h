#pragma once
// compare's scenes: each `--scene` (a glTF file, `builtin`, or a scene-suite .toml) becomes one or
// more SceneSpecs, every file checked before anything is rendered. A suite file lists scenes, each
// with its glTF, its environment and optionally its cameras and exposure:
//
//   [[scene]]
//   name = "helmet"                                  # optional: the glTF file's stem, or "builtin"
//   gltf = "models/FlightHelmet/FlightHelmet.gltf"   # or "builtin"; relative to the suite's folder
//   environment = "empty_warehouse_01_1k.hdr"        # optional: the built-in sky
//   exposure = 1.5                                   # optional: compare --exposure for this scene
//   [[scene.camera]]                                 # optional, up to 16: the scene's views
//   position = [0.0, 0.3, 1.0]
//   target = [0.0, 0.3, 0.0]
//   up = [0.0, 1.0, 0.0]                             # optional
//   fov_y_degrees = 40.0                             # optional (default 40.1, the scene camera's)
//
// A bad suite is refused with one line per problem, "file:line:col: message", as layout files are
// (layout_parser.cpp): a file that does not exist, a scene given twice, no scene at all.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "scene.h"

namespace gbl::compare {

inline constexpr const char* kBuiltinSceneName = "builtin";

struct SceneSpec {
    std::string name;         // the report's name of the scene and its folder, scenes/<name>/
    std::string gltfPath;     // empty: the built-in scene
    std::string envPath;      // empty: the built-in sky
    std::optional<float> exposure;  // the suite's; unset: compare's --exposure (or automatic)
    std::vector<Camera> cameras;    // the suite's; empty: compare --views placed from the scene
    std::string origin;       // where it was given: "--scene" or "suite.toml:3:1"
};

// Parses and checks a suite file (as above); throws UserError with every problem, one per line.
std::vector<SceneSpec> parseSceneSuite(const std::string& text, const std::string& fileName);
std::vector<SceneSpec> loadSceneSuite(const std::filesystem::path& path);

// The bundled scenes' folder (scenes/ of the repository: real CC0 assets with their licences, and
// default-suite.toml): $GBL_SCENE_DIR, else the source tree's scenes/ fixed at build time, as
// layouts/ and shaders/ are found. Throws UserError naming GBL_SCENE_DIR when it is not a folder.
std::filesystem::path bundledSceneDirectory();
// What compare runs without --scene: the bundled suite, <bundledSceneDirectory()>/default-suite.toml.
std::filesystem::path defaultSuitePath();

// Every --scene in order (none: the built-in scene), each a glTF path, `builtin` or a suite file
// (.toml), expanded; `--env` applies to the scenes named on the command line. Files that do not
// exist, a scene given twice (by its name, or by the same glTF and environment) are UserErrors.
std::vector<SceneSpec> resolveScenes(const std::vector<std::string>& sceneArgs, const std::string& envPath);

// A scene's name is its folder's: letters, digits, '-', '_' and '.', not starting with '.'.
bool isValidSceneName(const std::string& name);

}  // namespace gbl::compare
