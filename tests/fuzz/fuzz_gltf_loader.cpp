// libFuzzer target: any bytes as a .gltf/.glb scene. loadGltfScene must load it or throw a
// one-line UserError; anything else (a crash, another exception, a sanitizer finding) is a bug.
// The bytes are written to a scratch folder so that relative URIs resolve there (and are
// confined to it). Built and run by scripts/fuzz.sh (clang, -fsanitize=fuzzer).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "error.h"
#include "scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::filesystem::path dir = [] {
        const auto d = std::filesystem::temp_directory_path() / ("gbl-fuzz-gltf-" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        return d;
    }();
    const std::string path = (dir / "scene.gltf").string();
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) return 0;
    std::fwrite(data, 1, size, f);
    std::fclose(f);
    try {
        gbl::loadGltfScene(path);
    } catch (const gbl::UserError& e) {
        for (const char* c = e.what(); *c; ++c)
            if (*c == '\n') __builtin_trap();  // the error policy: one line
    }
    return 0;
}
