// compare's scenes: --scene arguments and scene-suite files (scene_suite.h). The suite is read with
// toml++ through the layout parser's pieces (layout_parser_detail.h: source places, type names and
// the guard against inputs toml++ 3.3.0 does not survive), so its messages read like a layout's.
#include "scene_suite.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>

#include "option_values.h"
#include "error.h"
#include "file_io.h"
#include "layout_parser_detail.h"

namespace gbl::compare {

namespace fs = std::filesystem;
using layout_parser::placeOf;
using layout_parser::typeName;

namespace {

constexpr int kMaxSuiteCameras = 16;  // compare --views' bound

struct Diagnostics {
    std::string file;
    std::vector<std::string> lines;
    void error(FilePlace place, const std::string& message) {
        lines.push_back(formatPlace(escapeText(file), place.line, place.column) + ": " + message);
    }
    void throwIfAny() const {
        if (lines.empty()) return;
        std::string all;
        for (const std::string& l : lines) all += (all.empty() ? "" : "\n") + l;
        throwUserError(all);
    }
};

std::string stemName(const std::string& gltfPath) {
    return gltfPath.empty() ? std::string(kBuiltinSceneName) : fs::path(gltfPath).stem().string();
}

// A path of the suite, relative to its folder; "builtin" stays the built-in input ("").
std::string suitePath(const fs::path& folder, const std::string& value) {
    if (value == kBuiltinSceneName) return "";
    const fs::path p(value);
    return (p.is_absolute() || folder.empty() ? p : folder / p).lexically_normal().string();
}

std::string lowerExtension(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

// A file given where another kind belongs, by its extension: "a scene suite" for a .toml given as
// a glTF; "" when it may be what `key` asks for (the loader checks the contents).
std::string wrongKindOfFile(const std::string& key, const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext == ".toml") return "is a scene suite (a .toml), not " + std::string(key == "gltf" ? "a glTF scene" : "an environment map") +
                               "; list its scenes in this suite, or give both suites to --scene";
    if (key == "gltf" && (ext == ".hdr" || ext == ".exr"))
        return "is an environment map, not a glTF scene; give it as the scene's 'environment'";
    if (key == "environment" && (ext == ".gltf" || ext == ".glb"))
        return "is a glTF scene, not an environment map; give it as the scene's 'gltf'";
    return "";
}

bool isRegularFile(const std::string& path) {
    std::error_code ec;
    return fs::is_regular_file(path, ec);
}

// Two inputs of scenes are the same when both are the built-in one ("") or both name one file,
// however reached (a relative and an absolute path, a symbolic link, a linked folder): the files
// are compared, not the text.
bool sameInput(const std::string& a, const std::string& b) {
    if (a.empty() || b.empty()) return a.empty() && b.empty();
    return a == b || isSameFile(a, b);
}

bool sameSceneFiles(const SceneSpec& a, const SceneSpec& b) {
    return sameInput(a.gltfPath, b.gltfPath) && sameInput(a.envPath, b.envPath);
}

// The same scene twice: the same name (its folder), or the same glTF under the same environment.
void refuseRepeats(const std::vector<SceneSpec>& scenes) {
    for (size_t i = 0; i < scenes.size(); ++i)
        for (size_t k = 0; k < i; ++k) {
            const bool sameFiles = sameSceneFiles(scenes[i], scenes[k]);
            if (scenes[i].name == scenes[k].name || sameFiles)
                throwUserError(scenes[i].origin + ": the scene " + quoteName(scenes[i].name) +
                               " is given twice (also " + scenes[k].origin + ")" +
                               (scenes[i].name == scenes[k].name && !sameFiles
                                    ? "; two scenes share a name, and so a folder: give one another `name` in a suite file"
                                    : "; give each scene once"));
        }
}

std::optional<glm::vec3> readVec3(const toml::table& t, const char* key, bool required, FilePlace owner,
                                  Diagnostics& d) {
    const toml::node* n = t.get(key);
    if (!n) {
        if (required) d.error(owner, "the camera has no '" + std::string(key) + "' (give [x, y, z])");
        return std::nullopt;
    }
    const toml::array* a = n->as_array();
    if (!a || a->size() != 3) {
        d.error(placeOf(*n), "'" + std::string(key) + "' must be an array of 3 numbers, [x, y, z]");
        return std::nullopt;
    }
    glm::vec3 v{};
    for (size_t i = 0; i < 3; ++i) {
        const toml::node& e = *a->get(i);
        const std::optional<double> x = e.is_integer() ? std::optional<double>(double(e.as_integer()->get()))
                                        : e.is_floating_point() ? std::optional<double>(e.as_floating_point()->get())
                                                                : std::nullopt;
        if (!x || !std::isfinite(*x) || std::abs(*x) > 1e6) {
            d.error(placeOf(e), "'" + std::string(key) + "' holds " + (x ? "a number outside +-1e6" : typeName(e)) +
                                    "; give finite numbers");
            return std::nullopt;
        }
        v[int(i)] = float(*x);
    }
    return v;
}

std::optional<double> readNumber(const toml::node& n, const std::string& what, double lo, double hi, Diagnostics& d) {
    const std::optional<double> x = n.is_integer()          ? std::optional<double>(double(n.as_integer()->get()))
                                    : n.is_floating_point() ? std::optional<double>(n.as_floating_point()->get())
                                                            : std::nullopt;
    if (!x) {
        d.error(placeOf(n), what + " must be a number, not " + typeName(n));
        return std::nullopt;
    }
    if (!(*x > lo && *x < hi)) {
        d.error(placeOf(n), what + " " + layout_parser::formatNumber(*x) + " is outside (" +
                                layout_parser::formatNumber(lo) + ", " + layout_parser::formatNumber(hi) + ")");
        return std::nullopt;
    }
    return x;
}

std::optional<Camera> readCamera(const toml::node& node, Diagnostics& d) {
    const toml::table* t = node.as_table();
    if (!t) {
        d.error(placeOf(node), "[[scene.camera]] must be a table, not " + std::string(typeName(node)));
        return std::nullopt;
    }
    for (auto&& [key, value] : *t) {
        (void)value;
        const std::string k(key.str());
        if (k != "position" && k != "target" && k != "up" && k != "fov_y_degrees")
            d.error(placeOf(key.source()),
                    "unknown key " + quoteName(k) + " in [[scene.camera]] (known: position, target, up, fov_y_degrees)");
    }
    const FilePlace place = placeOf(node);
    Camera c;
    const auto position = readVec3(*t, "position", true, place, d);
    const auto target = readVec3(*t, "target", true, place, d);
    const auto up = readVec3(*t, "up", false, place, d);
    if (!position || !target) return std::nullopt;
    c.position = *position;
    c.target = *target;
    if (up) c.up = *up;
    if (glm::length(c.target - c.position) < 1e-6f) {
        d.error(place, "the camera's position and target are the same point; give a target it looks at");
        return std::nullopt;
    }
    if (glm::length(glm::cross(glm::normalize(c.target - c.position), c.up)) < 1e-3f) {
        d.error(place, "the camera looks along its 'up'; give an up that is not parallel to target - position");
        return std::nullopt;
    }
    if (const toml::node* f = t->get("fov_y_degrees")) {
        const auto fov = readNumber(*f, "'fov_y_degrees'", 0.0, 180.0, d);
        if (!fov) return std::nullopt;
        c.yFovRadians = float(*fov * M_PI / 180.0);
    }
    c.fromFile = true;  // placed by the user: compare keeps it as given (near and far from the scene)
    return c;
}

SceneSpec readScene(const toml::node& node, const fs::path& folder, Diagnostics& d) {
    SceneSpec s;
    const FilePlace place = placeOf(node);
    s.origin = formatPlace(escapeText(d.file), place.line, place.column);
    const toml::table* t = node.as_table();
    if (!t) {
        d.error(place, "[[scene]] must be a table, not " + std::string(typeName(node)));
        return s;
    }
    for (auto&& [key, value] : *t) {
        (void)value;
        const std::string k(key.str());
        if (k != "name" && k != "gltf" && k != "environment" && k != "exposure" && k != "camera")
            d.error(placeOf(key.source()),
                    "unknown key " + quoteName(k) + " in [[scene]] (known: name, gltf, environment, exposure, camera)");
    }
    auto readFile = [&](const char* key, bool required, std::string& out) {
        const toml::node* n = t->get(key);
        if (!n) {
            if (required)
                d.error(place, "the scene has no '" + std::string(key) + "' (a .gltf / .glb path, or \"builtin\")");
            return;
        }
        if (!n->is_string()) {
            d.error(placeOf(*n), "'" + std::string(key) + "' must be a string, not " + typeName(*n));
            return;
        }
        const std::string& value = n->as_string()->get();
        out = suitePath(folder, value);
        if (const std::string wrong = out.empty() ? "" : wrongKindOfFile(key, out); !wrong.empty())
            d.error(placeOf(*n), "'" + std::string(key) + "' " + quoteName(value) + " " + wrong);
        else if (!out.empty() && !isRegularFile(out))
            d.error(placeOf(*n), "'" + std::string(key) + "' " + quoteName(value) + ": no such file (" +
                                     escapeText(out) + "; paths are relative to the suite's folder)");
    };
    readFile("gltf", true, s.gltfPath);
    readFile("environment", false, s.envPath);
    s.name = stemName(s.gltfPath);
    if (const toml::node* n = t->get("name")) {
        if (!n->is_string() || !isValidSceneName(n->as_string()->get()))
            d.error(placeOf(*n), "'name' must be a string of letters, digits, '-', '_' or '.' (the scene's folder)");
        else
            s.name = n->as_string()->get();
    } else if (!isValidSceneName(s.name)) {
        d.error(place, "the glTF's file name " + quoteName(s.name) + " cannot name a folder; give the scene a 'name'");
    }
    if (const toml::node* n = t->get("exposure")) {
        // The range compare --exposure accepts, no narrower and no wider.
        const std::optional<double> x = n->is_integer()          ? std::optional<double>(double(n->as_integer()->get()))
                                        : n->is_floating_point() ? std::optional<double>(n->as_floating_point()->get())
                                                                 : std::nullopt;
        if (!x)
            d.error(placeOf(*n), "'exposure' must be a number, not " + std::string(typeName(*n)));
        else if (const std::string problem = positiveFloatProblem(*x); !problem.empty())
            d.error(placeOf(*n), "'exposure' " + layout_parser::formatNumber(*x) +
                                     " is outside the range --exposure accepts: " + problem);
        else
            s.exposure = float(*x);
    }
    if (const toml::node* cams = t->get("camera")) {
        const toml::array* a = cams->as_array();
        if (!a || a->empty() || a->size() > size_t(kMaxSuiteCameras)) {
            d.error(placeOf(*cams), "'camera' must be 1 to " + std::to_string(kMaxSuiteCameras) +
                                        " [[scene.camera]] tables");
        } else {
            for (const toml::node& c : *a)
                if (auto camera = readCamera(c, d)) s.cameras.push_back(*camera);
        }
    }
    return s;
}

}  // namespace

bool isValidSceneName(const std::string& name) {
    return !name.empty() && name.size() <= 100 && name[0] != '.' &&
           std::all_of(name.begin(), name.end(), [](char c) {
               return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
                      c == '_' || c == '.';
           });
}

std::vector<SceneSpec> parseSceneSuite(const std::string& text, const std::string& fileName) {
    Diagnostics d{fileName, {}};
    if (auto unsafe = layout_parser::findTomlPlusPlusHazard(text)) {  // never handed to toml++
        d.error(unsafe->first, unsafe->second);
        d.throwIfAny();
    }
    toml::table root;
    try {
        root = toml::parse(text, fileName);
    } catch (const toml::parse_error& e) {
        d.error(placeOf(e.source()), "TOML syntax error: " + escapeText(e.description()));
        d.throwIfAny();
    }
    for (auto&& [key, value] : root) {
        (void)value;
        if (key.str() != "scene")
            d.error(placeOf(key.source()), "unknown key " + quoteName(std::string(key.str())) +
                                               " in the suite (known: scene, as [[scene]] tables)");
    }
    std::vector<SceneSpec> scenes;
    const fs::path folder = fs::path(fileName).parent_path();
    const toml::node* list = root.get("scene");
    if (!list || !list->is_array() || list->as_array()->empty()) {
        d.error(list ? placeOf(*list) : FilePlace{1, 1},
                "the suite has no scene; give at least one [[scene]] table with a 'gltf'");
    } else {
        for (const toml::node& n : *list->as_array()) scenes.push_back(readScene(n, folder, d));
    }
    // A scene twice: named where the second one is.
    for (size_t i = 0; i < scenes.size() && d.lines.empty(); ++i)
        for (size_t k = 0; k < i; ++k) {
            const bool sameFiles = sameSceneFiles(scenes[i], scenes[k]);
            if (scenes[i].name != scenes[k].name && !sameFiles) continue;
            const FilePlace at = placeOf(*list->as_array()->get(i));
            d.error(at, "the scene " + quoteName(scenes[i].name) + " is given twice (also at " + scenes[k].origin +
                            (sameFiles ? "); give each scene once" : "); give one of them another 'name'"));
            break;
        }
    d.throwIfAny();
    return scenes;
}

std::vector<SceneSpec> loadSceneSuite(const fs::path& path) {
    return parseSceneSuite(readTextFile(path), path.string());
}

fs::path bundledSceneDirectory() {
    std::error_code ec;
    if (const char* env = std::getenv("GBL_SCENE_DIR"); env && *env) {
        const fs::path dir(env);
        if (!fs::is_directory(dir, ec))
            throwUserError("GBL_SCENE_DIR=" + escapeText(dir.string()) +
                           ": not a directory (point it at gbufferlab's scenes/ or unset it)");
        return dir;
    }
    const fs::path dir(GBL_SOURCE_SCENE_DIR);
    if (!fs::is_directory(dir, ec))
        throwUserError(escapeText(dir.string()) +
                       ": the bundled scenes' directory is missing; set GBL_SCENE_DIR to gbufferlab's scenes/ "
                       "directory, or give --scene builtin (or a glTF, or a suite .toml)");
    return dir;
}

fs::path defaultSuitePath() { return bundledSceneDirectory() / "default-suite.toml"; }

std::vector<SceneSpec> resolveScenes(const std::vector<std::string>& sceneArgs, const std::string& envPath) {
    std::vector<SceneSpec> scenes;
    if (const std::string wrong = envPath.empty() ? "" : wrongKindOfFile("environment", envPath); !wrong.empty())
        throwUserError("--env " + quoteName(envPath) + ": " + wrong.substr(0, wrong.find(';')) +
                       "; give an .hdr or .exr file");
    if (!envPath.empty() && !isRegularFile(envPath))
        throwUserError("--env " + quoteName(envPath) + ": no such file; give an .hdr or .exr file");
    for (const std::string& arg : sceneArgs.empty() ? std::vector<std::string>{kBuiltinSceneName} : sceneArgs) {
        if (arg.size() > 5 && arg.compare(arg.size() - 5, 5, ".toml") == 0) {
            for (SceneSpec& s : loadSceneSuite(arg)) scenes.push_back(std::move(s));
            continue;
        }
        SceneSpec s;
        s.gltfPath = arg == kBuiltinSceneName ? "" : arg;
        s.envPath = envPath;
        s.name = stemName(s.gltfPath);
        s.origin = "--scene " + quoteName(arg);
        if (const std::string wrong = s.gltfPath.empty() ? "" : wrongKindOfFile("gltf", s.gltfPath);
            !wrong.empty() && lowerExtension(s.gltfPath) != ".toml")
            throwUserError("--scene " + quoteName(arg) + ": " + wrong.substr(0, wrong.find(';')) +
                           "; give it as --env, and a .gltf / .glb file, builtin or a suite .toml as --scene");
        if (!s.gltfPath.empty() && !isRegularFile(s.gltfPath))
            throwUserError("--scene " + quoteName(arg) + ": no such file; give a .gltf / .glb file, builtin, or a suite .toml");
        if (!isValidSceneName(s.name))
            throwUserError("--scene " + quoteName(arg) + ": its file name cannot name the scene's folder; list it in a "
                           "suite file with a 'name'");
        scenes.push_back(std::move(s));
    }
    refuseRepeats(scenes);
    return scenes;
}

}  // namespace gbl::compare
