// What the commands write, run as the real executable: a named output never replaces what is not
// a regular file (a device, a FIFO, a socket), `--out ""` is an error, and a write to standard
// output that fails is an error of the command (one line, a status below 128), never a silent 0.
// None of it needs a Vulkan device.
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "cli_runner.h"
#include "image.h"
#include "image_io.h"

namespace fs = std::filesystem;

namespace {

using namespace gbl::test;

const CliScratch scratch("gbl_outputs_test_");

RunResult run(const std::string& args) { return scratch.run(args); }

// `gbufferlab ARGS` with stdout sent to `target` (a shell redirection such as ">/dev/full" or
// ">&-"); stderr captured.
RunResult runWithStdout(const std::string& args, const std::string& target) {
    const fs::path err = scratch() / "stderr.txt";
    const std::string cmd = "cd " + scratch().string() + " && " + GBL_BINARY + " " + args + " " + target + " 2>" +
                            err.string();
    return {shellExitCode(cmd), "", slurp(err)};
}

mode_t typeOf(const fs::path& p) {
    struct stat st {};
    return ::lstat(p.c_str(), &st) == 0 ? (st.st_mode & S_IFMT) : 0;
}

// The special files an output might be aimed at, made in the scratch folder (never in /dev): a
// character device like /dev/full (when this process may mknod), a FIFO and a socket.
std::vector<std::pair<fs::path, mode_t>> specialFiles(const std::string& stem, const std::string& ext) {
    std::vector<std::pair<fs::path, mode_t>> out;
    const fs::path dev = scratch() / (stem + "-dev" + ext);
    if (::mknod(dev.c_str(), S_IFCHR | 0600, makedev(1, 7)) == 0) out.push_back({dev, S_IFCHR});
    const fs::path fifo = scratch() / (stem + "-fifo" + ext);
    if (::mkfifo(fifo.c_str(), 0600) == 0) out.push_back({fifo, S_IFIFO});
    const fs::path sock = scratch() / (stem + "-sock" + ext);
    const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::snprintf(addr.sun_path, sizeof(addr.sun_path), "%s", sock.c_str());
    if (fd >= 0 && ::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof(addr)) == 0) out.push_back({sock, S_IFSOCK});
    if (fd >= 0) ::close(fd);
    return out;
}

void writeSmallPngs() {
    gbl::Image8 a{8, 6, 3, std::vector<unsigned char>(8 * 6 * 3, 100)}, b = a;
    b.pixels[5] = 120;
    gbl::writePng((scratch() / "a.png").string(), a);
    gbl::writePng((scratch() / "b.png").string(), b);
}

}  // namespace

// layouts export --out F --force and diff --out F --force replaced a device, a FIFO or a socket
// with a regular file and exited 0 (as root, /dev/full itself).
TEST(Outputs, ANamedOutputNeverReplacesASpecialFile) {
    writeSmallPngs();
    const auto exports = specialFiles("export", ".hlsl");
    ASSERT_GE(exports.size(), 2u);  // the FIFO and the socket at least
    for (const auto& [path, type] : exports) {
        SCOPED_TRACE(path.string());
        for (const std::string force : {"", " --force"}) {
            const RunResult r = run("layouts export ue4 --lang hlsl --out " + path.filename().string() + force);
            expectOneLineError(r, {path.filename().string(), "not a regular file"});
            EXPECT_EQ(typeOf(path), type) << "replaced";
        }
    }
    // A layout whose export writes the best-fit table beside it: the table's path is held to the same.
    const auto tables = specialFiles("table", ".hlsl.bestfit.u32");
    for (const auto& [path, type] : tables) {
        const std::string name = path.filename().string();
        const std::string out = name.substr(0, name.size() - std::string(".bestfit.u32").size());
        const RunResult r = run("layouts export crysis2-slim --lang hlsl --force --out " + out);
        expectOneLineError(r, {name, "not a regular file"});
        EXPECT_EQ(typeOf(path), type);
        EXPECT_FALSE(fs::exists(scratch() / out)) << "half of the output written";
    }
    for (const auto& [path, type] : specialFiles("map", ".png")) {
        SCOPED_TRACE(path.string());
        const RunResult r = run("diff a.png b.png --force --out " + path.filename().string());
        expectOneLineError(r, {path.filename().string(), "not a regular file"});
        EXPECT_EQ(typeOf(path), type) << "replaced";
        EXPECT_TRUE(r.out.empty()) << r.out;
    }
}

