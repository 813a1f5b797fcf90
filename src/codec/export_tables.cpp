// The encodings' tables as select trees for `layouts export` (export_tables.h).
#include "export_tables.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace gbl::exporting {

namespace {

std::string hexWord(uint32_t w) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%08xu", w);
    return buf;
}

std::string uvec4Of(const std::vector<uint32_t>& words, size_t first) {
    std::string s = "uvec4(";
    for (size_t k = 0; k < 4; ++k) s += (k ? ", " : "") + hexWord(first + k < words.size() ? words[first + k] : 0u);
    return s + ")";
}

// The uvec4 `(q's bits) -> words[4q, 4q + 4)` for q in [lo, lo + span), span a power of two: a
// tree of selects on q's bits, most significant first.
std::string selectTree(const std::vector<uint32_t>& words, uint32_t lo, uint32_t span, const std::string& q,
                       const std::string& indent) {
    if (span == 1) return uvec4Of(words, size_t(lo) * 4);
    const uint32_t half = span / 2;
    const std::string inner = indent + "    ";
    return "((" + q + " & " + std::to_string(half) + "u) != 0u\n" + inner + "? " +
           selectTree(words, lo + half, half, q, inner) + "\n" + inner + ": " + selectTree(words, lo, half, q, inner) + ")";
}

uint32_t wordsPowerOfTwo(size_t n) {
    uint32_t p = 1;
    while (p * 4 < n) p *= 2;
    return p;
}

std::vector<uint32_t> bitsOf(const std::vector<float>& values) {
    std::vector<uint32_t> w(values.size());
    for (size_t i = 0; i < values.size(); ++i) std::memcpy(&w[i], &values[i], 4);
    return w;
}

// float NAME(uint i): entry i (i below the table's size).
std::string directFunction(const ConstFloatTable& t) {
    const std::vector<uint32_t> words = bitsOf(t.values);
    std::ostringstream o;
    o << "// " << t.name << "(i): entry i of the table's " << t.values.size()
      << " floats (their bits, 4 to a uvec4, chosen by the bits of i: straight code, no array).\n"
      << "float " << t.name << "(uint i) {\n    uint q = i >> 2u;\n    uvec4 v = "
      << selectTree(words, 0, wordsPowerOfTwo(words.size()), "q", "    ") << ";\n    return uintBitsToFloat(v[i & 3u]);\n}\n";
    return o.str();
}

// float NAME(uint step, uint j): of a 255-entry threshold table, the j-th of the 2^step entries that
// step `step` of the unrolled binary search can read (searchStepEntry). `step` is a constant at
// every call, so each call keeps one branch.
std::string searchFunction(const ConstFloatTable& t) {
    std::ostringstream o;
    o << "// " << t.name << "(step, j): the j-th of the 2^step thresholds that step `step` of the unrolled binary\n"
      << "// search reads: entry j * 2^(8 - step) + 2^(7 - step) - 1 of the table's 255 (their bits).\n"
      << "float " << t.name << "(uint step, uint j) {\n    uint q = j >> 2u;\n    uvec4 v = uvec4(0u);\n";
    for (uint32_t step = 0; step < 8; ++step) {
        std::vector<uint32_t> level;
        for (uint32_t j = 0; j < (1u << step); ++j) {
            uint32_t w;
            std::memcpy(&w, &t.values[searchStepEntry(step, j)], 4);
            level.push_back(w);
        }
        o << "    " << (step ? "else if" : "if") << " (step == " << step << "u) v = "
          << selectTree(level, 0, wordsPowerOfTwo(level.size()), "q", "        ") << ";\n";
    }
    o << "    return uintBitsToFloat(v[j & 3u]);\n}\n";
    return o.str();
}

// The encodings' binary search over a 255-entry table (shaders/scalar_encodings.glsl encodeSrgb8):
// COND reads TABLE[mid].
const std::regex& searchLoop() {
    static const std::regex re(
        R"(uint lo = 0u;\s*uint hi = 255u;\s*for \(int i = 0; i < 8; \+\+i\) \{\s*uint mid = \(lo \+ hi\) >> 1u;\s*)"
        R"(if \(([^\n]*)\) lo = mid \+ 1u; else hi = mid;\s*\})");
    return re;
}

