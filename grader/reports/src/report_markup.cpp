// JUnit XML, the static HTML report and the html pieces of Gradescope's output; see report.h. All
// are plain text assembled here, with every value from the submission escaped (a diagnostic may
// contain anything the student wrote).
#include "report_markup.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <utility>

#include "embed.h"
#include "grader/metrics/scoring.h"
#include "grader/reports/report.h"

namespace grader {

namespace {

// Length of the valid UTF-8 sequence starting at s[i], or 0 when the bytes there are not one
// (RFC 3629: no overlong forms, no surrogates, nothing above U+10FFFF).
std::size_t utf8Length(const std::string& s, std::size_t i) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
    const unsigned char b = byte(i);
    std::size_t n = 0;
    unsigned min = 0;
    if (b < 0x80) return 1;
    if (b >= 0xC2 && b <= 0xDF)
        n = 2, min = 0x80;
    else if (b >= 0xE0 && b <= 0xEF)
        n = 3, min = 0x800;
    else if (b >= 0xF0 && b <= 0xF4)
        n = 4, min = 0x10000;
    else
        return 0;
    if (i + n > s.size()) return 0;
    unsigned cp = b & (0x7F >> n);
    for (std::size_t k = 1; k < n; ++k) {
        if ((byte(i + k) & 0xC0) != 0x80) return 0;
        cp = (cp << 6) | (byte(i + k) & 0x3F);
    }
    if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
    return n;
}

std::string num(double v, const char* format = "%.3f") {
    if (std::isinf(v) && v > 0) return "&infin;";
    if (!std::isfinite(v)) return "n/a";
    char buf[64];
    std::snprintf(buf, sizeof buf, format, v);
    return buf;
}

std::string diagnosticLine(const ReportDiagnostic& d) { return formatDiagnostic(d); }

}  // namespace

// Escapes for both HTML and XML text and attributes. Invalid UTF-8 and the control characters
// XML 1.0 forbids (even escaped) become '?', so a hostile diagnostic cannot break the file.
std::string escapeMarkup(const std::string& s) {
    std::string out;
    out.reserve(s.size());
    // A byte that needs nothing (printable ASCII other than the five above) is copied in runs:
    // the pictures' data URIs, megabytes of base64, are nothing else.
    const auto plain = [](unsigned char b) {
        return b >= 0x20 && b < 0x7F && b != '&' && b != '<' && b != '>' && b != '"' && b != '\'';
    };
    for (std::size_t i = 0; i < s.size();) {
        std::size_t run = i;
        while (run < s.size() && plain(static_cast<unsigned char>(s[run]))) ++run;
        if (run > i) {
            out.append(s, i, run - i);
            i = run;
            continue;
        }
        const char c = s[i];
        const std::size_t n = utf8Length(s, i);
        if (n == 0) {
            out += '?';
            ++i;
            continue;
        }
        if (n > 1) {
            out.append(s, i, n);
            i += n;
            continue;
        }
        ++i;
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&#39;";
                break;
            default:
                if (static_cast<unsigned char>(c) < 0x20 && c != '\n' && c != '\t' && c != '\r')
                    out += '?';
                else
                    out += c;
        }
    }
    return out;
}

std::string reportToJunit(const Report& report) {
    std::ostringstream x;
    int total = 0, failures = 0;
    for (const ReportLab& lab : report.labs) {
        const std::size_t n = lab.scenes.empty() ? 1 : lab.scenes.size();
        total += static_cast<int>(n);
        if (lab.scenes.empty()) ++failures;
        for (const ReportScene& s : lab.scenes) failures += s.status != "passed";
    }
    x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    x << "<testsuites name=\"shaderlab\" tests=\"" << total << "\" failures=\"" << failures << "\">\n";
    for (const ReportLab& lab : report.labs) {
        int lab_failures = lab.scenes.empty() ? 1 : 0;
        for (const ReportScene& s : lab.scenes) lab_failures += s.status != "passed";
        x << "  <testsuite name=\"" << escapeMarkup(lab.id) << "\" tests=\""
          << (lab.scenes.empty() ? 1 : lab.scenes.size()) << "\" failures=\"" << lab_failures << "\" time=\""
          << num(lab.wall_ms / 1000.0) << "\">\n";
        if (lab.scenes.empty()) {
            std::string body = lab.message;
            for (const ReportDiagnostic& d : lab.diagnostics) body += "\n" + diagnosticLine(d);
            x << "    <testcase classname=\"" << escapeMarkup(lab.id) << "\" name=\"build\">\n"
              << "      <failure type=\"" << escapeMarkup(lab.status) << "\" message=\""
              << escapeMarkup(lab.message) << "\">" << escapeMarkup(body) << "</failure>\n    </testcase>\n";
        }
        for (const ReportScene& s : lab.scenes) {
            x << "    <testcase classname=\"" << escapeMarkup(lab.id) << "\" name=\"" << escapeMarkup(s.name)
              << "\" time=\"" << num(s.render_ms / 1000.0) << "\"";
            if (s.status == "passed") {
                x << "/>\n";
            } else {
                x << ">\n      <failure type=\"" << escapeMarkup(s.status) << "\" message=\""
                  << escapeMarkup(s.message) << "\">" << escapeMarkup(s.message)
                  << "</failure>\n    </testcase>\n";
            }
        }
        x << "  </testsuite>\n";
    }
    x << "</testsuites>\n";
    return x.str();
}

