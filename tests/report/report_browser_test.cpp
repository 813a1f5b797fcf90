// report.html in a real browser (headless Chromium, offline): it loads without console errors
// or failed image loads, its script sorts the table and switches the plot, and its screenshot
// is a picture, not a blank page. Skipped when /usr/bin/chromium is absent (scripts/setup.sh
// installs it).
//
// How console errors are seen: with --enable-logging=stderr, Chromium prints every console
// message, uncaught exception and failed resource load as a line containing ":CONSOLE" (e.g.
// `[..:INFO:CONSOLE:2] "boom", source: file:///..../t.html (2)`). Chromium 156 logs them all at
// INFO whatever the console level, so the level cannot tell an error from a log: any :CONSOLE
// line (the report itself never logs) or "Uncaught" fails. The CanaryPages test proves that the
// check fires on a deliberate console.error and an uncaught exception, and stays quiet on a clean
// page. A missing image is not logged at all (Chromium 156): report.html marks a broken <img>
// with class "missing" (onerror), which the DOM tests look for.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <map>
#include <cstdlib>
#include <set>
#include <sys/wait.h>
#include <unistd.h>

#include "file_io.h"
#include "image_io.h"
#include "report_html.h"
#include "crowded_report_sample.h"
#include "report_json.h"
#include "report_sample.h"
#include "tone_map.h"
#include "temp_dir.h"

