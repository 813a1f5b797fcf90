#pragma once
// File helpers that keep the promise "written whole or not at all, nothing overwritten
// without asking": writes go to a temporary name in the same directory and are renamed.
#include <filesystem>
#include <string>
#include <vector>

#include "interrupt.h"

namespace gbl {

// Whole regular files only: a directory, FIFO or device is a UserError naming the path, never a
// hang or a bad_alloc.
std::vector<unsigned char> readBinaryFile(const std::filesystem::path& path);
std::string readTextFile(const std::filesystem::path& path);

// For readers that open by name themselves (OpenEXR): the same refusal without reading.
void requireRegularFile(const std::filesystem::path& path);

// Writes `bytes` to `path` atomically (temporary file + rename). Throws UserError on failure.
void writeFileAtomic(const std::filesystem::path& path, const void* bytes, size_t size);
void writeFileAtomic(const std::filesystem::path& path, const std::string& text);

// Calls `write(tmpPath)` and renames tmpPath to path when it returns; removes tmpPath if it throws.
// For libraries (OpenEXR, stb) that want a file name to write to.
template <class WriteFn>
void writeViaTemporary(const std::filesystem::path& path, WriteFn&& write);
std::filesystem::path temporaryPathFor(const std::filesystem::path& path);
void commitTemporary(const std::filesystem::path& tmp, const std::filesystem::path& path);
void discardTemporary(const std::filesystem::path& tmp) noexcept;

// Prepares an output directory: creates it, or accepts it when empty; a non-empty directory
// is accepted only with `force` (its files are then replaced one by one, atomically). The
// directory is then locked for the rest of the process: a second run into it is refused.
// `flagName` is the CLI flag named in the error ("--out").
void prepareOutputDirectory(const std::filesystem::path& dir, bool force, const std::string& flagName);
void lockOutputDirectory(const std::filesystem::path& dir, const std::string& flagName);
// The same checks without creating anything: run before the work, so bad flags fail fast.
void checkOutputDirectory(const std::filesystem::path& dir, bool force, const std::string& flagName);
// out/<prefix>-YYYYmmdd-HHMMSS (with -2, -3... when taken): a fresh directory, never one in use.
std::filesystem::path defaultOutputDirectory(const std::string& prefix);

template <class WriteFn>
void writeViaTemporary(const std::filesystem::path& path, WriteFn&& write) {
    const auto tmp = temporaryPathFor(path);
    registerTemporary(tmp);  // removed on SIGINT / SIGTERM (interrupt.h)
    try {
        write(tmp);
    } catch (...) {
        discardTemporary(tmp);
        throw;
    }
    commitTemporary(tmp, path);
}

}  // namespace gbl
