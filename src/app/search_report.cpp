#include "search_report.h"

#include <cmath>
#include <functional>
#include <cstdio>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "error.h"
#include "file_io.h"
#include "json_number.h"
#include "layout_packer.h"
#include "search_front.h"

namespace gbl {

namespace fs = std::filesystem;

namespace {

std::string fixed(double v, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%.*f", digits, v);
    return buf;
}

// The score the goals are judged on: the full render's FLIP when confirmed, else the fast one.
double goalFlip(const SearchRow& r) { return r.fullFlip ? *r.fullFlip : r.fast.flip; }

const SearchRow* best(const std::vector<SearchRow>& rows, bool found, int minBytes, int maxBytes) {
    const SearchRow* b = nullptr;
    for (const SearchRow& r : rows)
        if (r.found == found && r.bytes >= minBytes && r.bytes <= maxBytes && goalFlip(r) >= 0 &&
            (!b || goalFlip(r) < goalFlip(*b)))
            b = &r;
    return b;
}

const SearchRow* named(const std::vector<SearchRow>& rows, const std::string& name) {
    for (const SearchRow& r : rows)
        if (r.name == name) return &r;
    return nullptr;
}

}  // namespace

namespace {

// Each split-sum run's flip_mean of one compare report (the schema of one scene), by layout.
void readRunFlips(const nlohmann::json& report, const std::function<void(const std::string&, double)>& take) {
    for (const auto& run : report["runs"]) {
        if (run.value("ibl_mode", "") != "split-sum" || run.value("status", "") != "ok") continue;
        const auto& ie = run.value("image_errors", nlohmann::json::object());
        double flip = 0.0;
        if (!ie.contains("flip_mean") || !readJsonNumber(ie["flip_mean"], flip)) continue;
        take(run.value("layout", ""), flip);
    }
}

}  // namespace

void readConfirmation(const fs::path& reportJson, std::vector<SearchRow>& rows) {
    const nlohmann::json report = nlohmann::json::parse(readTextFile(reportJson), nullptr, false);
    if (!report.is_discarded() && report.value("schema", "") == "gbufferlab-scene-suite" && report.contains("scenes")) {
        const auto& scenes = report["scenes"];
        for (SearchRow& r : rows) r.fullFlipPerScene.assign(scenes.size(), std::nullopt);
        for (size_t s = 0; s < scenes.size(); ++s) {
            if (!scenes[s].contains("report") || !scenes[s]["report"].is_object()) continue;
            readRunFlips(scenes[s]["report"], [&](const std::string& layout, double flip) {
                for (SearchRow& r : rows)
                    if (r.name == layout) r.fullFlipPerScene[s] = flip;
            });
        }
        for (SearchRow& r : rows) {
            double sum = 0.0;
            int n = 0;
            for (const auto& f : r.fullFlipPerScene)
                if (f) sum += *f, ++n;
            if (n == int(r.fullFlipPerScene.size()) && n > 0) r.fullFlip = sum / n;
        }
        return;
    }
    if (report.is_discarded() || !report.contains("runs"))
        throwUserError(reportJson.string() + ": not a compare report (no runs); the confirmation failed");
    readRunFlips(report, [&](const std::string& layout, double flip) {
        for (SearchRow& r : rows)
            if (r.name == layout) r.fullFlip = flip;
    });
}

std::string writeSearchReport(const SearchSummary& s, const fs::path& dir) {
    std::vector<double> fast, full;
    for (const SearchRow& r : s.rows)
        if (r.fullFlip && r.fast.flip >= 0) {
            fast.push_back(r.fast.flip);
            full.push_back(*r.fullFlip);
        }
    const double rho = fast.size() >= 2 ? search::spearman(fast, full) : std::numeric_limits<double>::quiet_NaN();

    std::ostringstream md;
    md << "# gbufferlab search\n\n`" << s.commandLine << "`\n\n"
       << "Budget " << s.budget << " B/px (targets + depth), objective " << s.objective << ", seed " << s.seed << ", "
       << s.size << ", " << s.views << " view(s). " << s.candidates << " candidates evaluated (" << s.resumed
       << " from the journal), " << fixed(s.perMinute, 0) << " per minute on " << s.threads << " thread(s) ("
       << fixed(s.cpuSecondsPerCandidate, 3) << " CPU s per candidate); "
       << s.counts << ".\n\n"
       << "Fast evaluation: the GPU-decoded reference Surfaces through each layout's CPU codec, re-lit on the "
          "CPU (split-sum IBL + direct lights), tone-mapped, LDR-FLIP against the CPU re-shade of the reference, "
          "full resolution, mean over views. The CPU re-shade of the reference against its GPU render: FLIP "
       << fixed(s.reshadeFlip, 5) << ", mean relative luminance error " << fixed(s.reshadeMeanRelative, 5) << ".\n\n"
       << "| layout | kind | B/px | fast FLIP | full-render FLIP | fast PSNR dB | how | engine code |\n"
          "|---|---|---|---|---|---|---|---|\n";
    for (const SearchRow& r : s.rows) {
        md << "| " << r.name << " | " << (r.found ? "found" : "published") << " | " << r.bytes << " | "
           << (r.fast.flip >= 0 ? fixed(r.fast.flip, 5) : "-") << " | " << (r.fullFlip ? fixed(*r.fullFlip, 5) : "-")
           << " | " << (s.objective == "attributes" ? "-" : fixed(r.fast.psnr, 2)) << " | " << r.how << " | ";
        // The exports lie in front/ beside the TOML (docs/export.md); published layouts: `layouts export NAME`.
        for (size_t i = 0; i < r.exports.size(); ++i)
            md << (i ? ", " : "") << "[" << r.exports[i].substr(r.exports[i].rfind('.') + 1) << "](front/" << r.exports[i] << ")";
        if (r.exports.empty()) md << "-";
        md << " |\n";
    }
    if (!s.sceneNames.empty()) {
        // Several scenes: the values above are means over them; each scene's here.
        md << "\nPer scene (fast FLIP / full-render FLIP; the search minimised their mean):\n\n| layout | B/px |";
        for (const std::string& name : s.sceneNames) md << " " << name << " |";
        md << "\n|---|---|";
        for (size_t i = 0; i < s.sceneNames.size(); ++i) md << "---|";
        md << "\n";
        for (const SearchRow& r : s.rows) {
            md << "| " << r.name << " | " << r.bytes << " |";
            for (size_t i = 0; i < s.sceneNames.size(); ++i) {
                const bool hasFast = i < r.fastPerScene.size() && r.fastPerScene[i].flip >= 0;
                const bool hasFull = i < r.fullFlipPerScene.size() && r.fullFlipPerScene[i];
                md << " " << (hasFast ? fixed(r.fastPerScene[i].flip, 5) : "-") << " / "
                   << (hasFull ? fixed(*r.fullFlipPerScene[i], 5) : "-") << " |";
            }
            md << "\n";
        }
    }

    std::ostringstream note;
    note << "search: closing note\n";
    const SearchRow* thin = named(s.rows, "crysis3-thin");
    const SearchRow* found12 = best(s.rows, true, 0, 12);
    if (thin && found12)
        note << "  12 B/px: " << found12->name << " FLIP " << fixed(goalFlip(*found12), 5) << " vs crysis3-thin "
             << fixed(goalFlip(*thin), 5) << (found12->fullFlip ? " (full renders)" : " (fast evaluation)") << ": "
             << (goalFlip(*found12) < goalFlip(*thin) ? "met" : "NOT met") << "\n";
    else
        note << "  12 B/px: no FLIP of a found layout at or under 12 B/px and of crysis3-thin (none found, or the "
                "objective is not flip and --no-confirm skipped the full renders)\n";
    const SearchRow* pub16 = best(s.rows, false, 16, 16);
    const SearchRow* found16 = best(s.rows, true, 0, 16);
    if (pub16 && found16)
        note << "  16 B/px: " << found16->name << " FLIP " << fixed(goalFlip(*found16), 5)
             << " vs the best published 16 B/px layout, " << pub16->name << " " << fixed(goalFlip(*pub16), 5) << ": "
             << (goalFlip(*found16) <= goalFlip(*pub16) ? "met" : "NOT met") << "\n";
    else
        note << "  16 B/px: no FLIP of a found layout at or under 16 B/px and of a published 16 B/px one (none "
                "found, or the objective is not flip and --no-confirm skipped the full renders)\n";
    note << "  rate: " << fixed(s.perMinute, 0) << " candidates per minute at " << s.size << ", " << s.views
         << " view(s), " << s.threads << " thread(s); " << fixed(s.cpuSecondsPerCandidate, 3)
         << " CPU s per candidate (" << fixed(s.cpuSecondsPerCandidate > 0 ? 60.0 * s.threads / s.cpuSecondsPerCandidate : 0.0, 0)
         << " per minute if the " << s.threads << " thread(s) had their cores to themselves)\n";
    if (!std::isnan(rho))
        note << "  ranking: Spearman rank correlation of fast FLIP and full-render FLIP over " << fast.size()
             << " layouts: " << fixed(rho, 3) << "\n";
    else
        note << "  ranking: not confirmed by full renders (--no-confirm)\n";
    note << metricsNote(s);
    md << metricsSection(s);
    md << "\n```\n" << note.str() << "```\n";
    writeFileAtomic(dir / "search-report.md", md.str());

    nlohmann::json j;
    j["command_line"] = s.commandLine;
    if (!s.sceneNames.empty()) j["scenes"] = s.sceneNames;
    j["budget"] = s.budget;
    j["objective"] = s.objective;
    j["seed"] = s.seed;
    j["candidates"] = s.candidates;
    j["resumed"] = s.resumed;
    j["candidates_per_minute"] = jsonNumber<nlohmann::json>(s.perMinute);
    j["cpu_seconds_per_candidate"] = jsonNumber<nlohmann::json>(s.cpuSecondsPerCandidate);
    j["threads"] = s.threads;
    j["reshade_flip"] = jsonNumber<nlohmann::json>(s.reshadeFlip);
    j["reshade_mean_relative_luminance_error"] = jsonNumber<nlohmann::json>(s.reshadeMeanRelative);
    if (!std::isnan(rho)) j["spearman_fast_vs_full"] = jsonNumber<nlohmann::json>(rho);
    j["layouts"] = nlohmann::json::array();
    for (const SearchRow& r : s.rows) {
        nlohmann::json o{{"name", r.name},
                         {"found", r.found},
                         {"bytes_per_pixel", r.bytes},
                         {"fast_psnr_db", jsonNumber<nlohmann::json>(r.fast.psnr)},
                         {"fast_score", jsonNumber<nlohmann::json>(r.fast.error)},
                         {"how", r.how}};
        if (r.fast.flip >= 0) o["fast_flip"] = jsonNumber<nlohmann::json>(r.fast.flip);
        if (r.fullFlip) o["full_flip"] = jsonNumber<nlohmann::json>(*r.fullFlip);
        if (!r.file.empty()) o["file"] = r.file;
        if (!r.exports.empty()) o["exports"] = r.exports;
        if (!s.sceneNames.empty()) {
            nlohmann::json perScene = nlohmann::json::array();
            for (size_t i = 0; i < s.sceneNames.size(); ++i) {
                nlohmann::json e{{"scene", s.sceneNames[i]}};
                if (i < r.fastPerScene.size()) {
                    e["fast_score"] = jsonNumber<nlohmann::json>(r.fastPerScene[i].error);
                    if (r.fastPerScene[i].flip >= 0) e["fast_flip"] = jsonNumber<nlohmann::json>(r.fastPerScene[i].flip);
                }
                if (i < r.fullFlipPerScene.size() && r.fullFlipPerScene[i])
                    e["full_flip"] = jsonNumber<nlohmann::json>(*r.fullFlipPerScene[i]);
                perScene.push_back(e);
            }
            o["per_scene"] = perScene;
        }
        j["layouts"].push_back(o);
    }
    addMetricsJson(j, s);
    writeFileAtomic(dir / "search.json", j.dump(2) + "\n");
    return note.str();
}

}  // namespace gbl