namespace gbl {
namespace {
namespace fs = std::filesystem;

const char* kChromium = "/usr/bin/chromium";

// GBL_KEEP_REPORT keeps the folder, to look at the pages.
struct TempDir : test::TempDir {
    explicit TempDir(const std::string& tag) : test::TempDir("gbl_report_browser_" + tag + "_") {
        keep = std::getenv("GBL_KEEP_REPORT") != nullptr;
    }
};

std::string shellQuote(const std::string& s) {
    std::string out = "'";
    for (char ch : s) out += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
    return out + "'";
}

struct BrowserRun {
    int exitCode = -1;
    std::string stdoutText, stderrText;
    double seconds = 0;
};

// Runs headless Chromium on `url` with a fresh profile; `mode` is "--screenshot=<png>" or "--dump-dom".
BrowserRun runChromium(const fs::path& work, const std::string& url, const std::string& mode,
                       const std::string& windowSize = "1400,1000") {
    static int runs = 0;
    const fs::path profile = work / ("profile" + std::to_string(++runs));
    const fs::path out = work / ("chromium" + std::to_string(runs) + ".out");
    const fs::path err = work / ("chromium" + std::to_string(runs) + ".err");
    fs::create_directories(profile);
    const std::string command =
        "timeout 120 " + std::string(kChromium) +
        " --headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking"
        " --disable-component-update --disable-sync --user-data-dir=" + shellQuote(profile.string()) +
        " --enable-logging=stderr --v=0 " + mode + " --window-size=" + windowSize + " " + shellQuote(url) + " >" +
        shellQuote(out.string()) + " 2>" + shellQuote(err.string()) + " </dev/null";
    const auto start = std::chrono::steady_clock::now();
    const int status = std::system(command.c_str());
    BrowserRun run;
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    run.stdoutText = fs::exists(out) ? readTextFile(out) : "";
    run.stderrText = fs::exists(err) ? readTextFile(err) : "";
    return run;
}

// The lines that mean the page went wrong (see the file comment).
std::vector<std::string> consoleProblems(const std::string& stderrText) {
    std::vector<std::string> problems;
    size_t begin = 0;
    while (begin < stderrText.size()) {
        size_t end = stderrText.find('\n', begin);
        if (end == std::string::npos) end = stderrText.size();
        const std::string line = stderrText.substr(begin, end - begin);
        if (line.find(":CONSOLE") != std::string::npos || line.find("Uncaught") != std::string::npos)
            problems.push_back(line);
        begin = end + 1;
    }
    return problems;
}

std::string joined(const std::vector<std::string>& lines) {
    std::string out;
    for (const std::string& l : lines) out += l + "\n";
    return out;
}

std::string fileUrl(const fs::path& path) { return "file://" + urlPathEscape(fs::absolute(path).string()); }

#define GBL_REQUIRE_CHROMIUM()                                                                         \
    do {                                                                                               \
        if (!fs::exists(kChromium)) GTEST_SKIP() << kChromium << " is absent (scripts/setup.sh installs it)"; \
    } while (0)

TEST(ReportBrowser, CanaryPagesProveTheConsoleCheck) {
    GBL_REQUIRE_CHROMIUM();
    TempDir dir("canary");
    struct Page {
        const char* name;
        const char* body;
        const char* expect;  // a problem line must contain this ("" = no problem expected)
    };
    const Page pages[] = {
        {"clean.html", "<p>fine</p><script>document.body.dataset.ok = '1';</script>", ""},
        {"console_error.html", "<script>console.error('deliberate console error');</script>", "deliberate console error"},
        {"uncaught.html", "<script>undefinedFunction();</script>", "Uncaught ReferenceError"},
    };
    for (const Page& page : pages) {
        SCOPED_TRACE(page.name);
        writeFileAtomic(dir.path / page.name,
                        std::string("<!DOCTYPE html><html><head><meta charset=\"utf-8\"></head><body>") + page.body +
                            "</body></html>");
        const BrowserRun run = runChromium(dir.path, fileUrl(dir.path / page.name), "--dump-dom");
        ASSERT_EQ(run.exitCode, 0) << run.stderrText;
        ASSERT_NE(run.stdoutText.find("</html>"), std::string::npos) << "the page did not load";
        const auto problems = consoleProblems(run.stderrText);
        if (*page.expect == 0) {
            EXPECT_TRUE(problems.empty()) << joined(problems);
        } else {
            ASSERT_FALSE(problems.empty()) << "the check missed it; Chromium's stderr:\n" << run.stderrText;
            EXPECT_NE(joined(problems).find(page.expect), std::string::npos) << joined(problems);
        }
    }
}

// The sample report, with every image it names, in `dir`.
fs::path writeSampleReport(const fs::path& dir) {
    const ReportModel model = test::sampleReport();
    test::writeSampleImages(dir, model);
    writeReport(dir, model);
    return dir / "report.html";
}

TEST(ReportBrowser, ScreenshotHasNoConsoleErrorsAndIsNotBlank) {
    GBL_REQUIRE_CHROMIUM();
    TempDir dir("shot");
    const fs::path html = writeSampleReport(dir.path / "report dir");  // a space: URLs are escaped
    const fs::path png = dir.path / "screenshot.png";
    const BrowserRun run = runChromium(dir.path, fileUrl(html), "--screenshot=" + shellQuote(png.string()));
    std::printf("[ info ] chromium screenshot run: %.2f s\n", run.seconds);
    ASSERT_EQ(run.exitCode, 0) << run.stderrText;
    EXPECT_TRUE(consoleProblems(run.stderrText).empty()) << joined(consoleProblems(run.stderrText));
    ASSERT_TRUE(fs::exists(png)) << run.stderrText;
    const Image8 shot = readImage8(png.string());
    EXPECT_EQ(shot.width, 1400);
    EXPECT_EQ(shot.height, 1000);
    ASSERT_GE(shot.channels, 3);
    // Not blank: the luminance varies and there are many colours (text, table stripes, images).
    double sum = 0, sumSquares = 0;
    std::set<uint32_t> colors;
    const size_t pixels = size_t(shot.width) * size_t(shot.height);
    for (size_t i = 0; i < pixels; ++i) {
        const unsigned char* p = &shot.pixels[i * size_t(shot.channels)];
        const double luma = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
        sum += luma;
        sumSquares += luma * luma;
        colors.insert(uint32_t(p[0]) << 16 | uint32_t(p[1]) << 8 | p[2]);
    }
    const double mean = sum / double(pixels), variance = sumSquares / double(pixels) - mean * mean;
    std::printf("[ info ] screenshot: mean luma %.1f, variance %.1f, %zu distinct colours\n", mean, variance,
                colors.size());
    EXPECT_GT(variance, 100.0);
    EXPECT_GT(colors.size(), 50u);
    EXPECT_GT(mean, 128.0);  // dark on light
}

// Extracts, in document order, the layout names of the table's rows from a dumped DOM.
std::vector<std::string> tableOrder(const std::string& dom) {
    std::vector<std::string> names;
    const size_t body = dom.find("<tbody>", dom.find("id=\"layouts\""));
    const size_t end = dom.find("</tbody>", body);
    for (size_t at = dom.find("<tr", body); at < end; at = dom.find("<tr", at + 1)) {
        const size_t a = dom.find("<a href=\"#", at);
        const size_t open = dom.find('>', a) + 1;
        const size_t ibl = dom.find("<td>", open) + 4;
        names.push_back(dom.substr(open, dom.find("</a>", open) - open) + "/" +
                        dom.substr(ibl, dom.find("</td>", ibl) - ibl));
    }
    return names;
}

TEST(ReportBrowser, ScriptSortsTheTableAndSwitchesThePlot) {
    GBL_REQUIRE_CHROMIUM();
    TempDir dir("dom");
    const fs::path html = writeSampleReport(dir.path / "report");
    const BrowserRun plain = runChromium(dir.path, fileUrl(html), "--dump-dom");
    ASSERT_EQ(plain.exitCode, 0) << plain.stderrText;
    EXPECT_TRUE(consoleProblems(plain.stderrText).empty()) << joined(consoleProblems(plain.stderrText));
    EXPECT_NE(plain.stdoutText.find("data-script=\"ready\""), std::string::npos) << "the script did not finish";
    EXPECT_EQ(plain.stdoutText.find("class=\"missing\""), std::string::npos) << "an image failed to load";
    const std::vector<std::string> original = {"ue4/split-sum",  "compact-octahedral/split-sum",
                                               "fat-naive/split-sum", "ryse/split-sum",
                                               "ue4/none",       "compact-octahedral/none",
                                               "broken&lt;layout&gt;/split-sum"};
    EXPECT_EQ(tableOrder(plain.stdoutText), original);

    // PSNR, best first: ∞ above every number; the failed run (no value) last.
    const BrowserRun psnr = runChromium(dir.path, fileUrl(html) + "#sort=psnr:desc&plot=psnr", "--dump-dom");
    ASSERT_EQ(psnr.exitCode, 0) << psnr.stderrText;
    EXPECT_TRUE(consoleProblems(psnr.stderrText).empty()) << joined(consoleProblems(psnr.stderrText));
    EXPECT_EQ(tableOrder(psnr.stdoutText),
              (std::vector<std::string>{"fat-naive/split-sum", "ue4/none", "ue4/split-sum", "compact-octahedral/none",
                                        "compact-octahedral/split-sum", "ryse/split-sum",
                                        "broken&lt;layout&gt;/split-sum"}));
    EXPECT_NE(psnr.stdoutText.find("data-key=\"psnr\" data-dir=\"descending\" title="), std::string::npos);
    EXPECT_NE(psnr.stdoutText.find("aria-sort=\"descending\""), std::string::npos);
    // The plot switched: the PSNR figure shown, the FLIP one hidden.
    EXPECT_NE(psnr.stdoutText.find("<figure class=\"plot\" id=\"plot-psnr\">"), std::string::npos);
    EXPECT_NE(psnr.stdoutText.find("<figure class=\"plot\" id=\"plot-flip\" hidden=\"\">"), std::string::npos);

    // Ascending: numbers sort as numbers (12 < 16 < 20 < 44, not as text), the failed run still last...
    const BrowserRun bytes = runChromium(dir.path, fileUrl(html) + "#sort=bpp:asc", "--dump-dom");
    ASSERT_EQ(bytes.exitCode, 0) << bytes.stderrText;
    const auto byBytes = tableOrder(bytes.stdoutText);
    ASSERT_EQ(byBytes.size(), 7u);
    EXPECT_EQ(byBytes[0].rfind("compact-octahedral/", 0), 0u);
    EXPECT_EQ(byBytes[2], "ryse/split-sum");
    EXPECT_EQ(byBytes[5], "broken&lt;layout&gt;/split-sum");  // 28 B/px: failed, but its size is known
    EXPECT_EQ(byBytes[6], "fat-naive/split-sum");
    // ...and by FLIP ascending, the failed run (no value) stays last.
    const BrowserRun flip = runChromium(dir.path, fileUrl(html) + "#sort=flip:asc", "--dump-dom");
    const auto byFlip = tableOrder(flip.stdoutText);
    ASSERT_EQ(byFlip.size(), 7u);
    EXPECT_EQ(byFlip[0], "fat-naive/split-sum");
    EXPECT_EQ(byFlip[6], "broken&lt;layout&gt;/split-sum");
}

// The A/B viewer driven by real DOM events (dispatched by a script appended to a copy of the
// page, run on load; its findings are written into the DOM that --dump-dom returns): Space, the
// button and a click on the image flip; the wheel zooms to 64 screen pixels per image pixel,
// with the pixel read-out under the pointer right; a drag pans without flipping; arrow keys pan;
// the exposure slider switches both images to the log preview through the filter whose table is
// the report's tone map at that exposure.
const char* kViewerDriver = R"JS(
<script>
window.addEventListener('load', function () {
  var out = [];
  function note(k, v) { out.push(k + '=' + v); }
  try {
    var ab = document.querySelector('.ab'), view = ab.querySelector('.ab-view');
    var imgs = ab.querySelectorAll('.ab-stage img'), stage = ab.querySelector('.ab-stage');
    function key(k) { ab.dispatchEvent(new KeyboardEvent('keydown', { key: k, bubbles: true, cancelable: true })); }
    function ptr(type, x, y) {
      var r = view.getBoundingClientRect();
      view.dispatchEvent(new PointerEvent(type, { clientX: r.left + x, clientY: r.top + y, bubbles: true, pointerId: 1 }));
    }
    note('ready', ab.getAttribute('data-viewer'));
    note('start', ab.getAttribute('data-showing'));
    note('both_in_stage', imgs.length === 2 && imgs[0].parentNode === stage && imgs[1].parentNode === stage);
    key(' ');
    note('space', ab.getAttribute('data-showing') + '/' + imgs[0].hidden + '/' + imgs[1].hidden);
    ab.querySelector('.ab-flip').click();
    note('button', ab.getAttribute('data-showing'));
    ptr('pointerdown', 40, 40); ptr('pointerup', 40, 40);
    note('imageclick', ab.getAttribute('data-showing'));
    key('F');
    note('fkey', ab.getAttribute('data-showing'));
    key('0');
    note('fit', ab.getAttribute('data-zoom'));
    for (var i = 0; i < 12; i++) {
      var r = view.getBoundingClientRect();
      view.dispatchEvent(new WheelEvent('wheel', { deltaY: -240, clientX: r.left + 10, clientY: r.top + 10,
                                                   bubbles: true, cancelable: true }));
    }
    note('zoom', ab.getAttribute('data-zoom'));
    var pan = ab.getAttribute('data-pan').split(',').map(Number);
    ptr('pointermove', pan[0] + 64 * 3 + 5, pan[1] + 64 * 2 + 5);
    note('pixel', ab.querySelector('.ab-pixel').textContent);
    note('pan0', pan.join(','));
    ptr('pointerdown', 300, 200); ptr('pointermove', 360, 230); ptr('pointerup', 360, 230);
    note('pan1', ab.getAttribute('data-pan'));
    note('afterdrag', ab.getAttribute('data-showing'));
    key('ArrowLeft');
    note('pan2', ab.getAttribute('data-pan'));
    note('same_transform', stage.style.transform.indexOf('scale(64)') >= 0);
    var ev = ab.querySelector('.ab-ev');
    ev.value = '2'; ev.dispatchEvent(new Event('input', { bubbles: true }));
    note('ev', ab.getAttribute('data-ev') + '/' + ab.getAttribute('data-hdr'));
    note('src', imgs[0].getAttribute('src') + '|' + imgs[1].getAttribute('src'));
    note('filter', imgs[1].style.filter.indexOf('abf-') >= 0);
    note('table', ab.querySelector('feFuncG').getAttribute('tableValues').split(' ').length + ':' +
                  ab.querySelector('feFuncG').getAttribute('tableValues').split(' ')[64]);
    ev.value = '0'; ev.dispatchEvent(new Event('input', { bubbles: true }));
    note('ev0', ab.getAttribute('data-hdr') + '/' + imgs[0].getAttribute('src'));
  } catch (e) { note('exception', e.message); }
  document.body.setAttribute('data-abtest', out.join(';'));
});
</script>
)JS";

std::map<std::string, std::string> viewerFindings(const std::string& dom) {
    std::map<std::string, std::string> found;
    const size_t at = dom.find("data-abtest=\"");
    if (at == std::string::npos) return found;
    const size_t begin = at + 13, end = dom.find('"', begin);
    std::string text = dom.substr(begin, end - begin);
    size_t pos = 0;
    while (pos < text.size()) {
        size_t semi = text.find(';', pos);
        if (semi == std::string::npos) semi = text.size();
        const std::string item = text.substr(pos, semi - pos);
        const size_t eq = item.find('=');
        if (eq != std::string::npos) found[item.substr(0, eq)] = item.substr(eq + 1);
        pos = semi + 1;
    }
    return found;
}

TEST(ReportBrowser, AbViewerFlipsZoomsPansAndExposes) {
    GBL_REQUIRE_CHROMIUM();
    TempDir dir("ab");
    const fs::path html = writeSampleReport(dir.path / "report");
    std::string page = readTextFile(html);
    const size_t body = page.rfind("</body>");
    ASSERT_NE(body, std::string::npos);
    page.insert(body, kViewerDriver);
    const fs::path driven = dir.path / "report" / "driven.html";
    writeFileAtomic(driven, page);
    const BrowserRun run = runChromium(dir.path, fileUrl(driven), "--dump-dom");
    ASSERT_EQ(run.exitCode, 0) << run.stderrText;
    EXPECT_TRUE(consoleProblems(run.stderrText).empty()) << joined(consoleProblems(run.stderrText));
    auto f = viewerFindings(run.stdoutText);
    ASSERT_FALSE(f.empty()) << "the driver did not run";
    EXPECT_EQ(f.count("exception"), 0u) << f["exception"];
    EXPECT_EQ(f["ready"], "ready");
    EXPECT_EQ(f["start"], "reference");
    EXPECT_EQ(f["both_in_stage"], "true");
    EXPECT_EQ(f["space"], "layout/true/false");
    EXPECT_EQ(f["button"], "reference");
    EXPECT_EQ(f["imageclick"], "layout");
    EXPECT_EQ(f["fkey"], "reference");
    EXPECT_GT(std::stod(f["fit"]), 1.0);  // 64x36 sample images fill the view
    EXPECT_EQ(f["zoom"], "64");           // clamped at 64 screen pixels per image pixel
    // The read-out names the image pixel under the pointer (5 screen pixels into image pixel 3, 2).
    const double tx = std::stod(f["pan0"]), ty = std::stod(f["pan0"].substr(f["pan0"].find(',') + 1));
    EXPECT_EQ(f["pixel"], "pixel 3, 2") << "pan " << f["pan0"];
    const double tx1 = std::stod(f["pan1"]), ty1 = std::stod(f["pan1"].substr(f["pan1"].find(',') + 1));
    EXPECT_NEAR(tx1 - tx, 60.0, 0.11);
    EXPECT_NEAR(ty1 - ty, 30.0, 0.11);
    EXPECT_EQ(f["afterdrag"], "reference") << "a drag must not flip";
    EXPECT_NEAR(std::stod(f["pan2"]) - tx1, 32.0, 0.11);
    EXPECT_EQ(f["same_transform"], "true");
    EXPECT_EQ(f["ev"], "2/log-preview");
    EXPECT_EQ(f["src"], "reference/split-sum/log.png|runs/ue4-split-sum/render_log.png");
    EXPECT_EQ(f["filter"], "true");
    // Entry 64 of the table: log2 x = lo + (hi - lo) 64 / 255, times exposure 1 x 2^2, through
    // the report's tone map (C++, tone_map.h).
    const double x = std::exp2(kPreviewLog2Min + (kPreviewLog2Max - kPreviewLog2Min) * 64.0 / 255.0) * 4.0;
    const double expected = linearToSrgb(acesFilmNarkowicz(float(x)));
    const std::string table = f["table"];
    ASSERT_EQ(table.substr(0, 4), "256:");
    EXPECT_NEAR(std::stod(table.substr(4)), expected, 2e-5);
    EXPECT_EQ(f["ev0"], "png/reference/split-sum/render.png");
}

// The page at a glance, at 1600x1000 as the issue measured it, on a report crowded like a real
// one (crowded_report_sample.h). A script appended to a copy of the page measures, on load, what
// the browser drew: every label's and marker's box in each of the three plots, the table's width
// folded and with all columns, the verdict's lines, and what pointing at a marker shows; its
// findings come back as JSON in an attribute of the dumped DOM.
const char* kGlanceDriver = R"JS(
<script>
window.addEventListener('load', function () {
  var f = {};
  function hit(a, b) { return a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom; }
  function rects(list) { return Array.prototype.map.call(list, function (e) { return e.getBoundingClientRect(); }); }
  try {
    var root = document.documentElement, table = document.getElementById('layouts');
    f.innerWidth = window.innerWidth;
    f.viewport = root.clientWidth;
    f.scrollWidth = root.scrollWidth;
    f.tableRight = table.getBoundingClientRect().right;
    f.tableWidth = table.getBoundingClientRect().width;
    f.columnsShown = Array.prototype.filter.call(table.tHead.rows[1].cells, function (c) { return c.offsetWidth > 0; }).length;
    var all = document.getElementById('all-columns');
    all.checked = true;
    f.allTableWidth = table.getBoundingClientRect().width;
    f.allScrollWidth = root.scrollWidth;
    f.allColumnsShown = Array.prototype.filter.call(table.tHead.rows[1].cells, function (c) { return c.offsetWidth > 0; }).length;
    all.checked = false;
    f.verdict = Array.prototype.map.call(document.querySelectorAll('#verdict li'), function (li) { return li.textContent; });
    f.plots = {};
    var figures = document.querySelectorAll('figure.plot');
    Array.prototype.forEach.call(figures, function (figure) {
      Array.prototype.forEach.call(figures, function (other) { other.hidden = other !== figure; });
      var labels = figure.querySelectorAll('text.label'), names = Array.prototype.map.call(labels, function (l) { return l.textContent; });
      var boxes = rects(labels), markers = rects(figure.querySelectorAll('a.pt > circle, a.pt > polygon'));
      var p = { labels: boxes.length, markers: markers.length, leaders: figure.querySelectorAll('line.leader').length,
                labelOverlaps: [], markerOverlaps: [], empty: 0, widthError: 0 };
      for (var i = 0; i < boxes.length; i++) {
        if (!(boxes[i].width > 0 && boxes[i].height > 0)) p.empty++;
        var pinned = Number(labels[i].getAttribute('textLength'));
        p.widthError = Math.max(p.widthError, Math.abs(boxes[i].width - pinned));
        for (var j = i + 1; j < boxes.length; j++)
          if (hit(boxes[i], boxes[j])) p.labelOverlaps.push(names[i] + ' / ' + names[j]);
        for (var k = 0; k < markers.length; k++)
          if (hit(boxes[i], markers[k])) p.markerOverlaps.push(names[i] + ' / marker ' + k);
      }
      f.plots[figure.id] = p;
    });
    Array.prototype.forEach.call(figures, function (other) { other.hidden = other.id !== 'plot-flip'; });
    var flip = document.getElementById('plot-flip'), point = flip.querySelector('a.pt[href="#run-visibility-32-split-sum"]');
    point.firstElementChild.dispatchEvent(new MouseEvent('mouseover', { bubbles: true }));
    f.readout = flip.querySelector('.plot-readout').textContent;
    f.info = point.getAttribute('data-info');
    f.hot = Array.prototype.map.call(flip.querySelectorAll('text.label.hot'), function (l) { return l.textContent; });
  } catch (e) { f.exception = e.message; }
  document.body.setAttribute('data-findings', encodeURIComponent(JSON.stringify(f)));
});
</script>
)JS";