namespace {

// ---- report.html ------------------------------------------------------------------------------
// One page, no scripts: a summary (score, scenes passed, where to look first), then per lab its
// goals and points and per scene its pictures and numbers. Boxes over the pictures are CSS
// percentages of the image size, so they scale with the picture on any screen.

const char* const kStyle =
    ":root{--ok:#1a7f37;--bad:#c62828;--bright:#c75000;--dark:#0d59d9;--line:#ddd}\n"
    "*{box-sizing:border-box}\n"
    "body{font:16px/1.45 system-ui,-apple-system,'Segoe UI',sans-serif;margin:0;background:#f6f6f6;"
    "color:#222}\n"
    "main{max-width:1180px;margin:0 auto;padding:1em}\n"
    "h1{font-size:1.5em;margin:.2em 0}\n"
    "h2{font-size:1.3em;margin:1.8em 0 .4em;border-bottom:2px solid var(--line)}\n"
    "h3{font-size:1.1em;margin:1.4em 0 .3em}\n"
    "h4{font-size:1.05em;margin:0 0 .3em}\n"
    "a{color:#0b57d0}\n"
    "code,pre{font-family:ui-monospace,Menlo,Consolas,monospace;font-size:.9em}\n"
    "pre{background:#fff;border:1px solid var(--line);padding:.6em;white-space:pre-wrap;"
    "overflow-wrap:anywhere}\n"
    ".meta{color:#555;font-size:.9em;overflow-wrap:anywhere}\n"
    ".card{background:#fff;border:1px solid var(--line);border-radius:6px;padding:.8em 1em;"
    "margin:.8em 0}\n"
    ".big{font-size:1.6em;font-weight:700}\n"
    ".badge{display:inline-block;padding:0 .45em;border-radius:4px;font-size:.8em;color:#fff;"
    "vertical-align:middle;background:var(--bad)}\n"
    ".badge.passed{background:var(--ok)}\n"
    ".ok{color:var(--ok)}.bad{color:var(--bad)}.info{color:#555}\n"
    ".first{border-left:5px solid var(--bad)}\n"
    ".allgood{border-left:5px solid var(--ok)}\n"
    ".hint{background:#fff6d6;border-left:5px solid #e0a800;padding:.5em .8em;margin:.5em 0}\n"
    ".explain{color:#333}\n"
    ".scroll{overflow-x:auto;max-width:100%}\n"
    "table{border-collapse:collapse;margin:.4em 0}\n"
    "th,td{padding:.25em .6em;text-align:left;vertical-align:top;border-bottom:1px solid #eee}\n"
    "th{font-weight:600;border-bottom:2px solid var(--line)}\n"
    "td.num{white-space:nowrap}\n"
    ".scene{scroll-margin-top:.5em}\n"
    ".scene.failed{border-left:5px solid var(--bad)}\n"
    ".passname{font-weight:600;margin:.8em 0 .2em}\n"
    ".pics{display:flex;flex-wrap:wrap;gap:.8em;margin:.5em 0;align-items:flex-start}\n"
    "figure{margin:0;flex:1 1 160px;max-width:256px}\n"
    "figure.zoom{flex:1 1 260px;max-width:400px}\n"
    ".frame{position:relative;line-height:0}\n"
    "img{display:block;width:100%;height:auto;image-rendering:pixelated;border:1px solid #888;"
    "background:#000}\n"
    ".box{position:absolute;border:2px solid #fff;outline:1px solid #000;pointer-events:none}\n"
    ".box.nonfinite{border:2px dashed #f0f}\n"
    "figcaption{font-size:.85em;color:#444;margin-top:.25em;line-height:1.3}\n"
    ".bright{color:var(--bright);font-weight:600}.dark{color:var(--dark);font-weight:600}\n"
    ".magenta{color:#b000b0;font-weight:600}\n"
    "details{margin:.5em 0}\n"
    "summary{cursor:pointer;color:#0b57d0}\n"
    "footer{color:#666;font-size:.85em;margin:2em 0 1em}\n"
    "@media (max-width:600px){body{font-size:15px}main{padding:.5em}.card{padding:.6em}"
    "figure{flex-basis:calc(50% - .4em)}figure.zoom{flex-basis:100%}}\n";

// Letters, digits, '-' and '_' as they are; anything else as '_' (ids must not contain spaces).
std::string anchorPart(const std::string& s) {
    std::string out;
    for (char c : s) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_') ? c : '_';
    return out;
}
std::string labAnchor(const std::string& lab) { return "lab-" + anchorPart(lab); }
std::string sceneAnchor(const std::string& lab, const std::string& scene) {
    return "scene-" + anchorPart(lab) + "--" + anchorPart(scene);
}

std::string fixed(double v, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

int decimalsOf(const std::string& s) {
    const std::size_t dot = s.find('.');
    return dot == std::string::npos ? 0 : static_cast<int>(s.size() - dot - 1);
}

// |value - limit| with `digits` decimals, more (up to 8) when that would read as 0 but is not.
std::string marginOf(double value, double limit, int digits) {
    const double m = std::fabs(value - limit);
    std::string text;
    for (int d = digits; d <= 8; ++d) {
        text = fixed(m, d);
        if (m == 0.0 || std::strtod(text.c_str(), nullptr) != 0.0) break;
    }
    return text;
}

// One row of an image's table: a check, what the student got, what it needs and by how much it
// passes or fails. state: 1 passes, 0 fails, -1 information only.
struct CheckRow {
    std::string name, value, needs, margin;
    int state = -1;
};

// A threshold check written so that the numbers never contradict the verdict: the value and the
// limit get as many decimals as it takes to read differently (formatDistinct), and the margin as
// many as it takes not to read 0.
CheckRow thresholdRow(const char* name, double value, double limit, bool higher_is_better, int digits,
                      const std::string& unit, bool known) {
    CheckRow r;
    r.name = name;
    if (!known) {
        r.value = fixed(value, digits) + unit;
        return r;
    }
    const bool ok = higher_is_better ? value >= limit : value <= limit;
    std::pair<std::string, std::string> shown =
        value == limit ? std::make_pair(fixed(value, digits), fixed(limit, digits))
                       : formatDistinct(value, limit, digits);
    r.value = shown.first + unit;
    r.needs = std::string(higher_is_better ? "\xE2\x89\xA5 " : "\xE2\x89\xA4 ") + shown.second + unit;
    const std::string by = marginOf(value, limit, decimalsOf(shown.first)) + unit;
    if (value == limit)
        r.margin = "exactly at the limit";
    else if (ok)
        r.margin = by + " to spare";
    else
        r.margin = (higher_is_better ? "short by " : "over by ") + by;
    r.state = ok ? 1 : 0;
    return r;
}

std::vector<CheckRow> checkRows(const ReportPass& p) {
    const ReportMetrics& m = p.metrics;
    const ReportThresholds& t = p.thresholds;
    std::vector<CheckRow> rows;
    if (std::isinf(m.psnr_db) && m.psnr_db > 0) {
        CheckRow r;
        r.name = "PSNR";
        r.value = "identical";
        if (t.known) r.needs = "\xE2\x89\xA5 " + fixed(t.psnr_min_db, 1) + " dB";
        r.margin = "no difference at all";
        r.state = 1;
        rows.push_back(r);
    } else {
        rows.push_back(thresholdRow("PSNR", m.psnr_db, t.psnr_min_db, true, 1, " dB", t.known));
    }
    if (m.ssim_defined) {
        rows.push_back(thresholdRow("SSIM", m.ssim, t.ssim_min, true, 3, "", t.known));
    } else {
        CheckRow r;
        r.name = "SSIM";
        r.value = "undefined";
        r.margin =
            "not checked: the image is smaller than SSIM's 11\xC3\x97"
            "11 window";
        rows.push_back(r);
    }
    rows.push_back(thresholdRow("FLIP mean", m.flip_mean, t.flip_mean_max, false, 3, "", t.known));
    rows.push_back(thresholdRow("pixels that differ", 100.0 * m.mismatch_fraction, 100.0 * t.mismatch_max,
                                false, 1, " %", t.known));
    CheckRow nf;
    nf.name = "NaN / Inf pixels";
    nf.value = std::to_string(m.nan_count) + " / " + std::to_string(m.inf_count);
    nf.needs = "none";
    const std::size_t broken = m.nan_count + m.inf_count;
    nf.margin = broken == 0 ? "none" : std::to_string(broken) + " too many (magenta in the pictures)";
    nf.state = broken == 0 ? 1 : 0;
    rows.push_back(nf);
    CheckRow px;
    px.name = "pixels graded";
    px.value = std::to_string(m.pixel_count);
    px.margin = "the pixels either image covers";
    rows.push_back(px);
    return rows;
}

void writeCheckTable(std::ostringstream& h, const ReportPass& p) {
    h << "<div class=\"scroll\"><table class=\"checks\"><tr><th>check</th><th>yours</th><th>needs</th>"
         "<th>verdict</th></tr>\n";
    for (const CheckRow& r : checkRows(p)) {
        const char* cls = r.state == 1 ? "ok" : r.state == 0 ? "bad" : "info";
        const char* verdict = r.state == 1 ? "<b>ok</b>: " : r.state == 0 ? "<b>fails</b>: " : "";
        h << "<tr><td>" << escapeMarkup(r.name) << "</td><td class=\"num\">" << escapeMarkup(r.value)
          << "</td><td class=\"num\">" << escapeMarkup(r.needs) << "</td><td class=\"" << cls << "\">"
          << verdict << escapeMarkup(r.margin) << "</td></tr>\n";
    }
    h << "</table></div>\n";
    if (p.thresholds.known && p.thresholds.pixel_tolerance > 0.0)
        h << "<p class=\"info\">A pixel differs when no pixel within one pixel of it in the other image is "
             "within "
          << escapeMarkup(fixed(p.thresholds.pixel_tolerance, 3)) << " in every channel.</p>\n";
}

// The CSS box of `b` over an image of w x h pixels, in percent.
std::string boxStyle(const PixelBox& b, int w, int h) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "left:%.3f%%;top:%.3f%%;width:%.3f%%;height:%.3f%%", 100.0 * b.x0 / w,
                  100.0 * b.y0 / h, 100.0 * b.width() / w, 100.0 * b.height() / h);
    return buf;
}

