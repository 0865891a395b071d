// JUnit XML and the static HTML report; see report.h. Both are plain text assembled here, with
// every value from the submission escaped (a diagnostic may contain anything the student wrote).
#include <cmath>
#include <cstdio>
#include <sstream>

#include "grader/report.h"

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

// Escapes for both HTML and XML text and attributes. Invalid UTF-8 and the control characters
// XML 1.0 forbids (even escaped) become '?', so a hostile diagnostic cannot break the file.
std::string escapeMarkup(const std::string& s) {
    std::string out;
    out.reserve(s.size());
    for (std::size_t i = 0; i < s.size();) {
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

std::string num(double v, const char* format = "%.3f") {
    if (std::isinf(v) && v > 0) return "&infin;";
    if (!std::isfinite(v)) return "n/a";
    char buf[64];
    std::snprintf(buf, sizeof buf, format, v);
    return buf;
}

std::string diagnosticLine(const ReportDiagnostic& d) { return formatDiagnostic(d); }

}  // namespace

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

std::string reportToHtml(const Report& report) {
    std::ostringstream h;
    h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
      << "<title>shaderlab report: " << escapeMarkup(report.submission) << "</title>\n"
      << "<style>\n"
         "body{font-family:sans-serif;margin:1.5em;background:#fafafa;color:#222}\n"
         "h2{margin-top:2em;border-bottom:1px solid #ccc}\n"
         ".passed{color:#1a7f37}.failed,.compile_error,.link_error,.timeout,.crashed,.missing{color:#c62828}"
         "\n"
         "table.scene{border-collapse:collapse;margin:0.8em 0}\n"
         "table.scene td{padding:4px;vertical-align:top;text-align:center;font-size:0.85em}\n"
         "img{image-rendering:pixelated;width:256px;border:1px solid #999;background:#000}\n"
         "pre{background:#fff;border:1px solid #ddd;padding:0.6em;overflow:auto}\n"
         "table.metrics td{text-align:left;padding:1px 8px}\n"
         "</style></head><body>\n";
    h << "<h1>shaderlab report</h1>\n<p>Submission <code>" << escapeMarkup(report.submission)
      << "</code>, backend " << escapeMarkup(report.backend) << " (" << escapeMarkup(report.renderer)
      << "). Score <b>" << num(report.score, "%.2f") << " / " << num(report.max_score, "%.2f")
      << "</b>.</p>\n";
    for (const ReportLab& lab : report.labs) {
        h << "<h2>" << escapeMarkup(lab.id) << ": " << escapeMarkup(lab.title) << " <span class=\""
          << escapeMarkup(lab.status) << "\">" << escapeMarkup(lab.status) << "</span> "
          << num(lab.score, "%.2f") << " / " << num(lab.max_score, "%.2f") << "</h2>\n";
        if (!lab.message.empty()) h << "<p>" << escapeMarkup(lab.message) << "</p>\n";
        if (!lab.diagnostics.empty()) {
            h << "<pre>";
            for (const ReportDiagnostic& d : lab.diagnostics) h << escapeMarkup(diagnosticLine(d)) << "\n";
            h << "</pre>\n";
        }
        if (!lab.goals.empty()) {
            h << "<table class=\"metrics\"><tr><th>learning goal</th><th>points</th><th></th></tr>\n";
            for (const ReportGoal& g : lab.goals) {
                std::string failing;
                for (const std::string& f : g.failing) failing += (failing.empty() ? "" : ", ") + f;
                h << "<tr><td>" << escapeMarkup(g.title) << "</td><td>" << num(g.met ? g.points : 0.0, "%.2f")
                  << " / " << num(g.points, "%.2f") << "</td><td class=\""
                  << (g.met ? "passed\">met" : "failed\">not met")
                  << (failing.empty() ? "" : ": " + escapeMarkup(failing)) << "</td></tr>\n";
            }
            h << "</table>\n";
        }
        if (!lab.reference_source.empty())
            h << "<p>Reference images from " << escapeMarkup(lab.reference_source) << ".</p>\n";
        for (const ReportScene& s : lab.scenes) {
            h << "<h3>" << escapeMarkup(s.name) << " <span class=\"" << escapeMarkup(s.status) << "\">"
              << escapeMarkup(s.status) << "</span> " << num(s.score, "%.2f") << " / "
              << num(s.max_score, "%.2f") << "</h3>\n";
            if (!s.message.empty()) h << "<p>" << escapeMarkup(s.message) << "</p>\n";
            h << "<table class=\"scene\"><tr><td><img src=\"" << escapeMarkup(s.student_image)
              << "\" alt=\"student\"><br>student</td><td><img src=\"" << escapeMarkup(s.reference_image)
              << "\" alt=\"reference\"><br>reference</td><td><img src=\"" << escapeMarkup(s.diff_image)
              << "\" alt=\"difference\"><br>FLIP error (mismatches outlined)</td><td>"
              << "<table class=\"metrics\">"
              << "<tr><td>PSNR</td><td>" << num(s.metrics.psnr_db, "%.2f") << " dB</td></tr>"
              << "<tr><td>SSIM</td><td>"
              << (s.metrics.ssim_defined ? num(s.metrics.ssim, "%.4f") : "undefined") << "</td></tr>"
              << "<tr><td>FLIP mean</td><td>" << num(s.metrics.flip_mean, "%.4f") << "</td></tr>"
              << "<tr><td>mismatching</td><td>" << num(100.0 * s.metrics.mismatch_fraction, "%.2f")
              << " %</td></tr>"
              << "<tr><td>NaN / Inf</td><td>" << s.metrics.nan_count << " / " << s.metrics.inf_count
              << "</td></tr>"
              << "<tr><td>pixels graded</td><td>" << s.metrics.pixel_count << "</td></tr>";
            if (!s.first_failing_pass.empty())
                h << "<tr><td>first failing pass</td><td>" << escapeMarkup(s.first_failing_pass)
                  << "</td></tr>";
            h << "</table></td></tr></table>\n";
            if (s.passes.size() > 1) {
                h << "<table class=\"scene\"><tr>";
                for (const ReportPass& p : s.passes)
                    h << "<td><img src=\"" << escapeMarkup(p.student_image) << "\" alt=\""
                      << escapeMarkup(p.name) << "\"><br>" << escapeMarkup(p.name) << " <span class=\""
                      << (p.passed ? "passed\">ok" : "failed\">differs") << "</span></td>";
                h << "</tr></table>\n";
            }
        }
    }
    h << "</body></html>\n";
    return h.str();
}

}  // namespace grader
