#include "search_journal.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <limits>
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

// A whole number of decimal digits only ("12", not "12.0", "+12", " 12", "1e1"), at most `max`.
bool wholeNumber(const std::string& s, int max, int& out) {
    if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos) return false;
    const long v = std::strtol(s.c_str(), nullptr, 10);
    if (v > max) return false;
    out = int(v);
    return true;
}

// Why a journal line is not one this gbufferlab wrote ("" when it is). A resumed search trusts
// every number of the line in place of an evaluation, so each must be one an evaluation can give:
// finite, in its metric's range (FLIP 0..1, an angle 0..180 degrees, every error >= 0, PSNR >= 0),
// and the score the objective's value of them (`objective`: the key's, "" when it names none).
std::string lineProblem(const std::string& line, const std::string& objective, JournalEntry& e) {
    std::vector<std::string> parts;
    std::string part;
    std::istringstream in(line);
    while (std::getline(in, part, '\t')) parts.push_back(part);
    if (parts.size() != 14) return std::to_string(parts.size()) + " columns, not 14";
    if (!wholeNumber(parts[0], 1 << 30, e.index)) return "index " + quoteName(parts[0]) + " is not a whole number";
    if (parts[1].size() != 16 || parts[1].find_first_not_of("0123456789abcdef") != std::string::npos)
        return "hash " + quoteName(parts[1]) + " is not 16 hexadecimal digits";
    e.hash = std::strtoull(parts[1].c_str(), nullptr, 16);
    if (!wholeNumber(parts[2], 1024, e.bytes) || e.bytes < 1)
        return "bytes " + quoteName(parts[2]) + " is not a whole number of bytes per pixel";
    struct Column {
        const char* name;
        double* value;
        double lo, hi;
    };
    constexpr double kInf = std::numeric_limits<double>::infinity();
    const Column columns[] = {{"score", &e.eval.error, -kInf, kInf},
                              {"flip", &e.eval.flip, 0.0, 1.0},
                              {"psnr", &e.eval.psnr, 0.0, kInf},
                              {"attributes", &e.eval.attributes, 0.0, kInf},
                              {"normal", &e.eval.normalDeg, 0.0, 180.0},
                              {"base colour", &e.eval.baseColorDe, 0.0, kInf},
                              {"diffuse colour", &e.eval.diffuseColorDe, 0.0, kInf},
                              {"specular colour", &e.eval.specularColorDe, 0.0, kInf},
                              {"roughness", &e.eval.roughness, 0.0, kInf},
                              {"metallic", &e.eval.metallic, 0.0, kInf},
                              {"occlusion", &e.eval.occlusion, 0.0, kInf}};
    for (size_t k = 0; k < std::size(columns); ++k) {
        const std::string& text = parts[3 + k];
        char* end = nullptr;
        errno = 0;
        const double v = std::strtod(text.c_str(), &end);
        const Column& c = columns[k];
        if (text.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
            return std::string(c.name) + " " + quoteName(text) + " is not a finite number";
        if (v < c.lo || v > c.hi)
            return std::string(c.name) + " " + quoteName(text) + " is outside " +
                   (c.hi == kInf ? "0 and above" : "0 to " + std::string(c.hi == 1.0 ? "1" : "180"));
        *c.value = v;
    }
    // The score is the objective's value of the metrics, bit for bit (fast_eval.cpp, search_metrics.cpp).
    const double expected = objective == "flip"         ? e.eval.flip
                            : objective == "psnr"       ? -e.eval.psnr
                            : objective == "attributes" ? e.eval.attributes
                                                        : e.eval.error;
    if (e.eval.error != expected)
        return "score " + quoteName(parts[3]) + " is not the " + objective + " objective's value of the line's metrics";
    return "";
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
    std::string objective;  // the key's objective=...: the score each line must hold
    for (const auto& [name, value] : keyFields(key))
        if (name == "objective") objective = value;
    if (std::filesystem::exists(path)) {
        const std::string text = readTextFile(path);
        if (text.compare(0, header.size(), header) != 0) throwUserError(headerProblem(path, text, key));
        size_t pos = header.size();
        while (pos < text.size()) {
            const size_t nl = text.find('\n', pos);
            if (nl == std::string::npos) break;  // torn last line: dropped
            JournalEntry e;
            const std::string line = text.substr(pos, nl - pos);
            std::string problem = lineProblem(line, objective, e);
            if (problem.empty() && e.index != int(entries_.size()))
                problem = "index " + std::to_string(e.index) + ", not " + std::to_string(entries_.size());
            if (!problem.empty())
                throwUserError(escapeText(path.string()) + ":" + std::to_string(entries_.size() + 2) +
                               ": malformed journal line (" + problem +
                               "); remove the file to start the search again");
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
