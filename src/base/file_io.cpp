#include "file_io.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <set>
#include <utility>
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
#include "memory_budget.h"

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
    // The file's size is the first allocation an input sizes: held to the budget like the rest.
    requireMemory(double(st.st_size), name + " (a file of " + formatBytes(double(st.st_size)) + ")",
                  "give a smaller file, or raise GBL_MEMORY_BUDGET on a machine with more memory");
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

namespace {

struct InputRegistry {
    std::mutex mutex;
    std::set<std::pair<dev_t, ino_t>> files;
};

InputRegistry& inputs() {
    static InputRegistry r;
    return r;
}

bool fileIdentity(const fs::path& path, std::pair<dev_t, ino_t>& id) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return false;
    id = {st.st_dev, st.st_ino};
    return true;
}

// Canonical where possible (a path that does not exist yet is made absolute and normalised).
fs::path absoluteNormal(const fs::path& path) {
    std::error_code ec;
    fs::path p = fs::weakly_canonical(path, ec);
    if (ec) p = fs::absolute(path, ec).lexically_normal();
    return p;
}

bool sameFile(const fs::path& a, const fs::path& b) {
    std::error_code ec;
    return fs::exists(a, ec) && fs::exists(b, ec) && fs::equivalent(a, b, ec) && !ec;
}

}  // namespace

void registerInput(const fs::path& path) {
    std::pair<dev_t, ino_t> id;
    if (!fileIdentity(path, id)) return;
    std::lock_guard<std::mutex> lock(inputs().mutex);
    inputs().files.insert(id);
}

bool isSameFile(const fs::path& a, const fs::path& b) { return sameFile(a, b); }

bool isRegisteredInput(const fs::path& path) {
    std::pair<dev_t, ino_t> id;
    if (!fileIdentity(path, id)) return false;
    std::lock_guard<std::mutex> lock(inputs().mutex);
    return inputs().files.count(id) != 0;
}

void refuseOutputOverInput(const fs::path& output, const std::vector<std::string>& inputList,
                           const std::string& flagName) {
    for (const std::string& in : inputList)
        if (!in.empty() && sameFile(output, in))
            throwUserError(flagName + " " + escapeText(output.string()) + ": is the input " + escapeText(in) +
                           "; an output never replaces an input, with or without --force: choose another name");
}

void refuseInputsInsideDirectory(const fs::path& dir, const std::vector<std::string>& inputList,
                                 const std::string& flagName) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return;
    const fs::path root = absoluteNormal(dir);
    for (const std::string& in : inputList) {
        if (in.empty() || !fs::exists(in, ec)) continue;
        const fs::path file = absoluteNormal(in);
        if (std::mismatch(root.begin(), root.end(), file.begin(), file.end()).first == root.end())
            throwUserError(flagName + " " + escapeText(dir.string()) + ": holds the input " + escapeText(in) +
                           ", and its files may be replaced; an output never replaces an input: choose another " +
                           flagName + " directory");
    }
}

namespace {

// What a path that is not a regular file is, for the message ("a FIFO"); "" for a regular file or
// a path that does not exist (nor a symbolic link whose target does not).
std::string nonRegularKind(const fs::path& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) {
        if (errno == ELOOP) return "a symbolic link that loops";
        return "";
    }
    if (S_ISREG(st.st_mode)) return "";
    if (S_ISDIR(st.st_mode)) return "a directory";
    if (S_ISCHR(st.st_mode)) return "a character device";
    if (S_ISBLK(st.st_mode)) return "a block device";
    if (S_ISFIFO(st.st_mode)) return "a FIFO";
    if (S_ISSOCK(st.st_mode)) return "a socket";
    return "not a regular file";
}

}  // namespace

void refuseNonRegularOutput(const fs::path& path, const std::string& flagName) {
    const std::string kind = nonRegularKind(path);
    if (kind.empty()) return;
    struct stat link {};
    const bool viaLink = ::lstat(path.c_str(), &link) == 0 && S_ISLNK(link.st_mode);
    throwUserError((flagName.empty() ? "" : flagName + " ") + escapeText(path.string()) + ": exists and is " +
                   (viaLink ? "a symbolic link to " : "") + kind +
                   ", not a regular file; an output replaces only a regular file, with or without --force: "
                   "choose another path");
}

void commitTemporary(const fs::path& tmp, const fs::path& path) {
    // The last line of defence of "outputs never replace inputs": whatever check a command made
    // before its work, a write over a file it read as input is refused here.
    if (isRegisteredInput(path)) {
        discardTemporary(tmp);
        throwUserError(escapeText(path.string()) + ": is an input of this command; an output never replaces an "
                       "input: choose another output path");
    }
    // Nor anything that is not a regular file (a device, a FIFO, a socket): checked again here,
    // just before the rename that would replace it.
    try {
        refuseNonRegularOutput(path);
    } catch (...) {
        discardTemporary(tmp);
        throw;
    }
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

void checkOutputDirectory(const fs::path& dir, bool force, const std::string& flagName, const std::string& reuse) {
    if (dir.empty())
        throwUserError(flagName + " '': an empty directory name; give a directory, or leave " + flagName +
                       " out for a new one under out/");
    std::error_code ec;
    if (!fs::exists(dir, ec)) return;
    if (!fs::is_directory(dir, ec))
        throwUserError(flagName + " " + escapeText(dir.string()) + ": exists and is not a directory; choose another path");
    if (!fs::is_empty(dir, ec) && !force)
        throwUserError(flagName + " " + escapeText(dir.string()) + ": directory exists and is not empty; choose a new "
                       "directory, or " + reuse);
    // Its files may be replaced: none may be a device, FIFO or socket (the writes would refuse it
    // at the end, after the work; refused here, before it). Links are not followed into.
    for (auto it = fs::recursive_directory_iterator(dir, fs::directory_options::skip_permission_denied, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
        if (it->is_directory(ec) && !it->is_symlink(ec)) continue;
        const std::string kind = nonRegularKind(it->path());
        if (!kind.empty() && kind != "a directory")
            throwUserError(flagName + " " + escapeText(dir.string()) + ": holds " + escapeText(it->path().string()) +
                           ", which is " + kind + ", not a regular file; an output replaces only a regular file: "
                           "remove it, or choose another directory");
    }
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

void prepareOutputDirectory(const fs::path& dir, bool force, const std::string& flagName, const std::string& reuse) {
    checkOutputDirectory(dir, force, flagName, reuse);
    std::error_code ec;
    if (!fs::exists(dir, ec)) {
        fs::create_directories(dir, ec);
        if (ec) throwUserError(flagName + " " + dir.string() + ": cannot create directory (" + ec.message() + ")");
    }
    lockOutputDirectory(dir, flagName);
    // Checked again under the lock: a run that finished between the first check and the lock has
    // filled the directory, and that is refused unless --force, as always.
    checkOutputDirectory(dir, force, flagName, reuse);
}

}  // namespace gbl
