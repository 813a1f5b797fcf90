// The encodings' GLSL as a library of declarations, and its HLSL translation (export_glsl_library.h).
#include "export_glsl_library.h"

#include "export_tables.h"

#include <cctype>
#include <map>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace gbl::exporting {

namespace {

enum class TokenKind { Identifier, Number, Comment, Space, Punct };

struct Token {
    TokenKind kind;
    std::string text;
};

bool identStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool identChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

std::vector<Token> tokenize(const std::string& s) {
    std::vector<Token> out;
    size_t i = 0;
    while (i < s.size()) {
        const char c = s[i];
        size_t j = i + 1;
        TokenKind kind = TokenKind::Punct;
        if (c == '/' && i + 1 < s.size() && s[i + 1] == '/') {
            j = s.find('\n', i);
            if (j == std::string::npos) j = s.size();
            kind = TokenKind::Comment;
        } else if (c == '/' && i + 1 < s.size() && s[i + 1] == '*') {
            j = s.find("*/", i + 2);
            j = j == std::string::npos ? s.size() : j + 2;
            kind = TokenKind::Comment;
        } else if (std::isspace(static_cast<unsigned char>(c))) {
            while (j < s.size() && std::isspace(static_cast<unsigned char>(s[j]))) ++j;
            kind = TokenKind::Space;
        } else if (identStart(c)) {
            while (j < s.size() && identChar(s[j])) ++j;
            kind = TokenKind::Identifier;
        } else if (std::isdigit(static_cast<unsigned char>(c)) ||
                   (c == '.' && i + 1 < s.size() && std::isdigit(static_cast<unsigned char>(s[i + 1])))) {
            const bool hex = c == '0' && i + 1 < s.size() && (s[i + 1] == 'x' || s[i + 1] == 'X');
            while (j < s.size() && (identChar(s[j]) || s[j] == '.' ||
                                    (!hex && (s[j] == '+' || s[j] == '-') && (s[j - 1] == 'e' || s[j - 1] == 'E'))))
                ++j;
            kind = TokenKind::Number;
        }
        out.push_back({kind, s.substr(i, j - i)});
        i = j;
    }
    return out;
}

// Index of the token after `i` that is not space or comment (tokens.size() when none).
size_t nextSignificant(const std::vector<Token>& t, size_t i) {
    for (++i; i < t.size(); ++i)
        if (t[i].kind != TokenKind::Space && t[i].kind != TokenKind::Comment) return i;
    return t.size();
}

// The ')' matching the '(' at `open`.
size_t matchingParen(const std::vector<Token>& t, size_t open) {
    int depth = 0;
    for (size_t i = open; i < t.size(); ++i) {
        if (t[i].kind != TokenKind::Punct) continue;
        if (t[i].text == "(") ++depth;
        if (t[i].text == ")" && --depth == 0) return i;
    }
    throw std::logic_error("export: unbalanced parentheses in GLSL");
}

const std::map<std::string, std::string>& hlslNames() {
    static const std::map<std::string, std::string> m = {
        {"vec2", "float2"},   {"vec3", "float3"},   {"vec4", "float4"},   {"uvec2", "uint2"},
        {"uvec3", "uint3"},   {"uvec4", "uint4"},   {"ivec2", "int2"},    {"ivec3", "int3"},
        {"ivec4", "int4"},    {"bvec2", "bool2"},   {"bvec3", "bool3"},   {"bvec4", "bool4"},
        {"floatBitsToUint", "asuint"}, {"floatBitsToInt", "asint"}, {"uintBitsToFloat", "asfloat"},
        {"intBitsToFloat", "asfloat"}, {"fract", "frac"}, {"mix", "lerp"}, {"inversesqrt", "rsqrt"},
        // HLSL's round rounds halfway cases to the nearest even integer, as GLSL's roundEven
        // (unorm_round_even, coat_roughness_bevy: Bevy's WGSL round).
        {"roundEven", "round"},
    };
    return m;
}

bool isVectorType(const std::string& s) {
    static const std::set<std::string> v = {"vec2", "vec3", "vec4", "uvec2", "uvec3", "uvec4",
                                           "ivec2", "ivec3", "ivec4", "bvec2", "bvec3", "bvec4"};
    return v.count(s) > 0;
}

bool isScalarType(const std::string& s) { return s == "float" || s == "uint" || s == "int" || s == "bool"; }

std::string translateTokens(const std::vector<Token>& t, size_t begin, size_t end) {
    std::string out;
    for (size_t i = begin; i < end; ++i) {
        const Token& k = t[i];
        if (k.kind != TokenKind::Identifier) {
            out += k.text;
            continue;
        }
        const auto mapped = hlslNames().find(k.text);
        const std::string name = mapped == hlslNames().end() ? k.text : mapped->second;
        const size_t n = nextSignificant(t, i);
        // T[N](a, b, ...): an array constructor -> { a, b, ... }
        if ((isVectorType(k.text) || isScalarType(k.text)) && n < end && t[n].text == "[") {
            const size_t num = nextSignificant(t, n), close = nextSignificant(t, num), paren = nextSignificant(t, close);
            if (num < end && close < end && paren < end && t[close].text == "]" && t[paren].text == "(") {
                const size_t last = matchingParen(t, paren);
                out += "{" + translateTokens(t, paren + 1, last) + "}";
                i = last;
                continue;
            }
        }
        // vecN(x): a cast in HLSL, which splats a scalar (float3(x) is an error there).
        if (isVectorType(k.text) && n < end && t[n].text == "(") {
            const size_t last = matchingParen(t, n);
            int depth = 0, commas = 0;
            for (size_t j = n + 1; j < last; ++j) {
                if (t[j].kind != TokenKind::Punct) continue;
                if (t[j].text == "(" || t[j].text == "[") ++depth;
                if (t[j].text == ")" || t[j].text == "]") --depth;
                if (t[j].text == "," && depth == 0) ++commas;
            }
            const std::string inner = translateTokens(t, n + 1, last);
            out += commas == 0 ? "((" + name + ")(" + inner + "))" : name + "(" + inner + ")";
            i = last;
            continue;
        }
        out += name;
    }
    return out;
}

// Text without // and /* */ comments (for brace counting and identifiers).
std::string stripComments(const std::string& s) {
    std::string out;
    for (const Token& t : tokenize(s))
        if (t.kind != TokenKind::Comment) out += t.text;
    return out;
}

std::string trim(const std::string& s) {
    const size_t a = s.find_first_not_of(" \t\r\n");
    if (a == std::string::npos) return "";
    const size_t b = s.find_last_not_of(" \t\r\n");
    return s.substr(a, b - a + 1);
}

// GBL_CODEC_TABLE(array, offset, i) -> array[i] (codec_tables.glsl's default).
std::string resolveCodecTables(const std::string& code) {
    static const std::regex re(R"(GBL_CODEC_TABLE\(\s*(\w+)\s*,\s*\w+\s*,\s*([^()]*)\))");
    return std::regex_replace(code, re, "$1[$2]");
}

std::string declaredName(const std::string& code) {
    const std::string c = stripComments(code);
    const size_t stop = c.find_first_of("([=");
    const std::string head = c.substr(0, stop);
    size_t end = head.find_last_not_of(" \t\r\n");
    if (end == std::string::npos) return "";
    size_t begin = end;
    while (begin > 0 && identChar(head[begin - 1])) --begin;
    return head.substr(begin, end - begin + 1);
}

}  // namespace

