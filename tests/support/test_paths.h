#pragma once
// Where tests find real inputs: ../shared/assets beside the repo (when present) and the
// Debian assimp-testmodels package.
#include <filesystem>
#include <string>

namespace gbl::test {

inline std::filesystem::path sharedAssets() { return std::filesystem::path(GBL_SHARED_DIR) / "assets"; }
inline std::filesystem::path assimpGltf2() { return "/usr/share/assimp/models/glTF2"; }
inline bool exists(const std::filesystem::path& p) { return std::filesystem::exists(p); }

}  // namespace gbl::test

// Skips a test (visibly) when an optional input is absent.
#define GBL_REQUIRE_FILE(path)                                                        \
    do {                                                                              \
        if (!std::filesystem::exists(path)) GTEST_SKIP() << "missing input " << (path); \
    } while (0)
