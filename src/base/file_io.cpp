#include "file_io.h"

#include <ctime>
#include <fstream>
#include <system_error>
#include <unistd.h>

#include "error.h"

namespace gbl {
namespace fs = std::filesystem;

std::vector<unsigned char> readBinaryFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throwUserError(path.string() + ": cannot open for reading (check the path and permissions)");
    in.seekg(0, std::ios::end);
    const auto size = in.tellg();
    in.seekg(0, std::ios::beg);
    std::vector<unsigned char> bytes(size_t(std::max<std::streamoff>(size, 0)));
    if (!bytes.empty() && !in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size())))
        throwUserError(path.string() + ": read failed");
    return bytes;
}

std::string readTextFile(const fs::path& path) {
    const auto bytes = readBinaryFile(path);
    return std::string(bytes.begin(), bytes.end());
}

fs::path temporaryPathFor(const fs::path& path) {
    return path.parent_path() / ("." + path.filename().string() + ".tmp" + std::to_string(::getpid()));
}

void commitTemporary(const fs::path& tmp, const fs::path& path) {
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        discardTemporary(tmp);
        throwUserError(path.string() + ": cannot write (" + ec.message() + ")");
    }
}

void discardTemporary(const fs::path& tmp) noexcept {
    std::error_code ec;
    fs::remove(tmp, ec);
}

void writeFileAtomic(const fs::path& path, const void* bytes, size_t size) {
    writeViaTemporary(path, [&](const fs::path& tmp) {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) throwUserError(path.string() + ": cannot open for writing (check the directory exists and is writable)");
        out.write(static_cast<const char*>(bytes), std::streamsize(size));
        out.close();
        if (!out) throwUserError(path.string() + ": write failed (disk full?)");
    });
}

void writeFileAtomic(const fs::path& path, const std::string& text) { writeFileAtomic(path, text.data(), text.size()); }

void checkOutputDirectory(const fs::path& dir, bool force, const std::string& flagName) {
    std::error_code ec;
    if (!fs::exists(dir, ec)) return;
    if (!fs::is_directory(dir, ec))
        throwUserError(flagName + " " + dir.string() + ": exists and is not a directory; choose another path");
    if (!fs::is_empty(dir, ec) && !force)
        throwUserError(flagName + " " + dir.string() +
                       ": directory exists and is not empty; choose a new directory or pass --force to overwrite");
}

fs::path defaultOutputDirectory(const std::string& prefix) {
    const std::time_t now = std::time(nullptr);
    char stamp[32];
    std::strftime(stamp, sizeof(stamp), "%Y%m%d-%H%M%S", std::localtime(&now));
    fs::path dir = fs::path("out") / (prefix + "-" + stamp);
    for (int i = 2; fs::exists(dir); ++i) dir = fs::path("out") / (prefix + "-" + stamp + "-" + std::to_string(i));
    return dir;
}

void prepareOutputDirectory(const fs::path& dir, bool force, const std::string& flagName) {
    checkOutputDirectory(dir, force, flagName);
    std::error_code ec;
    if (fs::exists(dir, ec)) return;
    fs::create_directories(dir, ec);
    if (ec) throwUserError(flagName + " " + dir.string() + ": cannot create directory (" + ec.message() + ")");
}

}  // namespace gbl