struct Figure {
    std::string path, alt, caption_html;
    bool boxed = true;
    bool zoom = false;
};

void writeFigure(std::ostringstream& h, const Figure& f, const ReportPass& p,
                 const detail::AllOrNothing& pics) {
    if (f.path.empty()) return;
    h << "<figure" << (f.zoom ? " class=\"zoom\"" : "") << "><div class=\"frame\"><img src=\""
      << escapeMarkup(pics.src(f.path)) << "\" alt=\"" << escapeMarkup(f.alt) << "\"";
    if (!f.zoom && p.width > 0 && p.height > 0)
        h << " width=\"" << p.width << "\" height=\"" << p.height << "\"";
    h << ">";
    if (f.boxed && p.width > 0 && p.height > 0) {
        if (!p.zoom_region.empty())
            h << "<div class=\"box\" style=\"" << boxStyle(p.zoom_region, p.width, p.height) << "\"></div>";
        if (!p.non_finite_box.empty())
            h << "<div class=\"box nonfinite\" style=\"" << boxStyle(p.non_finite_box, p.width, p.height)
              << "\"></div>";
    }
    h << "</div><figcaption>" << f.caption_html << "</figcaption></figure>\n";
}

// The pictures and numbers of one graded image. `full`: with the difference pictures and the
// close-up; otherwise the student's and the reference's only, and a matching image the student's.
void writeImageBlock(std::ostringstream& h, const ReportPass& p, const detail::AllOrNothing& pics,
                     const std::string& label, bool full) {
    if (!label.empty()) {
        h << "<p class=\"passname\">" << label << " <span class=\""
          << (p.passed ? "ok\">matches" : "bad\">differs") << "</span>";
        if (p.range == "hdr" && p.hdr_scale > 1.0)
            h << " <span class=\"info\">(compared above 1: shown divided by "
              << escapeMarkup(fixed(p.hdr_scale, 2)) << ")</span>";
        if (p.isolated)
            h << " <span class=\"" << (p.isolated_passed ? "ok" : "bad") << "\">on the reference's inputs: "
              << (p.isolated_passed ? "matches (it differs only because of what it reads)" : "differs too")
              << "</span>";
        h << "</p>\n";
    }
    const bool broken = p.metrics.nan_count + p.metrics.inf_count > 0;
    h << "<div class=\"pics\">\n";
    writeFigure(h,
                {p.student_image, "your image",
                 std::string(p.passed ? "yours (matches the reference)" : "yours") +
                     (broken ? ": <span class=\"magenta\">magenta</span> = NaN or Inf" : "")},
                p, pics);
    // An image that matches shows once: the reference looks the same.
    if (!p.passed) writeFigure(h, {p.reference_image, "the reference image", "reference"}, p, pics);
    if (full) {
        writeFigure(
            h,
            {p.signed_image, "difference: orange where yours is too bright, blue where it is too dark",
             "difference: <span class=\"bright\">orange</span> too bright, <span class=\"dark\">blue</span> "
             "too dark"},
            p, pics);
        writeFigure(
            h,
            {p.diff_image, "FLIP error map",
             "FLIP error: black none, pale yellow most; <span style=\"color:#008b8b\">cyan</span> rings "
             "pixels that differ"},
            p, pics);
        if (!p.zoom_image.empty()) {
            const PixelBox& z = p.zoom_region;
            const std::string where = z.empty() ? std::string()
                                                : "x " + std::to_string(z.x0) + "\xE2\x80\x93" +
                                                      std::to_string(z.x1) + ", y " + std::to_string(z.y0) +
                                                      "\xE2\x80\x93" + std::to_string(z.y1);
            writeFigure(h,
                        {p.zoom_image, "enlarged region: yours, reference, FLIP error",
                         "enlarged (" + where + "): yours, reference, FLIP error", false, true},
                        p, pics);
        }
    }
    h << "</div>\n";
    if (!p.zoom_region.empty() || !p.non_finite_box.empty())
        h << "<p class=\"info\">"
          << (p.zoom_region.empty() ? "" : "The white box marks the region shown enlarged. ")
          << (p.non_finite_box.empty() ? "" : "The dashed magenta box holds the NaN and Inf pixels.")
          << "</p>\n";
    writeCheckTable(h, p);
}