std::set<std::string> identifiersOf(const std::string& code) {
    std::set<std::string> ids;
    for (const Token& t : tokenize(code))
        if (t.kind == TokenKind::Identifier) ids.insert(t.text);
    return ids;
}

std::string prefixIdentifiers(const std::string& code, const std::set<std::string>& names, const std::string& prefix) {
    std::string out;
    for (const Token& t : tokenize(code)) {
        if (t.kind == TokenKind::Identifier && names.count(t.text)) {
            out += prefix + t.text;
        } else if (t.kind == TokenKind::Comment) {
            // Names in prose as well, so a comment names the function it describes.
            std::string c;
            size_t i = 0;
            while (i < t.text.size()) {
                if (identStart(t.text[i]) && (i == 0 || !identChar(t.text[i - 1]))) {
                    size_t j = i;
                    while (j < t.text.size() && identChar(t.text[j])) ++j;
                    const std::string w = t.text.substr(i, j - i);
                    c += names.count(w) ? prefix + w : w;
                    i = j;
                } else {
                    c += t.text[i++];
                }
            }
            out += c;
        } else {
            out += t.text;
        }
    }
    return out;
}

std::string translateGlslToHlsl(const std::string& code) {
    const std::vector<Token> t = tokenize(code);
    return translateTokens(t, 0, t.size());
}

