#pragma once
// GBL_CACHE_DIR (base/disk_cache.h) pointed at a fresh, empty folder for a test's lifetime, and
// the folder removed after it.
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

namespace gbl::test {

struct TempCacheDir {
    std::filesystem::path dir;
    explicit TempCacheDir(const std::string& name) {
        dir = std::filesystem::temp_directory_path() / (name + "-" + std::to_string(::getpid()));
        std::filesystem::remove_all(dir);
        ::setenv("GBL_CACHE_DIR", dir.c_str(), 1);
    }
    ~TempCacheDir() {
        ::unsetenv("GBL_CACHE_DIR");
        std::filesystem::remove_all(dir);
    }
    TempCacheDir(const TempCacheDir&) = delete;
    TempCacheDir& operator=(const TempCacheDir&) = delete;
};

}  // namespace gbl::test