// A scene from a report without passes (older writers): its final image as one pass.
ReportPass finalOf(const ReportScene& s) {
    if (!s.passes.empty()) return s.passes.back();
    ReportPass p;
    p.name = "final";
    p.passed = s.status == "passed";
    p.metrics = s.metrics;
    p.student_image = s.student_image;
    p.reference_image = s.reference_image;
    p.diff_image = s.diff_image;
    p.signed_image = s.signed_image;
    p.zoom_image = s.zoom_image;
    return p;
}

std::string passLabel(const ReportPass& p, const std::string& role) {
    return role + " <code>" + escapeMarkup(p.name) + "</code>";
}

std::vector<const ReportGoal*> goalsOfScene(const ReportLab& lab, const std::string& scene) {
    std::vector<const ReportGoal*> out;
    for (const ReportGoal& g : lab.goals) {
        bool in = std::find(g.scenes.begin(), g.scenes.end(), scene) != g.scenes.end();
        for (const std::string& f : g.failing) in = in || f.substr(0, f.find('/')) == scene;
        if (in) out.push_back(&g);
    }
    return out;
}

void writeHint(std::ostringstream& h, const ReportHint& hint) {
    if (hint.mistake.empty()) return;
    h << "<p class=\"hint\"><b>This looks like a known mistake:</b> " << escapeMarkup(hint.about)
      << " <span class=\"info\">(your image of <code>" << escapeMarkup(hint.image)
      << "</code> is very close to what that mistake draws: ";
    if (std::isinf(hint.psnr_db))
        h << "identical";
    else
        h << "PSNR " << escapeMarkup(fixed(hint.psnr_db, 1)) << " dB";
    h << ")</span></p>\n";
}

