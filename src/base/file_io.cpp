#include "file_io.h"

#include <atomic>
#include <cstdint>
#include <ctime>
#include <fstream>
#include <system_error>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "error.h"

namespace gbl {
namespace fs = std::filesystem;

// Opened non-blocking and checked with fstat on the open descriptor (no race with a stat by
// name): a FIFO or device would block or never end, a directory reads as garbage sizes.
std::vector<unsigned char> readBinaryFile(const fs::path& path) {
    const std::string name = escapeText(path.string());
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0 && errno == ENOENT) throwUserError(name + ": file not found; check the path");
    if (fd < 0)
        throwUserError(name + ": cannot open for reading (" + std::strerror(errno) + "); check the path and permissions");
    struct FdCloser {
        int fd;
        ~FdCloser() { ::close(fd); }
    } closer{fd};
    struct stat st {};
    if (::fstat(fd, &st) != 0) throwUserError(name + ": cannot read (" + std::strerror(errno) + ")");
    if (S_ISDIR(st.st_mode)) throwUserError(name + ": is a directory, not a file; give the path of a file");
    if (!S_ISREG(st.st_mode))
        throwUserError(name + ": is not a regular file (a FIFO, socket or device); copy the data to a file and give that");
    std::vector<unsigned char> bytes(size_t(std::max<off_t>(st.st_size, 0)));
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::read(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) throwUserError(name + ": read failed (" + std::strerror(errno) + ")");
        if (n == 0) break;  // the file shrank while being read
        done += size_t(n);
    }
    bytes.resize(done);
    return bytes;
}

void requireRegularFile(const fs::path& path) {
    const std::string name = escapeText(path.string());
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0)
        throwUserError(name + ": cannot open for reading (" + std::strerror(errno) + "); check the path");
    if (S_ISDIR(st.st_mode)) throwUserError(name + ": is a directory, not a file; give the path of a file");
    if (!S_ISREG(st.st_mode))
        throwUserError(name + ": is not a regular file (a FIFO, socket or device); copy the data to a file and give that");
}

std::string readTextFile(const fs::path& path) {
    const auto bytes = readBinaryFile(path);
    return std::string(bytes.begin(), bytes.end());
}

fs::path temporaryPathFor(const fs::path& path) {
    // Unique per call, not only per process: two threads writing the same file (two pipelines
    // compiling the same shader into the SPIR-V cache, background image writers) each get their
    // own temporary, and the last rename wins with a whole file.
    static std::atomic<uint64_t> serial{0};
    return path.parent_path() / ("." + path.filename().string() + ".tmp" + std::to_string(::getpid()) + "-" +
                                 std::to_string(serial.fetch_add(1)));
}

void commitTemporary(const fs::path& tmp, const fs::path& path) {
    std::error_code ec;
    fs::rename(tmp, path, ec);
    unregisterTemporary(tmp);
    if (ec) {
        discardTemporary(tmp);
        throwUserError(path.string() + ": cannot write (" + ec.message() + ")");
    }
}

void discardTemporary(const fs::path& tmp) noexcept {
    std::error_code ec;
    fs::remove(tmp, ec);
    unregisterTemporary(tmp);
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

// Two runs writing into one folder would interleave their files and overwrite each other's
// report. The directory itself is locked (flock on its descriptor, kept open until the process
// exits, so the kernel releases it even after a crash or kill -9); a second run is refused.
void lockOutputDirectory(const fs::path& dir, const std::string& flagName) {
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0)
        throwUserError(flagName + " " + escapeText(dir.string()) + ": cannot open directory (" + std::strerror(errno) + ")");
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
        const int error = errno;
        ::close(fd);
        if (error == EWOULDBLOCK)
            throwUserError(flagName + " " + escapeText(dir.string()) +
                           ": another gbufferlab run is writing into this directory; wait for it to finish or "
                           "choose another directory");
        throwUserError(flagName + " " + escapeText(dir.string()) + ": cannot lock directory (" + std::strerror(error) + ")");
    }
    // fd stays open (and locked) for the rest of the process.
}

void prepareOutputDirectory(const fs::path& dir, bool force, const std::string& flagName) {
    checkOutputDirectory(dir, force, flagName);
    std::error_code ec;
    if (!fs::exists(dir, ec)) {
        fs::create_directories(dir, ec);
        if (ec) throwUserError(flagName + " " + dir.string() + ": cannot create directory (" + ec.message() + ")");
    }
    lockOutputDirectory(dir, flagName);
    // Checked again under the lock: a run that finished between the first check and the lock has
    // filled the directory, and that is refused unless --force, as always.
    checkOutputDirectory(dir, force, flagName);
}

}  // namespace gbl
