#pragma once
// Folders and files of a test: a fresh folder removed after the test, the scratch folder of a
// test file (one per process, left behind for inspection), whole files read and written.
#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

namespace gbl::test {

// A fresh, empty folder in the system's temporary folder, named `prefix`, this process's id and a
// count, and removed with all it holds when the object goes (unless `keep` was set by then).
struct TempDir {
    std::filesystem::path path;
    bool keep = false;

    explicit TempDir(const std::string& prefix = "gbl_test_");
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    std::filesystem::path operator/(const std::filesystem::path& name) const { return path / name; }
    // The names of the folder's entries, sorted.
    std::vector<std::string> list() const;
};

// A fresh, empty folder for this test process (its pid in the name; emptied when it was there).
std::filesystem::path scratchFolder(const std::string& prefix);

// The scratch folder of one test file, made by scratchFolder(prefix) the first time it is asked
// for (scratch() / "name"), then the same folder for the whole process.
class ScratchDir {
public:
    explicit ScratchDir(std::string prefix) : prefix_(std::move(prefix)) {}
    const std::filesystem::path& operator()() const;
    std::filesystem::path operator/(const std::filesystem::path& name) const { return (*this)() / name; }

private:
    std::string prefix_;
    mutable std::once_flag once_;
    mutable std::filesystem::path path_;
};

// The whole file, byte for byte ("" when it cannot be read).
std::string readFile(const std::filesystem::path& path);
// Writes `bytes` as the whole file.
void writeFile(const std::filesystem::path& path, const std::string& bytes);

}  // namespace gbl::test