void writeScene(std::ostringstream& h, const ReportLab& lab, const ReportScene& s,
                const detail::AllOrNothing& pics) {
    const bool failed = s.status != "passed";
    h << "<section class=\"card scene " << (failed ? "failed" : "passed") << "\" id=\""
      << sceneAnchor(lab.id, s.name) << "\">\n<h4>" << escapeMarkup(s.name) << " <span class=\"badge "
      << (failed ? "failed" : "passed") << "\">" << escapeMarkup(s.status) << "</span> <span class=\"info\">"
      << num(s.score, "%.2f") << " of " << num(s.max_score, "%.2f") << " points</span></h4>\n";
    const std::vector<const ReportGoal*> goals = goalsOfScene(lab, s.name);
    if (!goals.empty()) {
        h << "<p class=\"info\">Shows: ";
        for (std::size_t i = 0; i < goals.size(); ++i)
            h << (i ? "; " : "") << escapeMarkup(goals[i]->title) << " ("
              << (goals[i]->met ? "<span class=\"ok\">met</span>" : "<span class=\"bad\">not met</span>")
              << ")";
        h << ".</p>\n";
    }
    const ReportPass last = finalOf(s);
    const bool multipass = s.passes.size() > 1;
    if (!failed) {
        h << "<p>Every graded image matches the reference.";
        if (s.score < s.max_score - 1e-9)
            h << " Its share of points is not earned because a goal it shows fails in another scene.";
        h << "</p>\n<details><summary>Pictures and numbers</summary>\n";
        for (const ReportPass& p : s.passes.empty() ? std::vector<ReportPass>{last} : s.passes)
            writeImageBlock(h, p, pics, multipass ? passLabel(p, "Image") : "", false);
        h << "</details>\n</section>\n";
        return;
    }
    if (!s.message.empty()) h << "<p><b>Why:</b> " << escapeMarkup(s.message) << "</p>\n";
    writeHint(h, s.hint);
    const ReportPass* focus = nullptr;
    for (const ReportPass& p : s.passes)
        if (p.name == s.first_failing_pass) focus = &p;
    std::vector<const ReportPass*> shown;
    if (focus != nullptr && focus->name != last.name) {
        writeImageBlock(h, *focus, pics, passLabel(*focus, "First wrong pass"), true);
        shown.push_back(focus);
    }
    writeImageBlock(h, last, pics, multipass ? passLabel(last, "Final image") : "", !last.passed);
    std::vector<const ReportPass*> rest;
    for (const ReportPass& p : s.passes)
        if (&p != focus && p.name != last.name) rest.push_back(&p);
    if (!rest.empty()) {
        h << "<details><summary>The other graded images (" << rest.size() << ")</summary>\n";
        for (const ReportPass* p : rest) writeImageBlock(h, *p, pics, passLabel(*p, "Image"), false);
        h << "</details>\n";
    }
    h << "</section>\n";
}

}  // namespace

std::string judgedWithText(const ReportGoal& goal) {
    if (goal.judged_with.empty()) return "";
    std::string list;
    for (std::size_t i = 0; i < goal.judged_with.size(); ++i)
        list += (i == 0 ? "" : i + 1 == goal.judged_with.size() ? " and " : ", ") + goal.judged_with[i];
    return "with your changes to " + list + ", code the starter gave that uses it";
}

std::string goalJudgement(const ReportGoal& goal) {
    const std::string with = judgedWithText(goal);
    if (goal.judged == "alone" && goal.met && !goal.whole_failing.empty())
        return "Your own work for it is right: its pictures fail only because of another part.";
    if (goal.judged == "alone" && goal.met) return "Your own work for it is right.";
    if (goal.judged == "alone")
        return "Judged on your own work for it" + (with.empty() ? "" : " (" + with + ")") +
               ", the rest taken from the reference solution: still wrong.";
    if (goal.judged == "whole" && !goal.met && !goal.judged_note.empty())
        return "Judged on your whole shaders, because your work for it could not be taken alone: " +
               goal.judged_note + ".";
    return "";
}

// "the ramp goal" or "'Ramp' and 'Edges'": the titles of the goals `ids` names, quoted.
std::string goalsNamed(const ReportLab& lab, const std::vector<std::string>& ids) {
    std::string out;
    for (std::size_t i = 0; i < ids.size(); ++i) {
        std::string title = ids[i];
        for (const ReportGoal& g : lab.goals)
            if (g.id == ids[i]) title = g.title;
        out += (i == 0 ? "" : i + 1 == ids.size() ? " and " : ", ") + ("'" + title + "'");
    }
    return out;
}

