#include "search_front.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "error.h"
#include "file_io.h"
#include "best_fit_normals.h"
#include "json_number.h"
#include "layout_export.h"
#include "layout_packer.h"
#include "search_metrics.h"
#include "shader_compiler.h"

namespace gbl {

namespace fs = std::filesystem;

namespace {

std::string fixed(double v, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%.*f", digits, v);
    return buf;
}

std::string metricsText(const search::Evaluation& e) {
    std::string out;
    for (int m = 0; m < search::kMetricCount; ++m) {
        const search::MetricInfo& info = search::metricInfo(m);
        out += (m ? ", " : "") + std::string(info.label) + " " + fixed(search::metricValue(e, m), info.digits) +
               (info.higherIsBetter ? " dB" : "");
    }
    return out;
}

const SearchRow* namedRow(const std::vector<SearchRow>& rows, const std::string& name) {
    for (const SearchRow& r : rows)
        if (r.name == name) return &r;
    return nullptr;
}

// Both confirmed: the full renders'; else the fast evaluation's, for both.
bool bothFull(const SearchRow& a, const SearchRow& b) { return a.full && b.full; }

}  // namespace

const SearchRow* comparatorFor(int bytes, const std::vector<SearchRow>& rows) {
    int budget = -1;
    for (const SearchRow& r : rows)
        if (!r.found && r.bytes >= bytes && (budget < 0 || r.bytes < budget)) budget = r.bytes;
    if (budget < 0) return nullptr;
    const SearchRow* best = nullptr;
    for (const SearchRow& r : rows)
        if (!r.found && r.bytes <= budget && (!best || r.fast.error < best->fast.error)) best = &r;
    return best;
}

std::vector<SearchRow> writeFront(const search::SearchResult& result, const fs::path& dir, const std::string& commandLine,
                                  const std::string& objective, uint64_t seed, const std::vector<std::string>& constraints,
                                  const std::vector<SearchRow>& published) {
    fs::create_directories(dir);
    // Per byte count (result.front is by bytes, then the objective): the first, and the first no
    // worse than the comparator on any metric.
    std::map<int, std::vector<int>> byBytes;
    for (int i : result.front) byBytes[result.evaluated[size_t(i)].bytes].push_back(i);
    std::vector<SearchRow> rows;
    for (const auto& [bytes, members] : byBytes) {
        const SearchRow* comparator = comparatorFor(bytes, published);
        std::vector<std::pair<int, std::string>> chosen = {{members.front(), ""}};
        auto allRound = [&](int i) {
            const search::Verdict v = search::verdictOf(result.evaluated[size_t(i)].eval, comparator->fast);
            return v == search::Verdict::Beats || v == search::Verdict::Equal;
        };
        if (comparator && !allRound(members.front()))
            for (int i : members)
                if (allRound(i)) {
                    chosen.push_back({i, "-allround"});
                    break;
                }
        for (const auto& [i, suffix] : chosen) {
            const search::Candidate& c = result.evaluated[size_t(i)];
            SearchRow row;
            row.name = "found-" + std::to_string(c.bytes) + "b" + suffix;
            row.found = true;
            row.bytes = c.bytes;
            row.fast = c.eval;
            row.how = c.how;
            row.role = suffix.empty() ? "first of the front's " + std::to_string(bytes) + " B/px layouts by " + objective
                                      : "first of the front's " + std::to_string(bytes) + " B/px layouts by " +
                                            objective + " that is no worse than " + comparator->name + " on any metric";
            if (comparator) row.comparator = comparator->name;
            std::ostringstream comment;
            comment << "Found by `gbufferlab search` (src/search): candidate #" << c.index << " of "
                    << result.evaluated.size() << ", " << c.how << ", seed " << seed << ".\n"
                    << "Command: " << commandLine << "\n"
                    << "On the Pareto front over bytes and every metric; objective " << objective
                    << " (the front's order). This layout: the " << row.role << ".\n"
                    << "Fast evaluation (CPU codec + CPU re-shade, mean over views): " << metricsText(c.eval)
                    << "; score " << fixed(c.eval.error, 6) << ".\n";
            if (comparator)
                comment << "Against " << comparator->name << " (" << comparator->bytes
                        << " B/px, the best published layout at the same or the next larger budget), fast: "
                        << search::verdictName(search::verdictOf(c.eval, comparator->fast))
                        << (search::tradeText(c.eval, comparator->fast).empty()
                                ? std::string()
                                : " (" + search::tradeText(c.eval, comparator->fast) + ")")
                        << ".\n";
            comment << "Engine constraints:\n";
            for (const std::string& line : constraints) comment << "  " << line << "\n";
            comment << c.bytes << " bytes per pixel (targets + depth).\n" << search::describeGenome(c.genome) << ".";
            const fs::path file = dir / (row.name + ".toml");
            const std::string text = search::layoutText(row.name, comment.str(), c.body);
            writeFileAtomic(file, text);
            row.file = file.string();
            // The layout as an engine takes it (layouts export): HLSL and GLSL next to its TOML.
            const Layout layout = parseLayout(text, file.string());
            // The shaders' declarations, read and split once for every front layout and language.
            static const exporting::GlslLibrary library([](const std::string& n) { return resolveShaderInclude(n, {}); });
            for (ExportLanguage lang : {ExportLanguage::Hlsl, ExportLanguage::Glsl}) {
                ExportOptions options;
                options.language = lang;
                const std::string ext = lang == ExportLanguage::Hlsl ? ".hlsl" : ".glsl";
                writeFileAtomic(dir / (row.name + ext), exportLayout(layout, options, library));
                row.exports.push_back(row.name + ext);
            }
            if (exportUsesBestFitTable(layout)) {
                const std::vector<uint32_t>& table = enc::bestFitNormalTable();
                writeFileAtomic(dir / (row.name + ".hlsl.bestfit.u32"), table.data(), table.size() * sizeof(uint32_t));
            }
            rows.push_back(row);
        }
    }
    return rows;
}

namespace {

// Every metric of each split-sum run of one compare report (one scene), by layout; false for a
// metric it lacks (the run is then left out).
void readRunMetrics(const nlohmann::json& report, const std::function<void(const std::string&, const search::Evaluation&)>& take) {
    if (!report.contains("runs") || !report["runs"].is_array()) return;
    for (const auto& run : report["runs"]) {
        if (run.value("ibl_mode", "") != "split-sum" || run.value("status", "") != "ok") continue;
        const auto ie = run.value("image_errors", nlohmann::json::object());
        const auto ae = run.value("attribute_errors", nlohmann::json::object());
        search::Evaluation e;
        bool ok = ie.contains("flip_mean") && readJsonNumber(ie["flip_mean"], e.flip) &&
                  ie.contains("psnr_tonemapped_db") && readJsonNumber(ie["psnr_tonemapped_db"], e.psnr);
        const std::pair<const char*, double*> attributes[] = {
            {"normal", &e.normalDeg},           {"base_color", &e.baseColorDe}, {"diffuse_color", &e.diffuseColorDe},
            {"specular_color", &e.specularColorDe}, {"roughness", &e.roughness},   {"metallic", &e.metallic}};
        for (const auto& [key, out] : attributes) {
            if (!ok) break;
            ok = ae.contains(key) && ae[key].is_object() && ae[key].contains("all") && ae[key]["all"].contains("mean") &&
                 readJsonNumber(ae[key]["all"]["mean"], *out);
        }
        // Reports before occlusion joined the attribute errors lack it: NaN, and the fast value stands in.
        e.occlusion = std::numeric_limits<double>::quiet_NaN();
        if (ae.contains("occlusion") && ae["occlusion"].is_object() && ae["occlusion"].contains("all") &&
            ae["occlusion"]["all"].contains("mean"))
            readJsonNumber(ae["occlusion"]["all"]["mean"], e.occlusion);
        if (ok) take(run.value("layout", ""), e);
    }
}

// The split-sum pair of the two layouts in a significance object's pairs.
void readPair(const nlohmann::json& significance, SearchRow& row) {
    if (!significance.is_object() || !significance.contains("pairs")) return;
    for (const auto& p : significance["pairs"]) {
        const std::string a = p.value("better", ""), b = p.value("worse", "");
        if (p.value("ibl_mode", "split-sum") != "split-sum") continue;
        if (!((a == row.name && b == row.comparator) || (a == row.comparator && b == row.name))) continue;
        double pv = 0.0;
        if (p.contains("p_value") && readJsonNumber(p["p_value"], pv)) {
            row.flipPValue = pv;
            row.flipUnits = p.value("units", 0);
        }
    }
}

}  // namespace

void readFullMetrics(const fs::path& reportJson, std::vector<SearchRow>& rows) {
    const nlohmann::json report = nlohmann::json::parse(readTextFile(reportJson), nullptr, false);
    if (report.is_discarded())
        throwUserError(reportJson.string() + ": not valid JSON; the confirmation failed");
    std::map<std::string, std::vector<search::Evaluation>> byLayout;
    const bool suite = report.value("schema", "") == "gbufferlab-scene-suite" && report.contains("scenes");
    size_t sceneCount = 1;
    auto collect = [&](const std::string& layout, const search::Evaluation& e) { byLayout[layout].push_back(e); };
    if (suite) {
        sceneCount = report["scenes"].size();
        for (const auto& scene : report["scenes"])
            if (scene.contains("report") && scene["report"].is_object()) readRunMetrics(scene["report"], collect);
    } else {
        readRunMetrics(report, collect);
    }
    for (SearchRow& r : rows) {
        const auto it = byLayout.find(r.name);
        if (it == byLayout.end() || it->second.size() != sceneCount) continue;  // measured on every scene only
        search::Evaluation full = search::meanEvaluation(it->second);
        if (std::isnan(full.occlusion)) full.occlusion = r.fast.occlusion;  // an older report: the fast value (the CPU codec is the GPU's, bit for bit)
        full.error = r.fast.error;
        r.full = full;
    }
    const nlohmann::json significance =
        suite ? report.value("significance_across_scenes", nlohmann::json()) : report.value("significance", nlohmann::json());
    for (SearchRow& r : rows)
        if (r.found && !r.comparator.empty()) readPair(significance, r);
}

std::string metricsSection(const SearchSummary& s) {
    std::ostringstream md;
    md << "\n## Every metric\n\n"
       << "The front holds " << s.front.size()
       << " layouts: those no other candidate is at most as costly as and no worse than on every metric (FLIP, "
          "tone-mapped PSNR, normal angle, base, diffuse and specular colour CIEDE2000, roughness, metallic, "
          "occlusion). It is listed and mutated in the order of the objective ("
       << s.objective
       << "). Written to front/: per byte count the first in that order, and the first that is no worse than its "
          "published comparator (the best published layout at the same or the next larger budget) on any metric, "
          "where that is another layout.\n\n"
       << "Values: the full renders' (compare at the same size, views and scenes, exposure 1) where confirmed, else "
          "the fast evaluation's (marked *). "
          "A found layout beats its comparator only when no worse on any metric; otherwise the trade lists each "
          "difference (relative for errors, dB for PSNR). Significance: for FLIP only, the p-value of compare's "
          "paired sign-flip permutation test on 16 x 9 tiles per view; the other metrics have none.\n\n"
       << "Engine constraints (on by default):\n\n";
    for (const std::string& line : s.constraints) md << "- " << line << "\n";
    md << "\n| layout | B/px |";
    for (int m = 0; m < search::kMetricCount; ++m)
        md << " " << search::metricInfo(m).label << (search::metricInfo(m).higherIsBetter ? " dB" : "") << " |";
    md << " vs | verdict | trade | FLIP p |\n|---|---|";
    for (int m = 0; m < search::kMetricCount; ++m) md << "---|";
    md << "---|---|---|---|\n";
    for (const SearchRow& r : s.rows) {
        const search::Evaluation& e = r.full ? *r.full : r.fast;
        md << "| " << r.name << (r.full ? "" : " *") << " | " << r.bytes << " |";
        for (int m = 0; m < search::kMetricCount; ++m)
            md << " " << fixed(search::metricValue(e, m), search::metricInfo(m).digits) << " |";
        const SearchRow* c = r.found ? namedRow(s.rows, r.comparator) : nullptr;
        if (c) {
            const bool full = bothFull(r, *c);
            const search::Evaluation& a = full ? *r.full : r.fast;
            const search::Evaluation& b = full ? *c->full : c->fast;
            md << " " << c->name << " (" << c->bytes << ") | " << search::verdictName(search::verdictOf(a, b))
               << (full ? "" : " *") << " | " << search::tradeText(a, b) << " | "
               << (r.flipPValue ? fixed(*r.flipPValue, 4) : "-") << " |\n";
        } else {
            md << " - | - | - | - |\n";
        }
    }
    return md.str();
}

std::string metricsNote(const SearchSummary& s) {
    std::ostringstream note;
    note << "  front: " << s.front.size()
         << " layouts, over bytes and every metric, under the engine constraints (search-report.md lists them)\n";
    for (const SearchRow& r : s.rows) {
        const SearchRow* c = r.found ? namedRow(s.rows, r.comparator) : nullptr;
        if (!c) continue;
        const bool full = bothFull(r, *c);
        const search::Evaluation& a = full ? *r.full : r.fast;
        const search::Evaluation& b = full ? *c->full : c->fast;
        note << "  " << r.name << " vs " << c->name << " (" << c->bytes
             << " B/px): " << search::verdictName(search::verdictOf(a, b));
        if (!search::tradeText(a, b).empty()) note << " (" << search::tradeText(a, b) << ")";
        if (r.flipPValue) note << "; FLIP difference p = " << fixed(*r.flipPValue, 4);
        note << (full ? " [full renders]" : " [fast evaluation]") << "\n";
    }
    // Per comparator: the byte counts set beside it, and which found layouts beat it.
    struct Group {
        int lo = 1 << 30, hi = 0;
        std::vector<std::string> beating;
        bool full = true;
    };
    std::map<std::string, Group> groups;
    std::vector<std::string> order;
    for (const SearchRow& r : s.rows) {
        const SearchRow* c = r.found ? namedRow(s.rows, r.comparator) : nullptr;
        if (!c) continue;
        if (!groups.count(c->name)) order.push_back(c->name);
        Group& g = groups[c->name];
        g.lo = std::min(g.lo, r.bytes);
        g.hi = std::max(g.hi, r.bytes);
        const bool full = bothFull(r, *c);
        g.full = g.full && full;
        const search::Verdict v = search::verdictOf(full ? *r.full : r.fast, full ? *c->full : c->fast);
        if (v == search::Verdict::Beats || v == search::Verdict::Equal) g.beating.push_back(r.name);
    }
    for (const std::string& name : order) {
        const Group& g = groups[name];
        const SearchRow* c = namedRow(s.rows, name);
        note << "  at " << g.lo << (g.hi > g.lo ? "-" + std::to_string(g.hi) : "") << " B/px: ";
        if (g.beating.empty()) {
            note << "no found layout is no worse than " << name << " (" << c->bytes << " B/px) on every metric";
        } else {
            for (size_t i = 0; i < g.beating.size(); ++i) note << (i ? ", " : "") << g.beating[i];
            note << (g.beating.size() > 1 ? " beat " : " beats ") << name << " (" << c->bytes << " B/px) on every metric";
        }
        note << (g.full ? " (full renders)" : " (fast evaluation)") << "\n";
    }
    return note.str();
}

void addMetricsJson(nlohmann::json& j, const SearchSummary& s) {
    auto metricsJson = [](const search::Evaluation& e) {
        nlohmann::json o = nlohmann::json::object();
        for (int m = 0; m < search::kMetricCount; ++m)
            o[search::metricInfo(m).key] = jsonNumber<nlohmann::json>(search::metricValue(e, m));
        return o;
    };
    j["constraints"] = s.constraints;
    j["front"] = nlohmann::json::array();
    for (const search::Candidate& c : s.front)
        j["front"].push_back(nlohmann::json{{"candidate", c.index},
                                            {"bytes_per_pixel", c.bytes},
                                            {"how", c.how},
                                            {"score", jsonNumber<nlohmann::json>(c.eval.error)},
                                            {"fast", metricsJson(c.eval)}});
    for (auto& o : j["layouts"]) {
        const SearchRow* r = namedRow(s.rows, o.value("name", ""));
        if (!r) continue;
        o["fast_metrics"] = metricsJson(r->fast);
        if (r->full) o["full_metrics"] = metricsJson(*r->full);
        if (!r->found) continue;
        o["role"] = r->role;
        const SearchRow* c = namedRow(s.rows, r->comparator);
        if (!c) continue;
        const bool full = bothFull(*r, *c);
        o["comparator"] = c->name;
        o["verdict"] = search::verdictName(search::verdictOf(full ? *r->full : r->fast, full ? *c->full : c->fast));
        o["verdict_from"] = full ? "full renders" : "fast evaluation";
        o["trade"] = search::tradeText(full ? *r->full : r->fast, full ? *c->full : c->fast);
        if (r->flipPValue) {
            o["flip_p_value"] = jsonNumber<nlohmann::json>(*r->flipPValue);
            o["flip_units"] = r->flipUnits;
        }
    }
}

}  // namespace gbl
