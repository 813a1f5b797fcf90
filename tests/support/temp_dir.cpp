#include "temp_dir.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <fstream>
#include <sstream>

namespace gbl::test {

namespace fs = std::filesystem;

TempDir::TempDir(const std::string& prefix) {
    static std::atomic<unsigned> count{0};
    path = fs::temp_directory_path() / (prefix + std::to_string(::getpid()) + "_" + std::to_string(count++));
    fs::remove_all(path);
    fs::create_directories(path);
}

TempDir::~TempDir() {
    if (keep) return;
    std::error_code ec;
    fs::remove_all(path, ec);
}

std::vector<std::string> TempDir::list() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(path)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

fs::path scratchFolder(const std::string& prefix) {
    const fs::path d = fs::temp_directory_path() / (prefix + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

const fs::path& ScratchDir::operator()() const {
    std::call_once(once_, [this] { path_ = scratchFolder(prefix_); });
    return path_;
}

std::string readFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

void writeFile(const fs::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

}  // namespace gbl::test