namespace {

void writeGoals(std::ostringstream& h, const ReportLab& lab) {
    if (lab.goals.empty()) return;
    int met = 0;
    for (const ReportGoal& g : lab.goals) met += g.met;
    h << "<h3>Learning goals and points</h3>\n<p class=\"explain\">Points follow the learning goals. A goal "
         "earns its points only when every image that shows it matches the reference; a goal that fails "
         "costs its own points and no others, and nothing is earned for an image that is merely close. Here "
      << met << " of " << lab.goals.size() << " goals are met: " << num(lab.score, "%.2f") << " of "
      << num(lab.max_score, "%.2f")
      << " points. Each scene's points are its share of the goals it shows, so a scene that matches "
         "can still earn less when one of its goals fails elsewhere.</p>\n";
    h << "<div class=\"scroll\"><table class=\"goals\"><tr><th>goal</th><th>points</th><th></th></tr>\n";
    for (const ReportGoal& g : lab.goals) {
        h << "<tr><td>" << escapeMarkup(g.title);
        if (!g.not_met_because.empty()) {
            h << "<br><span class=\"info\">not met because "
              << escapeMarkup(goalsNamed(lab, g.not_met_because))
              << (g.not_met_because.size() > 1 ? " are" : " is") << " not met</span>";
        }
        // "<scene>/<pass>" checks grouped by scene: "fails in teapot (blur1_h, blur1_v), cube (...)".
        std::string open_scene;
        for (std::size_t i = 0; g.not_met_because.empty() && i < g.failing.size(); ++i) {
            const std::size_t slash = g.failing[i].find('/');
            const std::string scene = g.failing[i].substr(0, slash);
            const std::string pass = slash == std::string::npos ? "" : g.failing[i].substr(slash + 1);
            if (i == 0 || scene != open_scene) {
                h << (i == 0 ? "<br><span class=\"info\">fails in " : "), ") << "<a href=\"#"
                  << sceneAnchor(lab.id, scene) << "\">" << escapeMarkup(scene) << "</a> (";
                open_scene = scene;
            } else {
                h << ", ";
            }
            h << escapeMarkup(pass);
        }
        if (!g.failing.empty() && g.not_met_because.empty()) h << ")</span>";
        const std::string judgement = goalJudgement(g);
        if (!judgement.empty())
            h << "<br><span class=\"info judged-" << escapeMarkup(g.judged) << "\">"
              << escapeMarkup(judgement) << "</span>";
        h << "</td><td class=\"num\">" << num(g.met ? g.points : 0.0, "%.2f") << " / "
          << num(g.points, "%.2f") << "</td><td class=\"num " << (g.met ? "ok\">met" : "bad\">not met")
          << "</td></tr>\n";
    }
    h << "</table></div>\n";
}

const ReportScene* findScene(const ReportLab& lab, const std::string& name) {
    for (const ReportScene& s : lab.scenes)
        if (s.name == name) return &s;
    return nullptr;
}

// Where to look first: the first lab that did not pass; in it, the first goal not met, its first
// failing check's scene, and that scene's first wrong pass.
// `links`: to the sections of report.html (Gradescope's copy has none to link to).
void writeLookFirst(std::ostringstream& h, const Report& report, bool links) {
    const auto link = [&](const std::string& anchor, const std::string& text) {
        return links ? "<a href=\"#" + anchor + "\">" + escapeMarkup(text) + "</a>"
                     : "<b>" + escapeMarkup(text) + "</b>";
    };
    const ReportLab* lab = nullptr;
    for (const ReportLab& l : report.labs)
        if (l.status != "passed") {
            lab = &l;
            break;
        }
    if (lab == nullptr) {
        h << "<div class=\"card allgood\"><p><b>Everything passes.</b> Every graded image of every scene "
             "matches the reference.</p></div>\n";
        return;
    }
    h << "<div class=\"card first\"><h2 style=\"margin-top:0;border:0\">Look here first</h2>\n";
    if (lab->scenes.empty()) {
        const bool untouched = lab->status == "not_attempted";  // the starter: nothing was drawn
        h << "<p>" << link(labAnchor(lab->id), lab->id)
          << (untouched ? " is not attempted yet" : " did not render (" + escapeMarkup(lab->status) + ")")
          << ". " << escapeMarkup(lab->message) << "</p>\n";
        if (!lab->diagnostics.empty())
            h << "<pre>" << escapeMarkup(diagnosticLine(lab->diagnostics.front())) << "</pre>\n";
        h << "</div>\n";
        return;
    }
    const ReportGoal* goal = nullptr;
    const ReportScene* scene = nullptr;
    for (const ReportGoal& g : lab->goals) {
        if (g.met || g.failing.empty()) continue;
        scene = findScene(*lab, g.failing.front().substr(0, g.failing.front().find('/')));
        if (scene != nullptr) {
            goal = &g;
            break;
        }
    }
    if (scene == nullptr)
        for (const ReportScene& s : lab->scenes)
            if (s.status != "passed") {
                scene = &s;
                break;
            }
    if (scene == nullptr) {
        h << "<p>" << link(labAnchor(lab->id), lab->id) << ": " << escapeMarkup(lab->status) << ". "
          << escapeMarkup(lab->message) << "</p></div>\n";
        return;
    }
    // The scene's message names its first wrong pass when there are several.
    h << "<p>" << link(sceneAnchor(lab->id, scene->name), lab->id + " \xE2\x80\xBA " + scene->name) << ": "
      << escapeMarkup(scene->message) << "</p>\n";
    if (goal != nullptr)
        h << "<p>It decides the goal \xE2\x80\x9C" << escapeMarkup(goal->title) << "\xE2\x80\x9D ("
          << num(goal->points, "%.2f") << " points).</p>\n";
    writeHint(h, scene->hint);
    h << "</div>\n";
}

std::vector<std::string> picturePaths(const Report& report) {
    std::vector<std::string> paths;
    for (const ReportLab& lab : report.labs)
        for (const ReportScene& s : lab.scenes) {
            const std::vector<ReportPass> passes =
                s.passes.empty() ? std::vector<ReportPass>{finalOf(s)} : s.passes;
            for (const ReportPass& p : passes) {
                // As writeScene shows them: the difference pictures of a failing scene's first
                // wrong image and of its final image when that fails; of every other image the
                // student's and the reference's only (the rest stay on disk and in report.json), so
                // that the page of a whole course stays small enough to embed.
                const bool full = s.status != "passed" && !p.passed &&
                                  (p.name == s.first_failing_pass || &p == &passes.back());
                std::vector<const std::string*> shown = {&p.student_image};
                if (!p.passed) shown.push_back(&p.reference_image);
                if (full)
                    for (const std::string* extra : {&p.diff_image, &p.signed_image, &p.zoom_image})
                        shown.push_back(extra);
                for (const std::string* path : shown)
                    if (!path->empty()) paths.push_back(*path);
            }
        }
    return paths;
}

}  // namespace

