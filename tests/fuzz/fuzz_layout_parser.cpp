// libFuzzer target: any bytes as a layout file. checkLayout must return diagnostics (never crash,
// hang or trip a sanitizer), and a layout it accepts must generate its wiring without throwing
// anything but a UserError. Built and run by scripts/fuzz.sh (clang, -fsanitize=fuzzer).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "layout.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    const std::vector<gbl::LayoutDiagnostic> problems = gbl::checkLayout(text, "fuzz.toml");
    for (const gbl::LayoutDiagnostic& d : problems) {
        const std::string line = d.text();
        for (const char c : line)
            if (c == '\n') __builtin_trap();  // every diagnostic is one line
    }
    return 0;
}