// --force lets a command replace the files of a non-empty --out: a device, FIFO or socket in it is
// refused before any work (the writes would refuse it too, at the end).
TEST(Outputs, ForceIntoAFolderHoldingASpecialFileIsRefusedBeforeTheWork) {
    fs::create_directories(scratch() / "used" / "runs");
    { std::ofstream(scratch() / "used" / "notes.txt") << "x"; }
    ASSERT_EQ(::mkfifo((scratch() / "used" / "runs" / "report.json").c_str(), 0600), 0);
    for (const std::string command : {"compare --scene builtin --size 32x32 --layouts ue4", "render --size 32x32", "ibl"}) {
        SCOPED_TRACE(command);
        const RunResult r = run(command + " --out used --force");
        expectOneLineError(r, {"--out used", "report.json", "a FIFO", "not a regular file"});
        EXPECT_EQ(typeOf(scratch() / "used" / "runs" / "report.json"), mode_t(S_IFIFO));
        EXPECT_FALSE(fs::exists(scratch() / "used" / "INCOMPLETE"));
    }
}

// An empty --out named no file: layouts export printed to stdout; it is an error for every command.
TEST(Outputs, AnEmptyOutIsAnError) {
    writeSmallPngs();
    for (const std::string command : {"layouts export ue4 --lang glsl --out ''", "layouts export ue4 --lang glsl --out=",
                                      "diff a.png b.png --out ''", "compare --scene builtin --size 32x32 --layouts ue4 --out ''",
                                      "render --size 32x32 --out ''", "ibl --out ''", "search --budget 12 --out ''"}) {
        SCOPED_TRACE(command);
        const RunResult r = run(command);
        expectOneLineError(r, {"--out ''", "empty"});
        EXPECT_TRUE(r.out.empty()) << r.out.substr(0, 200);
    }
}

// A failed write to stdout (a full disk: /dev/full; a closed stdout) exited 0 with the text lost.
TEST(Outputs, AFailedWriteToStandardOutputIsAnError) {
    writeSmallPngs();
    const std::vector<std::string> commands = {
        "layouts export ue4 --lang hlsl", "layouts glsl ue4", "layouts show ue4", "layouts list",
        "layouts check " + std::string(GBL_SOURCE_LAYOUT_DIR) + "/ue4.toml", "encodings --list",
        "encodings --encoding normal_octahedral --samples 1024 --json", "diff a.png b.png --json", "diff a.png b.png",
        "diff --help", "--help"};
    for (const std::string& command : commands) {
        for (const std::string target : {">/dev/full", ">&-"}) {
            SCOPED_TRACE(command + " " + target);
            const RunResult r = runWithStdout(command, target);
            EXPECT_EQ(r.exitCode, 1) << r.err;
            EXPECT_EQ(lineCount(r.err), 1u) << r.err;
            EXPECT_NE(r.err.find("standard output"), std::string::npos) << r.err;
        }
    }
    // A reader that has gone (a pipe closed before the text was written): EPIPE, not a death by
    // SIGPIPE (exit 141).
    const fs::path err = scratch() / "stderr.txt";
    const std::string piped = "cd " + scratch().string() + " && bash -c '" + GBL_BINARY +
                              " layouts export ue4 --lang hlsl 2>" + err.string() + " | true; exit ${PIPESTATUS[0]}'";
    const int status = std::system(piped.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 1) << slurp(err);
    EXPECT_NE(slurp(err).find("standard output"), std::string::npos) << slurp(err);
    // The same commands into a file: exit 0, the text whole.
    const RunResult ok = runWithStdout("layouts export ue4 --lang hlsl", ">" + (scratch() / "ue4.hlsl").string());
    EXPECT_EQ(ok.exitCode, 0) << ok.err;
    EXPECT_GT(fs::file_size(scratch() / "ue4.hlsl"), 1000u);
}