std::string percentDecoded(const std::string& text) {
    std::string out;
    for (size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '%' && i + 2 < text.size()) {
            out += char(std::stoi(text.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += text[i];
        }
    }
    return out;
}

TEST(ReportBrowser, AtAGlanceAt1600LabelsApartTableFitsVerdictIsReportJsons) {
    GBL_REQUIRE_CHROMIUM();
    TempDir dir("glance");
    const fs::path reportDir = dir.path / "report";
    const ReportModel model = test::crowdedReport();
    test::writeSampleImages(reportDir, model);
    writeReport(reportDir, model);
    std::string page = readTextFile(reportDir / "report.html");
    page.insert(page.rfind("</body>"), kGlanceDriver);
    writeFileAtomic(reportDir / "driven.html", page);
    const BrowserRun run = runChromium(dir.path, fileUrl(reportDir / "driven.html"), "--dump-dom", "1600,1000");
    ASSERT_EQ(run.exitCode, 0) << run.stderrText;
    EXPECT_TRUE(consoleProblems(run.stderrText).empty()) << joined(consoleProblems(run.stderrText));
    const size_t at = run.stdoutText.find("data-findings=\"");
    ASSERT_NE(at, std::string::npos) << "the driver did not run";
    const size_t begin = at + 15;
    const auto f = nlohmann::json::parse(percentDecoded(run.stdoutText.substr(begin, run.stdoutText.find('"', begin) - begin)));
    ASSERT_FALSE(f.contains("exception")) << f["exception"];
    std::printf("[ info ] at 1600 px: table %.1f px in a %d px viewport (all columns %.1f px), page %d px wide\n",
                f["tableWidth"].get<double>(), f["viewport"].get<int>(), f["allTableWidth"].get<double>(),
                f["scrollWidth"].get<int>());
    ASSERT_EQ(f["innerWidth"], 1600);

    // The table fits the window, folded (the default) and with every column shown.
    const double viewport = f["viewport"].get<double>();
    EXPECT_LE(f["tableRight"].get<double>(), viewport);
    EXPECT_LE(f["scrollWidth"].get<double>(), viewport) << "the page scrolls sideways";
    EXPECT_LE(f["allTableWidth"].get<double>(), viewport);
    EXPECT_LE(f["allScrollWidth"].get<double>(), viewport);
    EXPECT_EQ(f["columnsShown"], 11);     // layout, IBL, 9 numeric columns less the normal p99, status
    EXPECT_EQ(f["allColumnsShown"], 12);  // the p99 unfolded

    // No two labels and no label and marker intersect, in any plot. 19 layouts, two of them
    // visibility buffers with a second marker each; the crowd needs leader lines.
    for (const char* id : {"plot-flip", "plot-flip-linear", "plot-psnr"}) {
        SCOPED_TRACE(id);
        const auto& p = f["plots"][id];
        EXPECT_EQ(p["labels"], 21);
        EXPECT_EQ(p["markers"], 21);
        EXPECT_EQ(p["empty"], 0) << "a label was not drawn";
        EXPECT_LT(p["widthError"].get<double>(), 1.0) << "a label is not as wide as it was placed";
        EXPECT_TRUE(p["labelOverlaps"].empty()) << p["labelOverlaps"].dump();
        EXPECT_TRUE(p["markerOverlaps"].empty()) << p["markerOverlaps"].dump();
    }
    EXPECT_GT(f["plots"]["plot-flip"]["leaders"].get<int>(), 0);

    // The verdict's lines are report.json's, in order.
    const auto json = nlohmann::json::parse(readTextFile(reportDir / "report.json"));
    std::vector<std::string> expected;
    for (const auto& b : json["verdict"]["budgets"]) expected.push_back(b["sentence"]);
    EXPECT_EQ(f["verdict"].get<std::vector<std::string>>(), expected);
    EXPECT_EQ(expected.size(), 6u);

    // Pointing at a marker names it under the plot and marks its labels.
    EXPECT_EQ(f["readout"], f["info"]);
    EXPECT_EQ(f["info"].get<std::string>().rfind("visibility-32 (IBL split-sum): 8 B/px", 0), 0u) << f["info"];
    EXPECT_EQ(f["hot"], nlohmann::json({"visibility-32", "visibility-32 + fetches"}));
}

TEST(ReportBrowser, MissingImageIsReported) {
    GBL_REQUIRE_CHROMIUM();
    TempDir dir("missing");
    const fs::path html = writeSampleReport(dir.path / "report");
    fs::remove(dir.path / "report" / "runs" / "ue4-none" / "flip.png");
    const BrowserRun run = runChromium(dir.path, fileUrl(html), "--dump-dom");
    ASSERT_EQ(run.exitCode, 0) << run.stderrText;
    // Chromium 156 does not log a failed image load to the console; the page's onerror marks it.
    const size_t img = run.stdoutText.find("src=\"runs/ue4-none/flip.png\"");
    ASSERT_NE(img, std::string::npos);
    EXPECT_NE(run.stdoutText.substr(img, 200).find("class=\"missing\""), std::string::npos)
        << run.stdoutText.substr(img, 200);
    size_t marked = 0;
    for (size_t at = run.stdoutText.find("class=\"missing\""); at != std::string::npos;
         at = run.stdoutText.find("class=\"missing\"", at + 1))
        ++marked;
    EXPECT_EQ(marked, 1u);  // only that one
}

}  // namespace
}  // namespace gbl