std::string reportToHtml(const Report& report, const ImageEmbedding& images) {
    const detail::AllOrNothing pics(picturePaths(report), images);
    std::ostringstream h;
    h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      << "<title>shaderlab report: " << escapeMarkup(report.submission) << "</title>\n<style>\n"
      << kStyle << "</style>\n</head>\n<body>\n<main>\n";
    h << "<h1>shaderlab report</h1>\n<p class=\"meta\">Submission <code>" << escapeMarkup(report.submission)
      << "</code>, backend " << escapeMarkup(report.backend);
    if (!report.renderer.empty()) h << " (" << escapeMarkup(report.renderer) << ")";
    h << ".</p>\n";

    int scenes = 0, scenes_passed = 0, labs_passed = 0;
    for (const ReportLab& lab : report.labs) {
        labs_passed += lab.status == "passed";
        for (const ReportScene& s : lab.scenes) {
            ++scenes;
            scenes_passed += s.status == "passed";
        }
    }
    h << "<div class=\"card\"><p><span class=\"big\">" << num(report.score, "%.2f") << " / "
      << num(report.max_score, "%.2f") << "</span> points";
    if (scenes > 0) h << " &middot; <b>" << scenes_passed << " of " << scenes << "</b> scenes pass";
    h << " &middot; <b>" << labs_passed << " of " << report.labs.size() << "</b> labs pass</p>\n";
    h << "<div class=\"scroll\"><table><tr><th>lab</th><th>points</th><th>scenes passing</th><th>goals "
         "met</th></tr>\n";
    for (const ReportLab& lab : report.labs) {
        int passed = 0, met = 0;
        for (const ReportScene& s : lab.scenes) passed += s.status == "passed";
        for (const ReportGoal& g : lab.goals) met += g.met;
        h << "<tr><td class=\"num\"><a href=\"#" << labAnchor(lab.id) << "\">" << escapeMarkup(lab.id)
          << "</a> <span class=\"badge " << (lab.status == "passed" ? "passed" : "failed") << "\">"
          << escapeMarkup(lab.status) << "</span></td><td class=\"num\">" << num(lab.score, "%.2f") << " / "
          << num(lab.max_score, "%.2f") << "</td>";
        // A lab that did not render has neither scenes nor goals to count.
        if (lab.scenes.empty())
            h << "<td class=\"num\">&mdash;</td><td class=\"num\">&mdash;</td></tr>\n";
        else
            h << "<td class=\"num\">" << passed << " of " << lab.scenes.size() << "</td><td class=\"num\">"
              << met << " of " << lab.goals.size() << "</td></tr>\n";
    }
    h << "</table></div></div>\n";
    writeLookFirst(h, report, true);

    for (const ReportLab& lab : report.labs) {
        h << "<h2 id=\"" << labAnchor(lab.id) << "\">" << escapeMarkup(lab.id);
        if (!lab.title.empty()) h << ": " << escapeMarkup(lab.title);
        h << " <span class=\"badge " << (lab.status == "passed" ? "passed" : "failed") << "\">"
          << escapeMarkup(lab.status) << "</span> <span class=\"info\">" << num(lab.score, "%.2f") << " / "
          << num(lab.max_score, "%.2f") << "</span></h2>\n";
        if (!lab.message.empty()) h << "<p>" << escapeMarkup(lab.message) << "</p>\n";
        if (!lab.diagnostics.empty()) {
            h << "<pre>";
            for (const ReportDiagnostic& d : lab.diagnostics) h << escapeMarkup(diagnosticLine(d)) << "\n";
            h << "</pre>\n";
        }
        writeGoals(h, lab);
        if (lab.scenes.empty()) continue;
        h << "<h3>Scenes</h3>\n";
        if (!lab.reference_source.empty())
            h << "<p class=\"info\">Reference images from " << escapeMarkup(lab.reference_source)
              << ". Failing scenes come first.</p>\n";
        for (const ReportScene& s : lab.scenes)
            if (s.status != "passed") writeScene(h, lab, s, pics);
        for (const ReportScene& s : lab.scenes)
            if (s.status == "passed") writeScene(h, lab, s, pics);
    }
    h << "<footer>shaderlab " << escapeMarkup(report.tool_version) << ".";
    if (!picturePaths(report).empty())
        h << (pics.embedded()
                  ? " The pictures are embedded in this page, which opens anywhere on its own."
                  : " The pictures are linked from the folders beside this page: keep them together.");
    h << "</footer>\n</main>\n</body>\n</html>\n";
    return h.str();
}

