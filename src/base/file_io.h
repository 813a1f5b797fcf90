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

// An output replaces only a regular file. An existing `path` that is anything else (a character
// or block device such as /dev/full, a FIFO, a socket, a directory, or a symbolic link to one) is a
// UserError naming the path, what it is and the fix: the rename of an atomic write would put a
// regular file in its place. `flagName` ("--out"), when given, starts the message. Every atomic
// write below checks this itself; commands call it before their work, so that it fails fast.
void refuseNonRegularOutput(const std::filesystem::path& path, const std::string& flagName = "");

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

// Outputs never replace inputs. A command registers the files the user gave it to read (images,
// scenes and the files they name, environment maps, layout files) as they are read; every
// atomic write above refuses to rename over one of them (the same file by device and inode, so
// a symbolic or hard link to an input is caught too), whatever --force says. Caches and a
// command's own earlier outputs (a resumed search's journal) are not registered: they are
// meant to be rewritten.
void registerInput(const std::filesystem::path& path);
// Whether two paths name the same existing file (by device and inode: a relative and an absolute
// path, a symbolic link or a hard link to it, a path through a linked folder).
bool isSameFile(const std::filesystem::path& a, const std::filesystem::path& b);
// Whether `path` exists and is a registered input.
bool isRegisteredInput(const std::filesystem::path& path);
// Checks made before the work, so that a clash fails fast: `output` (a file) must not be one of
// `inputs`; with --force an output directory must not hold any of them (its files may be
// replaced). Each names the flag, the input and the fix.
void refuseOutputOverInput(const std::filesystem::path& output, const std::vector<std::string>& inputs,
                           const std::string& flagName);
void refuseInputsInsideDirectory(const std::filesystem::path& dir, const std::vector<std::string>& inputs,
                                 const std::string& flagName);

// Prepares an output directory: creates it, or accepts it when empty; a non-empty directory
// is accepted only with `force` (its files are then replaced one by one, atomically). The
// directory is then locked for the rest of the process: a second run into it is refused.
// `flagName` is the CLI flag named in the error ("--out").
void prepareOutputDirectory(const std::filesystem::path& dir, bool force, const std::string& flagName,
                            const std::string& reuse = "add --force to replace files in it");
void lockOutputDirectory(const std::filesystem::path& dir, const std::string& flagName);
// The same checks without creating anything: run before the work, so bad flags fail fast.
// `reuse` is how the command lets a non-empty directory be used, for the message ("add --force
// to replace its files"; search: resuming).
void checkOutputDirectory(const std::filesystem::path& dir, bool force, const std::string& flagName,
                          const std::string& reuse = "add --force to replace files in it");
// out/<prefix>-YYYYmmdd-HHMMSS (with -2, -3... when taken): a fresh directory, never one in use.
std::filesystem::path defaultOutputDirectory(const std::string& prefix);

template <class WriteFn>
void writeViaTemporary(const std::filesystem::path& path, WriteFn&& write) {
    refuseNonRegularOutput(path);
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