// The loop as 8 steps: the same count (the number of entries for which COND holds, COND monotonic
// over the table as the search requires), each step reading one of the entries it can reach.
std::string unrolledSearch(const std::string& cond, const std::string& table, const std::string& indent) {
    std::string s = "// The binary search over " + table + ", unrolled (export_tables.h: a table lookup per step of\n" +
                    indent + "// the 2^step entries it can reach).\n" + indent + "uint lo = 0u;\n";
    for (uint32_t step = 0; step < 8; ++step) {
        std::string c = cond;
        const std::string use = table + "[mid]";
        const std::string by = table + "(" + std::to_string(step) + "u, lo >> " + std::to_string(8 - step) + "u)";
        for (size_t at = c.find(use); at != std::string::npos; at = c.find(use, at + by.size())) c.replace(at, use.size(), by);
        s += indent + "if (" + c + ") lo += " + std::to_string(128u >> step) + "u;\n";
    }
    s.pop_back();  // the text after the loop supplies the line end
    return s;
}

// `NAME[e]` -> `NAME(e)` in code (brackets matched).
std::string indexToCall(const std::string& code, const std::string& name) {
    std::string out;
    const std::regex use("\\b" + name + "\\s*\\[");
    size_t from = 0;
    for (auto it = std::sregex_iterator(code.begin(), code.end(), use); it != std::sregex_iterator(); ++it) {
        const size_t at = size_t(it->position(0)), open = at + size_t(it->length(0)) - 1;
        if (at < from) continue;
        int depth = 0;
        size_t close = open;
        for (; close < code.size(); ++close) {
            depth += code[close] == '[' ? 1 : code[close] == ']' ? -1 : 0;
            if (depth == 0) break;
        }
        if (close >= code.size()) return code;  // unbalanced: leave as is
        out += code.substr(from, open - from) + "(" + code.substr(open + 1, close - open - 1) + ")";
        from = close + 1;
    }
    return out + code.substr(from);
}

}  // namespace

std::optional<ConstFloatTable> parseConstFloatTable(const std::string& code) {
    static const std::regex decl(R"(^\s*const\s+float\s+(\w+)\s*\[\s*(\d+)\s*\]\s*=\s*float\s*\[\s*\d+\s*\]\s*\(([^()]*)\)\s*;\s*$)");
    std::smatch m;
    if (!std::regex_match(code, m, decl)) return std::nullopt;
    ConstFloatTable t;
    t.name = m[1];
    const std::string list = m[3];
    const char* p = list.c_str();
    while (*p) {
        char* end = nullptr;
        const double v = std::strtod(p, &end);
        if (end == p) return std::nullopt;
        t.values.push_back(float(v));
        p = end;
        while (*p == ' ' || *p == '\n' || *p == '\r' || *p == '\t' || *p == ',') ++p;
    }
    if (t.values.size() != std::stoul(m[2].str())) return std::nullopt;
    return t;
}

void rewriteCodecTables(std::vector<GlslDeclaration>& declarations) {
    std::map<std::string, ConstFloatTable> tables;
    for (const GlslDeclaration& d : declarations)
        if (d.isConstant)
            if (std::optional<ConstFloatTable> t = parseConstFloatTable(d.code)) tables[t->name] = *t;
    // The searches first: a table read by a search (and nowhere else) becomes its per-step form.
    std::map<std::string, int> searched, indexed;
    for (GlslDeclaration& d : declarations) {
        if (d.isConstant || d.isDefine) continue;
        std::smatch m;
        std::string code = d.code;
        while (std::regex_search(code, m, searchLoop())) {
            const std::string cond = m[1];
            std::string table;
            for (const auto& [name, t] : tables)
                if (cond.find(name + "[mid]") != std::string::npos && t.values.size() == 255) table = name;
            if (table.empty()) break;
            const size_t lineStart = code.rfind('\n', size_t(m.position(0)));
            const std::string indent = code.substr(lineStart + 1, size_t(m.position(0)) - lineStart - 1);
            code = m.prefix().str() + unrolledSearch(cond, table, indent) + m.suffix().str();
            ++searched[table];
        }
        d.code = code;
    }
    for (GlslDeclaration& d : declarations) {
        if (d.isConstant || d.isDefine) continue;
        for (const auto& [name, t] : tables)
            if (d.code.find(name) != std::string::npos) {
                const std::string rewritten = indexToCall(d.code, name);
                if (rewritten != d.code) ++indexed[name];
                d.code = rewritten;
            }
    }
    for (GlslDeclaration& d : declarations) {
        if (!d.isConstant) continue;
        const auto t = tables.find(d.name);
        if (t == tables.end()) continue;
        if (searched.count(d.name) && indexed.count(d.name))
            throw std::logic_error("export: " + d.name + " is both searched and indexed; export_tables.cpp writes one form");
        const bool bySearch = searched.count(d.name) > 0;
        d.code = bySearch ? searchFunction(t->second) : directFunction(t->second);
        d.isConstant = false;
    }
    for (GlslDeclaration& d : declarations)
        if (!d.isDefine) {
            d.uses = identifiersOf(d.code);
            d.uses.erase(d.name);
        }
}

}  // namespace gbl::exporting