// ---- Gradescope html output (report_json.cpp writes the JSON) ----------------------------------

namespace detail {

std::string gradescopeGoalHtml(const ReportLab& lab, const ReportGoal& goal, Budget& budget) {
    std::ostringstream h;
    const std::string judgement = goalJudgement(goal);
    if (goal.met) {
        h << "<p><b>Met</b> (" << num(goal.points, "%.2f")
          << (goal.judged == "alone" ? " points)."
                                     : " points): every image that shows it matches the reference.");
        if (!judgement.empty()) h << " " << escapeMarkup(judgement);
        h << "</p>";
        return h.str();
    }
    if (!judgement.empty()) h << "<p>" << escapeMarkup(judgement) << "</p>\n";
    if (!goal.not_met_because.empty()) {
        h << "<p><b>Not met</b> (0 of " << num(goal.points, "%.2f") << " points) because "
          << escapeMarkup(goalsNamed(lab, goal.not_met_because))
          << (goal.not_met_because.size() > 1 ? " are" : " is") << " not met: this goal rests on "
          << (goal.not_met_because.size() > 1 ? "them" : "it") << ". Look there first.</p>";
        return h.str();
    }
    h << "<p><b>Not met</b> (0 of " << num(goal.points, "%.2f")
      << " points). A goal earns its points only when every image that shows it matches the reference. "
         "These do not:</p>\n";
    // The failing "<scene>/<pass>" checks grouped by scene, in order.
    std::vector<std::pair<std::string, std::vector<std::string>>> scenes;
    for (const std::string& check : goal.failing) {
        const std::size_t slash = check.find('/');
        const std::string scene = check.substr(0, slash);
        if (scenes.empty() || scenes.back().first != scene) scenes.push_back({scene, {}});
        if (slash != std::string::npos) scenes.back().second.push_back(check.substr(slash + 1));
    }
    std::string last_hint;
    for (const auto& [scene_name, passes] : scenes) {
        h << "<h4>" << escapeMarkup(scene_name);
        for (std::size_t i = 0; i < passes.size(); ++i) h << (i ? ", " : " (") << escapeMarkup(passes[i]);
        h << (passes.empty() ? "" : ")") << "</h4>\n";
        const ReportScene* scene = findScene(lab, scene_name);
        if (scene == nullptr) continue;
        if (!scene->message.empty()) h << "<p>" << escapeMarkup(scene->message) << "</p>\n";
        if (!scene->hint.mistake.empty() && scene->hint.about != last_hint)
            h << "<p><b>This looks like a known mistake:</b> " << escapeMarkup(scene->hint.about) << "</p>\n";
        last_hint = scene->hint.about;
        // The pictures of one failing image of these checks: the scene's first wrong image when it
        // is one of them, else the first; the final image when none is found.
        ReportPass shown = finalOf(*scene);
        const ReportPass* first = nullptr;
        for (const ReportPass& p : scene->passes) {
            if (p.passed || std::find(passes.begin(), passes.end(), p.pass) == passes.end()) continue;
            if (first == nullptr || p.name == scene->first_failing_pass) first = &p;
            if (p.name == scene->first_failing_pass) break;
        }
        if (first != nullptr) shown = *first;
        std::string row;
        // A named array, not a braced list of make_pair temporaries in the loop header: GCC 14's
        // -Wdangling-reference takes a reference into such a list for one that outlives it.
        const std::pair<const std::string*, const char*> pictures[] = {
            {&shown.student_image, "yours"},
            {&shown.reference_image, "reference"},
            {&shown.signed_image, "orange too bright, blue too dark"},
            {&shown.diff_image, "FLIP error"}};
        for (const auto& [path, alt] : pictures) {
            const std::string uri = budget.take(*path);
            if (!uri.empty())
                row += "<img src=\"" + uri + "\" width=\"160\" alt=\"" + alt + "\" title=\"" + alt + "\"> ";
        }
        if (!row.empty())
            h << "<p>" << row << "</p>\n<p><i>Image <code>" << escapeMarkup(shown.name)
              << "</code>: yours, the reference, the difference (orange: too bright, blue: too dark), the "
                 "FLIP "
                 "error (pale yellow: largest).</i></p>\n";
    }
    return h.str();
}

std::string gradescopeSummaryHtml(const Report& report) {
    std::ostringstream h;
    writeLookFirst(h, report, false);
    return h.str();
}

}  // namespace detail

}  // namespace grader
