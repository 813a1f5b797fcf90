// Provenance in the layout language (layouts/README.md, "Provenance"): the [sources] table of
// named citations, the `from` / `status` / `differs` keys every entry may carry, and the rules
// that hold them together (a cited key exists, "verified" cites code and "talk" a talk, a layout
// with [sources] gives provenance on every entry). Part of the layout parser
// (layout_parser_detail.h) and of validation.
#include <cctype>

#include "layout_parser_detail.h"

namespace gbl {

namespace {

bool isCitationKey(std::string_view s) {
    return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
    });
}

bool isHex(std::string_view s) {
    return std::all_of(s.begin(), s.end(), [](char c) { return std::isxdigit(static_cast<unsigned char>(c)) != 0; });
}

std::string trimSpaces(std::string_view s) {
    size_t b = 0, e = s.size();
    while (b < e && s[b] == ' ') ++b;
    while (e > b && s[e - 1] == ' ') --e;
    return std::string(s.substr(b, e - b));
}

// "705", "686-705", "12, 40-45": numbers and ascending ranges, comma-separated.
bool isNumberList(std::string_view s) {
    size_t i = 0;
    auto number = [&](long& out) {
        const size_t start = i;
        out = 0;
        while (i < s.size() && s[i] >= '0' && s[i] <= '9') {
            out = out * 10 + (s[i] - '0');
            if (out > 100000000) return false;
            ++i;
        }
        return i > start && out > 0;
    };
    while (true) {
        long a = 0, b = 0;
        if (!number(a)) return false;
        if (i < s.size() && s[i] == '-') {
            ++i;
            if (!number(b) || b < a) return false;
        }
        if (i == s.size()) return true;
        if (s[i] != ',') return false;
        ++i;
        while (i < s.size() && s[i] == ' ') ++i;
    }
}

// A function or type name in the cited file: "EncodeGBuffer", "FSceneTextures::InitializeViewFamily".
bool isSymbol(std::string_view s) {
    if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
    return std::all_of(s.begin(), s.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == ':' || c == '.';
    });
}

}  // namespace

const char* provenanceStatusName(ProvenanceStatus s) {
    switch (s) {
        case ProvenanceStatus::Verified: return "verified";
        case ProvenanceStatus::Talk: return "talk";
        case ProvenanceStatus::Lineage: return "lineage";
        case ProvenanceStatus::Assumed: return "assumed";
        case ProvenanceStatus::Own: return "own";
        case ProvenanceStatus::None: break;
    }
    return "";
}

std::string Citation::text() const {
    std::string s;
    if (kind == CitationKind::Code) {
        // A file: the short pin, then the path; a repository (cited by its files' `in`): the full pin.
        s = path.empty() ? repo + "@" + commit : repo + "@" + commit.substr(0, 8) + " " + path;
    } else {
        s = (authors.empty() ? "" : authors + ": ") + title + ", " + venue;
        if (slide > 0) s += ", slide " + std::to_string(slide);
        if (page > 0) s += ", page " + std::to_string(page);
        if (!url.empty()) s += " (" + url + ")";
    }
    if (!version.empty()) s += " [" + version + "]";
    return s;
}

const Citation* Layout::findCitation(std::string_view key) const {
    for (const Citation& c : citations)
        if (c.key == key) return &c;
    return nullptr;
}

std::vector<ProvenanceEntry> provenanceEntries(const Layout& layout) {
    std::vector<ProvenanceEntry> out;
    if (layout.depth.place.line > 0) out.push_back({"[depth]", &layout.depth.provenance});
    for (const Field& f : layout.depth.stencil)
        out.push_back({"stencil field " + quoteName(attributeName(f.attribute)), &f.provenance});
    for (const Target& t : layout.targets) {
        out.push_back({"target " + quoteName(t.name), &t.provenance});
        for (const Field& f : t.fields)
            out.push_back({"field " + quoteName(attributeName(f.attribute)) + " of target " + quoteName(t.name),
                           &f.provenance});
    }
    if (layout.ids.declared) out.push_back({"[ids]", &layout.ids.provenance});
    for (const LightBuffer& b : layout.lightBuffers)
        out.push_back({"light buffer " + quoteName(b.name), &b.provenance});
    if (layout.materialPass.declared) out.push_back({"[material_pass]", &layout.materialPass.provenance});
    for (const Fallback& f : layout.fallbacks)
        out.push_back({"fallback " + quoteName(attributeName(f.attribute)), &f.provenance});
    for (const ClearValue& c : layout.clears)
        out.push_back({"clear " + quoteName(attributeName(c.attribute)), &c.provenance});
    if (layout.space.declared) out.push_back({"[space]", &layout.space.provenance});
    return out;
}

