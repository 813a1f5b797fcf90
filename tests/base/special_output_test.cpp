// An output replaces only a regular file (base/file_io.h): every atomic write aimed at a device,
// a FIFO, a socket or a directory, by its name or through a link, is refused in one line and
// leaves it what it was; a regular file, or a path that does not exist, is written as before.
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "error.h"
#include "file_io.h"
#include "temp_dir.h"

namespace gbl {
namespace {

namespace fs = std::filesystem;

const test::ScratchDir scratch("gbl_special_output_test_");

std::string refusal(const std::function<void()>& write) {
    try {
        write();
    } catch (const UserError& e) {
        return e.what();
    }
    return "";
}

// A character device like /dev/full (1, 7), made here: /dev itself is never a target of a test.
// Needs CAP_MKNOD (root); without it the caller skips.
bool makeCharDevice(const fs::path& at) { return ::mknod(at.c_str(), S_IFCHR | 0600, makedev(1, 7)) == 0; }

bool makeSocket(const fs::path& at) {
    const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
    if (fd < 0) return false;
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    if (at.string().size() >= sizeof(addr.sun_path)) return false;
    std::snprintf(addr.sun_path, sizeof(addr.sun_path), "%s", at.c_str());
    const bool ok = ::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof(addr)) == 0;
    ::close(fd);  // the socket file stays
    return ok;
}

void expectRefusedAndKept(const fs::path& path, mode_t type, const std::string& kind) {
    SCOPED_TRACE(path.string());
    for (const auto& write : std::vector<std::function<void()>>{
             [&] { writeFileAtomic(path, std::string("replacement")); },
             [&] { writeViaTemporary(path, [](const fs::path& tmp) { std::ofstream(tmp) << "x"; }); },
             [&] { refuseNonRegularOutput(path, "--out"); }}) {
        const std::string m = refusal(write);
        EXPECT_NE(m.find(path.string()), std::string::npos) << m;
        EXPECT_NE(m.find(kind), std::string::npos) << m;
        EXPECT_NE(m.find("not a regular file"), std::string::npos) << m;
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
        struct stat st {};
        ASSERT_EQ(::lstat(path.c_str(), &st), 0);
        EXPECT_EQ(st.st_mode & S_IFMT, type) << "replaced";
    }
    // No temporary left beside it.
    for (const auto& e : fs::directory_iterator(path.parent_path()))
        EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

TEST(SpecialOutput, AFifoIsNeverReplaced) {
    const fs::path fifo = scratch() / "fifo.hlsl";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    expectRefusedAndKept(fifo, S_IFIFO, "a FIFO");
}

TEST(SpecialOutput, ASocketIsNeverReplaced) {
    const fs::path sock = scratch() / "s.png";
    ASSERT_TRUE(makeSocket(sock));
    expectRefusedAndKept(sock, S_IFSOCK, "a socket");
}

TEST(SpecialOutput, ACharacterDeviceIsNeverReplaced) {
    const fs::path dev = scratch() / "full.json";
    if (!makeCharDevice(dev)) GTEST_SKIP() << "mknod needs CAP_MKNOD";
    expectRefusedAndKept(dev, S_IFCHR, "a character device");
}

TEST(SpecialOutput, ADirectoryOrALinkToAFifoIsNeverReplaced) {
    const fs::path dir = scratch() / "dir.csv";
    fs::create_directories(dir);
    EXPECT_NE(refusal([&] { writeFileAtomic(dir, std::string("x")); }).find("a directory"), std::string::npos);
    EXPECT_TRUE(fs::is_directory(dir));
    const fs::path fifo = scratch() / "target-fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const fs::path link = scratch() / "link.html";
    fs::create_symlink(fifo, link);
    const std::string m = refusal([&] { writeFileAtomic(link, std::string("x")); });
    EXPECT_NE(m.find("a symbolic link to a FIFO"), std::string::npos) << m;
    EXPECT_TRUE(fs::is_symlink(link));
    EXPECT_TRUE(fs::is_fifo(fifo));
}

TEST(SpecialOutput, RegularFilesAndNewPathsAreWrittenAsBefore) {
    const fs::path file = scratch() / "report.json";
    { std::ofstream(file) << "old"; }
    writeFileAtomic(file, std::string("new"));
    std::ifstream in(file);
    std::stringstream ss;
    ss << in.rdbuf();
    EXPECT_EQ(ss.str(), "new");
    const fs::path fresh = scratch() / "fresh.txt";
    writeFileAtomic(fresh, std::string("x"));
    EXPECT_TRUE(fs::is_regular_file(fresh));
    EXPECT_NO_THROW(refuseNonRegularOutput(scratch() / "absent.txt", "--out"));
    EXPECT_NE(refusal([] { checkOutputDirectory("", false, "--out"); }).find("--out '': an empty directory name"),
              std::string::npos);
}

}  // namespace
}  // namespace gbl
