#include "search_journal.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <sstream>
#include <utility>
#include <vector>

#include "disk_cache.h"
#include "error.h"
#include "file_io.h"

namespace gbl::search {

namespace {

constexpr const char* kMagic = "gbufferlab-search-journal 2";
// Version 1 held one error (before the front was over every metric): its searches cannot resume.
constexpr const char* kMagicV1 = "gbufferlab-search-journal 1";

std::string hexFloat(double v) {
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%a", v);
    return buf;
}

bool parseLine(const std::string& line, JournalEntry& e) {
    std::vector<std::string> parts;
    std::string part;
    std::istringstream in(line);
    while (std::getline(in, part, '\t')) parts.push_back(part);
    if (parts.size() != 14) return false;
    char* end = nullptr;
    auto number = [&](const std::string& s, double& out) {
        errno = 0;
        out = std::strtod(s.c_str(), &end);
        return !s.empty() && *end == '\0' && errno == 0;
    };
    double index, bytes;
    if (!number(parts[0], index) || !number(parts[2], bytes)) return false;
    e.index = int(index);
    e.bytes = int(bytes);
    errno = 0;
    e.hash = std::strtoull(parts[1].c_str(), &end, 16);
    if (parts[1].size() != 16 || *end != '\0') return false;
    double* values[] = {&e.eval.error,       &e.eval.flip,        &e.eval.psnr,           &e.eval.attributes,
                        &e.eval.normalDeg,   &e.eval.baseColorDe, &e.eval.diffuseColorDe, &e.eval.specularColorDe,
                        &e.eval.roughness,   &e.eval.metallic,    &e.eval.occlusion};
    for (size_t k = 0; k < std::size(values); ++k)
        if (!number(parts[3 + k], *values[k])) return false;
    return true;
}

// The key's fields ("budget=16 scene=... seed=1") by name.
std::vector<std::pair<std::string, std::string>> keyFields(const std::string& key) {
    std::vector<std::pair<std::string, std::string>> fields;
    std::istringstream in(key);
    std::string word;
    while (in >> word) {
        const size_t eq = word.find('=');
        if (eq != std::string::npos) fields.emplace_back(word.substr(0, eq), word.substr(eq + 1));
        else if (!fields.empty()) fields.back().second += " " + word;  // a value with spaces (a path)
    }
    return fields;
}

// Why the first line is not this search's header, in the words the user can act on.
std::string headerProblem(const std::filesystem::path& path, const std::string& text, const std::string& key) {
    const std::string where = escapeText(path.string()) + ":1: ";
    const std::string restart = "remove the file to start the search again, or give another --out";
    if (text.empty()) return where + "the journal is empty (a search stopped before its first line); " + restart;
    const size_t nl = text.find('\n');
    const std::string line = text.substr(0, nl);
    if (!line.empty() && line.back() == '\r')
        return where + "the journal has Windows line endings (CRLF), which gbufferlab never writes; convert it back "
                       "(e.g. dos2unix) or " + restart;
    if (nl == std::string::npos) return where + "the journal's first line is cut off (no line end); " + restart;
    if (line.compare(0, std::strlen(kMagicV1), kMagicV1) == 0)
        return where + "a journal of an older gbufferlab, whose search judged one error (this one judges every "
                       "metric, under engine constraints); " + restart;
    if (line.compare(0, std::strlen(kMagic), kMagic) != 0 || line.size() <= std::strlen(kMagic) ||
        line[std::strlen(kMagic)] != '\t')
        return where + "not a gbufferlab search journal (it does not start with '" + kMagic + "'); " + restart;
    const auto theirs = keyFields(line.substr(std::strlen(kMagic) + 1)), ours = keyFields(key);
    for (const auto& [name, value] : ours) {
        std::string recorded = "(none)";
        for (const auto& [n, v] : theirs)
            if (n == name) recorded = v;
        if (recorded != value)
            return where + "this journal is of a search with " + name + "=" + escapeText(recorded) + ", not " + name +
                   "=" + escapeText(value) + "; resume with the same arguments, or give another --out";
    }
    return where + "this journal is of a search with other arguments (" + escapeText(line) +
           "); resume with the same arguments, or give another --out";
}

}  // namespace

uint64_t textHash(const std::string& text) {
    Fnv64 f;
    f.bytes(text.data(), text.size());
    return f.h;
}

Journal::Journal(const std::filesystem::path& path, const std::string& key) : path_(path) {
    const std::string header = std::string(kMagic) + "\t" + key + "\n";
    std::string valid = header;
    if (std::filesystem::exists(path)) {
        const std::string text = readTextFile(path);
        if (text.compare(0, header.size(), header) != 0) throwUserError(headerProblem(path, text, key));
        size_t pos = header.size();
        while (pos < text.size()) {
            const size_t nl = text.find('\n', pos);
            if (nl == std::string::npos) break;  // torn last line: dropped
            JournalEntry e;
            const std::string line = text.substr(pos, nl - pos);
            if (!parseLine(line, e) || e.index != int(entries_.size()))
                throwUserError(path.string() + ":" + std::to_string(entries_.size() + 2) +
                               ": malformed journal line; remove the file to start the search again");
            entries_.push_back(e);
            pos = nl + 1;
        }
        valid = text.substr(0, pos);
        if (valid.size() != text.size()) writeFileAtomic(path, valid);  // drop the torn line
    } else {
        writeFileAtomic(path, header);
    }
    fd_ = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
    if (fd_ < 0) throwUserError(path.string() + ": cannot open the search journal: " + std::strerror(errno));
}

Journal::~Journal() {
    if (fd_ >= 0) ::close(fd_);
}

void Journal::append(const JournalEntry& e) {
    char hash[17];
    std::snprintf(hash, sizeof(hash), "%016llx", static_cast<unsigned long long>(e.hash));
    const std::string line = std::to_string(e.index) + "\t" + hash + "\t" + std::to_string(e.bytes) + "\t" +
                             hexFloat(e.eval.error) + "\t" + hexFloat(e.eval.flip) + "\t" + hexFloat(e.eval.psnr) +
                             "\t" + hexFloat(e.eval.attributes) + "\t" + hexFloat(e.eval.normalDeg) + "\t" +
                             hexFloat(e.eval.baseColorDe) + "\t" + hexFloat(e.eval.diffuseColorDe) + "\t" +
                             hexFloat(e.eval.specularColorDe) + "\t" + hexFloat(e.eval.roughness) + "\t" +
                             hexFloat(e.eval.metallic) + "\t" + hexFloat(e.eval.occlusion) + "\n";
    // One write of the whole line (O_APPEND), then fsync: a crash leaves whole lines or a torn last one.
    const ssize_t n = ::write(fd_, line.data(), line.size());
    if (n != ssize_t(line.size()) || ::fsync(fd_) != 0)
        throwUserError(path_.string() + ": cannot append to the search journal: " + std::strerror(errno));
    entries_.push_back(e);
}

}  // namespace gbl::search