std::vector<GlslDeclaration> splitGlslDeclarations(const std::string& text) {
    std::vector<GlslDeclaration> out;
    std::istringstream in(text);
    std::string line, comment, pending;
    bool inDecl = false, inResource = false;
    int depth = 0;
    // The declaration gathered in `pending` ends when its braces balance at a ';' or '}'.
    auto closeDeclarationIfComplete = [&] {
        const std::string code = trim(stripComments(pending));
        if (depth != 0 || code.empty() || (code.back() != ';' && code.back() != '}')) return;
        GlslDeclaration d;
        d.code = resolveCodecTables(pending);
        d.comment = comment;
        d.name = declaredName(d.code);
        d.isConstant = code.rfind("const ", 0) == 0;
        d.uses = identifiersOf(stripComments(d.code));
        d.uses.erase(d.name);
        out.push_back(std::move(d));
        comment.clear();
        pending.clear();
        inDecl = false;
    };
    auto depthOf = [](const std::string& l) {
        int d = 0;
        for (char c : stripComments(l)) d += (c == '(' || c == '{') - (c == ')' || c == '}');
        return d;
    };
    while (std::getline(in, line)) {
        const std::string t = trim(line);
        if (inResource) {
            depth += depthOf(line);
            if (depth <= 0 && t.find(';') != std::string::npos) inResource = false;
            continue;
        }
        if (inDecl) {
            pending += line + "\n";
            depth += depthOf(line);
            closeDeclarationIfComplete();
            continue;
        }
        if (t.empty()) {
            comment.clear();
        } else if (t.rfind("//", 0) == 0) {
            comment += line + "\n";
        } else if (t[0] == '#') {
            // Object-like macros with a value are declarations (GBL_BEST_FIT_TABLE_SIZE); include
            // guards, conditionals, #include and function-like macros are not carried over.
            static const std::regex def(R"(#\s*define\s+(\w+)\s+(\S.*))");
            std::smatch m;
            if (std::regex_match(t, m, def)) {
                GlslDeclaration d;
                d.name = m[1];
                d.code = "#define " + d.name + " " + trim(stripComments(m[2])) + "\n";
                d.isDefine = true;
                d.uses = identifiersOf(trim(stripComments(m[2])));
                out.push_back(std::move(d));
            }
        } else if (t.rfind("layout", 0) == 0) {
            inResource = true;
            depth = depthOf(line);
            if (depth <= 0 && t.find(';') != std::string::npos) inResource = false;
        } else {
            inDecl = true;
            pending = line + "\n";
            depth = depthOf(line);
            closeDeclarationIfComplete();  // a declaration on one line
        }
    }
    if (inDecl || inResource) throw std::runtime_error("export: a GLSL declaration is not closed at the end of the file");
    return out;
}

GlslLibrary::GlslLibrary(const ShaderFileReader& read) {
    const std::optional<std::string> top = read("encodings.glsl");
    if (!top) throw std::runtime_error("encodings.glsl: shader file not found (set GBL_SHADER_DIR to the shaders/ directory)");
    static const std::regex inc(R"(#\s*include\s+\"([^\"]+)\")");
    for (auto it = std::sregex_iterator(top->begin(), top->end(), inc); it != std::sregex_iterator(); ++it) {
        const std::string file = (*it)[1];
        const std::optional<std::string> text = read(file);
        if (!text) throw std::runtime_error(file + ": shader file not found (set GBL_SHADER_DIR to the shaders/ directory)");
        for (GlslDeclaration& d : splitGlslDeclarations(*text)) decls_.push_back(std::move(d));
    }
    source_ = decls_;
    rewriteCodecTables(decls_);
}

std::vector<const GlslDeclaration*> GlslLibrary::closure(const std::set<std::string>& roots, ExportTables tables) const {
    const std::vector<GlslDeclaration>& decls = declarations(tables);
    std::set<std::string> names;
    for (const GlslDeclaration& d : decls) names.insert(d.name);
    std::set<std::string> reached, todo;
    for (const std::string& r : roots)
        if (names.count(r)) todo.insert(r);
    while (!todo.empty()) {
        const std::string n = *todo.begin();
        todo.erase(todo.begin());
        if (!reached.insert(n).second) continue;
        for (const GlslDeclaration& d : decls)
            if (d.name == n)
                for (const std::string& u : d.uses)
                    if (!reached.count(u) && names.count(u)) todo.insert(u);
    }
    std::vector<const GlslDeclaration*> out;
    for (const GlslDeclaration& d : decls)
        if (reached.count(d.name)) out.push_back(&d);
    return out;
}

}  // namespace gbl::exporting