ProvenanceCounts provenanceCounts(const Layout& layout) {
    ProvenanceCounts c;
    for (const ProvenanceEntry& e : provenanceEntries(layout)) {
        ++c.entries;
        switch (e.provenance->status) {
            case ProvenanceStatus::Verified: ++c.verified; break;
            case ProvenanceStatus::Talk: ++c.talk; break;
            case ProvenanceStatus::Lineage: ++c.lineage; break;
            case ProvenanceStatus::Assumed: ++c.assumed; break;
            case ProvenanceStatus::Own: ++c.own; break;
            case ProvenanceStatus::None: ++c.missing; break;
        }
        if (!e.provenance->differs.empty()) ++c.differs;
    }
    return c;
}

std::string ProvenanceCounts::text() const {
    if (missing == entries) return "none";
    std::string s = "verified " + std::to_string(verified) + "/" + std::to_string(entries);
    auto add = [&](const char* name, int n) {
        if (n > 0) s += std::string(", ") + name + " " + std::to_string(n);
    };
    add("talk", talk);
    add("lineage", lineage);
    add("assumed", assumed);
    add("own", own);
    add("missing", missing);
    add("differs", differs);
    return s;
}

namespace layout_parser {

// [sources]: key = { repo, commit, path [, version] } (code) or { title, venue [, authors, url,
// unit, slide | page, version] } (a talk, paper or article).
void Parser::parseSources(const toml::table& root, Layout& layout) {
    const toml::node* n = root.get("sources");
    if (!n) return;
    layout.sourcesDeclared = true;
    layout.sourcesPlace = placeOf(*n);
    const toml::table* t = n->as_table();
    if (!t) {
        error(placeOf(*n), "'sources' must be a table ([sources]) of named citations, not " + std::string(typeName(*n)));
        return;
    }
    for (auto&& [key, value] : *t) {
        const FilePlace keyPlace = placeOf(key.source());
        const std::string name(key.str());
        if (!isCitationKey(name)) {
            error(keyPlace, "citation name " + squote(name) + " must be lowercase letters, digits, '-' or '_'");
            continue;
        }
        const toml::table* c = value.as_table();
        if (!c) {
            error(placeOf(value), "citation " + squote(name) +
                                      " must be a table: { repo = \"owner/name\", commit = \"...\", path = \"...\" } "
                                      "or { title = \"...\", venue = \"...\" }, not " + std::string(typeName(value)));
            continue;
        }
        const FilePlace at = placeOf(value);
        const std::string where = "citation " + squote(name);
        checkKeys(*c, {"repo", "commit", "path", "in", "version", "title", "authors", "venue", "url", "unit", "slide",
                       "page"},
                  where.c_str());
        Citation cite;
        cite.key = name;
        cite.place = at;
        if (const toml::node* in = c->get("in")) {
            // a file of a repository another citation pins: { in = "ue532", path = "..." }
            cite.kind = CitationKind::Code;
            if (c->get("repo") || c->get("commit"))
                error(placeOf(*in), where + " has 'in' and its own repo or commit: keep one (in = \"key\" takes "
                                            "the repository and commit of that citation)");
            if (auto base = getString(*c, "in", false, at, where)) {
                cite.in = *base;
                cite.inPlace = placeOf(*in);
            }
            if (auto path = getString(*c, "path", true, at, where)) cite.path = *path;
            cite.version = getString(*c, "version", false, at, where).value_or("");
            layout.citations.push_back(std::move(cite));
            continue;
        }
        const bool code = c->get("repo") || c->get("commit") || c->get("path");
        const bool talk = c->get("title") || c->get("venue") || c->get("authors") || c->get("unit") ||
                          c->get("slide") || c->get("page");
        cite.version = getString(*c, "version", false, at, where).value_or("");
        cite.url = getString(*c, "url", false, at, where).value_or("");
        if (code && talk) {
            error(at, where + " mixes code keys (repo, commit, path) with talk keys (title, venue, authors, unit, "
                              "slide, page): cite code and a talk as two citations");
            cite.incomplete = true;  // kept, so that entries citing it are not also "unknown citation"
            layout.citations.push_back(std::move(cite));
            continue;
        }
        if (code) {
            cite.kind = CitationKind::Code;
            if (auto repo = getString(*c, "repo", true, at, where)) {
                const size_t slash = repo->find('/');
                const bool ok = slash != std::string::npos && slash > 0 && slash + 1 < repo->size() &&
                                repo->find('/', slash + 1) == std::string::npos &&
                                std::all_of(repo->begin(), repo->end(), [](char ch) {
                                    return std::isalnum(static_cast<unsigned char>(ch)) || ch == '/' || ch == '-' ||
                                           ch == '_' || ch == '.';
                                });
                if (!ok)
                    error(placeOf(*c->get("repo")),
                          where + ": 'repo' " + squote(*repo) + " must be \"owner/name\" (e.g. \"zeux/niagara\")");
                cite.repo = *repo;
            }
            if (auto commit = getString(*c, "commit", true, at, where)) {
                if (commit->size() < 7 || commit->size() > 40 || !isHex(*commit))
                    error(placeOf(*c->get("commit")), where + ": 'commit' " + squote(*commit) +
                                                          " must be a commit hash, 7 to 40 hexadecimal digits");
                cite.commit = *commit;
            }
            if (auto path = getString(*c, "path", false, at, where)) {  // none: a repository that others cite `in`
                if (path->empty()) error(placeOf(*c->get("path")), where + ": 'path' is empty");
                cite.path = *path;
            }
        } else if (talk || c->get("url")) {
            cite.kind = CitationKind::Talk;
            cite.title = getString(*c, "title", true, at, where).value_or("");
            cite.venue = getString(*c, "venue", true, at, where).value_or("");
            cite.authors = getString(*c, "authors", false, at, where).value_or("");
            if (auto unit = getString(*c, "unit", false, at, where)) {
                if (*unit == "page")
                    cite.pages = true;
                else if (*unit != "slide")
                    error(placeOf(*c->get("unit")),
                          where + ": unknown unit " + squote(*unit) + " (known: slide, page): what its locators count");
            }
            auto readNumber = [&](const char* k, int& v) {
                const toml::node* x = c->get(k);
                if (!x) return;
                auto i = getInteger(*x, where + ": '" + k + "'");
                if (!i) return;
                if (*i < 1 || *i > 100000)
                    error(placeOf(*x), where + ": '" + k + "' " + std::to_string(*i) + " must be 1 or more");
                else
                    v = static_cast<int>(*i);
            };
            readNumber("slide", cite.slide);
            readNumber("page", cite.page);
            if (cite.slide > 0 && cite.page > 0)
                error(placeOf(*c->get("page")), where + " names both a slide and a page: keep the one the talk uses");
        } else {
            error(at, where + " is neither code ({ repo = \"owner/name\", commit = \"...\", path = \"...\" }) nor a "
                              "talk ({ title = \"...\", venue = \"...\" })");
            cite.incomplete = true;
        }
        layout.citations.push_back(std::move(cite));
    }
    std::stable_sort(layout.citations.begin(), layout.citations.end(), [](const Citation& a, const Citation& b) {
        return a.place.line != b.place.line ? a.place.line < b.place.line : a.place.column < b.place.column;
    });
    // `in`: the repository and commit (and version, unless the file names its own) of another citation.
    for (Citation& c : layout.citations) {
        if (c.in.empty()) continue;
        const Citation* base = layout.findCitation(c.in);
        if (base && base->incomplete) {
            c.incomplete = true;
            continue;
        }
        if (!base || base->kind != CitationKind::Code || !base->in.empty() || base->repo.empty()) {
            c.incomplete = true;
            error(c.inPlace, "citation " + squote(c.key) + ": 'in' names " + squote(c.in) +
                                 ", which is not a repository citation of [sources] ({ repo = \"owner/name\", "
                                 "commit = \"...\" })");
            continue;
        }
        c.repo = base->repo;
        c.commit = base->commit;
        if (c.version.empty()) c.version = base->version;
    }
}

// `from`, `status` and `differs` of one entry (its keys are checked by the caller's checkKeys).
// Whether the citations exist and suit the status is validation's (validateProvenance).
void Parser::readProvenance(const toml::table& t, Provenance& p, FilePlace entry) {
    p.place = entry;
    const std::string where = "provenance";
    if (const toml::node* s = t.get("status")) {
        p.statusPlace = placeOf(*s);
        if (auto status = getString(t, "status", false, entry, where)) {
            if (*status == "verified")
                p.status = ProvenanceStatus::Verified;
            else if (*status == "talk")
                p.status = ProvenanceStatus::Talk;
            else if (*status == "lineage")
                p.status = ProvenanceStatus::Lineage;
            else if (*status == "assumed")
                p.status = ProvenanceStatus::Assumed;
            else if (*status == "own")
                p.status = ProvenanceStatus::Own;
            else
                error(p.statusPlace, "unknown status " + squote(*status) +
                                         " (known: verified, read in source code; talk, a talk, paper or article; "
                                         "lineage, read in a later version's code; assumed; own, gbufferlab's own "
                                         "choice)");
        }
    }
    if (const toml::node* f = t.get("from")) {
        p.fromPlace = placeOf(*f);
        if (auto from = getString(t, "from", false, entry, where)) {
            p.from = *from;
            // "key:locator; key:locator": each piece's key is placed in the file for messages
            // (the string's opening quote, then its characters; layout strings hold no escapes).
            size_t start = 0;
            while (start <= from->size()) {
                size_t end = from->find(';', start);
                if (end == std::string::npos) end = from->size();
                const std::string piece = trimSpaces(std::string_view(*from).substr(start, end - start));
                size_t lead = start;
                while (lead < end && (*from)[lead] == ' ') ++lead;
                const FilePlace at{p.fromPlace.line, p.fromPlace.column + 1 + static_cast<int>(lead)};
                if (piece.empty()) {
                    error(at, "empty citation in 'from' " + squote(*from) +
                                  ": write from = \"key:line\", or several as \"key:line; key:line\"");
                } else {
                    const size_t colon = piece.find(':');
                    CitationRef ref;
                    ref.key = trimSpaces(piece.substr(0, colon));
                    ref.locator = colon == std::string::npos ? "" : trimSpaces(piece.substr(colon + 1));
                    ref.place = at;
                    if (colon != std::string::npos && ref.locator.empty())
                        error(at, "citation " + squote(ref.key) + " in 'from' has ':' but no line or slide after it");
                    else
                        p.refs.push_back(std::move(ref));
                }
                start = end + 1;
            }
        }
    }
    if (const toml::node* d = t.get("differs")) {
        if (auto differs = getString(t, "differs", false, entry, where)) {
            if (differs->empty())
                error(placeOf(*d), "'differs' is empty: say how the engine differs, or remove it");
            p.differs = *differs;
        }
    }
}

// A [fallback] or [clear] entry is a value, or a table { value = ..., from, status, differs }
// with its provenance: returns the value's node (nullptr, reported, when the table has none).
const toml::node* Parser::entryValue(const toml::node& node, Provenance& p, const std::string& what) {
    const toml::table* t = node.as_table();
    if (!t) {
        p.place = placeOf(node);
        return &node;
    }
    checkKeys(*t, {"value", "from", "status", "differs"}, what.c_str());
    readProvenance(*t, p, placeOf(node));
    const toml::node* v = t->get("value");
    if (!v) error(placeOf(node), what + " is a table without 'value': write { value = ..., from = \"...\", status = \"...\" }");
    return v;
}

}  // namespace layout_parser

void validateProvenance(const Layout& layout, std::vector<LayoutDiagnostic>& out) {
    using layout_parser::squote;
    auto error = [&](FilePlace place, std::string message) {
        out.push_back({layout.sourceFile, place, std::move(message)});
    };
    std::string known;
    for (const Citation& c : layout.citations) known += (known.empty() ? "" : ", ") + c.key;
    for (const ProvenanceEntry& e : provenanceEntries(layout)) {
        const Provenance& p = *e.provenance;
        // A citation that is wrong itself (reported where it is) or cited wrongly (reported here)
        // makes the status checks below moot: one message per mistake.
        bool citesCode = false, citesTalk = false, refError = false;
        for (const CitationRef& r : p.refs) {
            const Citation* c = layout.findCitation(r.key);
            if (c && c->incomplete) {
                refError = true;
                continue;
            }
            if (!c) {
                refError = true;
                if (!layout.sourcesDeclared)
                    error(r.place, "'from' cites " + squote(r.key) +
                                       " but the layout has no [sources] table: add [sources] with " + r.key +
                                       " = { repo = \"owner/name\", commit = \"...\", path = \"...\" } (or a talk: "
                                       "{ title = \"...\", venue = \"...\" })");
                else
                    error(r.place, "unknown citation " + squote(r.key) + " in 'from' (known: " +
                                       (known.empty() ? std::string("none") : known) + "): add it to [sources]");
                continue;
            }
            if (c->kind == CitationKind::Code) {
                if (c->path.empty()) {
                    error(r.place, "citation " + squote(r.key) + " names a repository, not a file: cite a file of it "
                                                                "({ in = \"" + r.key + "\", path = \"...\" })");
                    refError = true;
                    continue;
                }
                citesCode = true;
                if (!r.locator.empty() && !isNumberList(r.locator) && !isSymbol(r.locator))
                    error(r.place, "locator " + squote(r.locator) + " of " + squote(r.key) +
                                       ": write line numbers (\"705\", \"686-705\", \"12, 40-45\") or a symbol "
                                       "name (EncodeGBuffer)");
            } else {
                citesTalk = true;
                if (!r.locator.empty() && !isNumberList(r.locator))
                    error(r.place, "locator " + squote(r.locator) + " of " + squote(r.key) + ": write " +
                                       (c->pages ? "page" : "slide") + " numbers (\"29\", \"10-13\")");
            }
        }
        if (!p.refs.empty() && p.status == ProvenanceStatus::None && p.statusPlace.line == 0)
            error(p.fromPlace, e.what + " has 'from' but no 'status': add status = \"verified\" (source code), "
                                        "\"talk\" (a talk, paper or article), \"lineage\", \"assumed\" or \"own\"");
        const bool needsCode = p.status == ProvenanceStatus::Verified || p.status == ProvenanceStatus::Lineage;
        if (needsCode && !citesCode && !refError)
            error(p.statusPlace, e.what + " is \"" + provenanceStatusName(p.status) + "\" but 'from' cites no code: " +
                                     (p.refs.empty() ? std::string("add from = \"key:line\" naming the source file in [sources]")
                                                     : std::string("cite the source file (repo, commit, path), or say "
                                                                   "status = \"talk\"")));
        if (p.status == ProvenanceStatus::Talk && !citesTalk && !refError)
            error(p.statusPlace, e.what + " is \"talk\" but 'from' cites no talk: " +
                                     (p.refs.empty() ? std::string("add from = \"key:slide\" naming the talk in [sources]")
                                                     : std::string("cite the talk (title, venue), or say status = "
                                                                   "\"verified\" for code")));
        if (layout.sourcesDeclared && !p.given() && p.refs.empty() && p.statusPlace.line == 0)
            error(p.place.line > 0 ? p.place : FilePlace{1, 1},
                  e.what + " has no provenance: add status = \"verified\", \"talk\", \"lineage\", \"assumed\" or "
                           "\"own\" and "
                           "from = \"key:line\" (a layout with [sources] gives it on every entry)");
    }
}

}  // namespace gbl
