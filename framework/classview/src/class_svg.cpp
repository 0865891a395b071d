// The class page's text helpers and SVG plots; see class_markup.h.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "class_markup.h"
#include "grader/base/untrusted_text.h"
#include "grader/reports/report.h"

namespace shaderlab::classview {

namespace {

std::string fmt(const char* format, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, v);
    return buf;
}

// Coordinates in the viewBox, one decimal.
std::string px(double v) { return fmt("%.1f", v); }

// Grid steps of 1, 2 or 5 times a power of ten, about five of them up to `top`.
int tickStep(int top) {
    if (top <= 6) return 1;
    const double raw = top / 5.0;
    const double p = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * p >= raw) return std::max(1, int(m * p));
    return std::max(1, int(10 * p));
}

}  // namespace

std::string escapeHtml(std::string_view s) { return grader::escapeMarkup(std::string(s)); }

std::string escapeUntrusted(std::string_view s) { return escapeHtml(grader::printableText(s, 2000)); }

std::string urlPath(std::string_view path) {
    static const char* const hex = "0123456789ABCDEF";
    std::string out;
    for (unsigned char c : path) {
        if (std::isalnum(c) || c == '/' || c == '-' || c == '_' || c == '.' || c == '~') {
            out += char(c);
        } else {
            out += '%';
            out += hex[c >> 4];
            out += hex[c & 15];
        }
    }
    return out;
}

std::string clipText(const std::string& s, std::size_t n) {
    std::size_t count = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
        if ((static_cast<unsigned char>(s[i]) & 0xC0) == 0x80) continue;
        if (count++ == n) return s.substr(0, i) + "…";
    }
    return s;
}

std::string safeName(const std::string& s) {
    std::string out;
    for (char c : s)
        out += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.') ? c : '_';
    if (out.empty() || out[0] == '.') out = "_" + out;
    return out;
}

std::string percent(double share) { return fmt("%.0f", std::round(share * 100.0)) + " %"; }

std::string points(double v) {
    std::string s = fmt("%.2f", v);
    while (s.find('.') != std::string::npos && (s.back() == '0' || s.back() == '.')) {
        const bool dot = s.back() == '.';
        s.pop_back();
        if (dot) break;
    }
    return s;
}

const char* statusColor(const std::string& status) {
    if (status == "passed" || status == "graded") return "#1a7f37";
    if (status == "failed") return "#d98e04";
    if (status == "compile_error" || status == "bad_archive") return "#c62828";
    if (status == "link_error" || status == "unsafe_archive") return "#8e1b1b";
    if (status == "timeout" || status == "too_large") return "#7b3fb5";
    if (status == "crashed") return "#444";
    return "#a8a8a8";  // missing, empty, anything new
}

const char* shareColor(double share) {
    if (share < 0.5) return "#c62828";
    if (share < 0.8) return "#d98e04";
    return "#1a7f37";
}

std::string goalSharesSvg(const std::vector<GoalShare>& goals) {
    // Drawn for a card the width of the page: the title on the left, the bar, the numbers.
    const double width = 1100, label = 500, bar = 460, row = 30;
    const double height = goals.size() * row + 4;
    std::string s = "<svg class=\"plot goals\" viewBox=\"0 0 " + px(width) + " " + px(height) +
                    "\" role=\"img\" aria-label=\"share of students meeting each learning goal\">\n";
    for (std::size_t i = 0; i < goals.size(); ++i) {
        const GoalShare& g = goals[i];
        const double y = i * row + 2, share = g.share();
        s += "<g class=\"goal\" data-goal=\"" + escapeHtml(g.id) + "\" data-met=\"" + std::to_string(g.met) +
             "\" data-of=\"" + std::to_string(g.of) + "\"><title>" + escapeHtml(g.title) + " (" +
             escapeHtml(g.id) + ", " + points(g.points) + " points)</title>\n";
        s += "<text class=\"label\" x=\"0\" y=\"" + px(y + 18) + "\">" + escapeHtml(clipText(g.title, 70)) +
             "</text>\n";
        s += "<rect class=\"track\" x=\"" + px(label) + "\" y=\"" + px(y + 5) + "\" width=\"" + px(bar) +
             "\" height=\"18\" rx=\"3\"/>\n";
        s += "<rect class=\"bar\" x=\"" + px(label) + "\" y=\"" + px(y + 5) + "\" width=\"" +
             px(std::max(share * bar, 0.0)) + "\" height=\"18\" rx=\"3\" fill=\"" + shareColor(share) +
             "\"/>\n";
        s += "<text class=\"value\" x=\"" + px(label + bar + 12) + "\" y=\"" + px(y + 19) + "\">" +
             std::to_string(g.met) + " / " + std::to_string(g.of) + " · " + percent(share) +
             "</text>\n</g>\n";
    }
    return s + "</svg>\n";
}

std::string statusBarSvg(const std::vector<StatusCount>& counts) {
    int total = 0;
    for (const StatusCount& c : counts) total += c.count;
    const double width = 640, height = 30;
    std::string s = "<svg class=\"plot statuses\" viewBox=\"0 0 " + px(width) + " " + px(height) +
                    "\" role=\"img\" aria-label=\"statuses\">\n";
    double x = 0;
    for (const StatusCount& c : counts) {
        const double w = total > 0 ? width * c.count / total : 0.0;
        s += "<g class=\"status\" data-status=\"" + escapeHtml(c.status) + "\" data-count=\"" +
             std::to_string(c.count) + "\"><title>" + escapeHtml(c.status) + ": " + std::to_string(c.count) +
             "</title><rect x=\"" + px(x) + "\" y=\"0\" width=\"" + px(w) + "\" height=\"" + px(height) +
             "\" fill=\"" + statusColor(c.status) + "\"/>";
        if (w >= 22)
            s += "<text class=\"inbar\" x=\"" + px(x + w / 2) + "\" y=\"20\" text-anchor=\"middle\">" +
                 std::to_string(c.count) + "</text>";
        s += "</g>\n";
        x += w;
    }
    return s + "</svg>\n";
}

std::string histogramSvg(const Histogram& h, const std::string& unit) {
    const double width = 640, height = 242, left = 40, right = 8, top = 28, bottom = 50;
    const double plot_w = width - left - right, plot_h = height - top - bottom;
    int most = 1;
    for (const Histogram::Bin& b : h.bins) most = std::max(most, b.count);
    const int step = tickStep(most);
    const int y_top = (most + step - 1) / step * step;
    std::string s = "<svg class=\"plot histogram\" viewBox=\"0 0 " + px(width) + " " + px(height) +
                    "\" role=\"img\" aria-label=\"students by " + escapeHtml(unit) + "\">\n";
    s += "<text class=\"axis\" x=\"0\" y=\"11\">students</text>\n";
    for (int t = 0; t <= y_top; t += step) {
        const double y = top + plot_h - plot_h * t / y_top;
        s += "<line class=\"grid\" x1=\"" + px(left) + "\" y1=\"" + px(y) + "\" x2=\"" + px(width - right) +
             "\" y2=\"" + px(y) + "\"/><text class=\"tick\" x=\"" + px(left - 6) + "\" y=\"" + px(y + 4) +
             "\" text-anchor=\"end\">" + std::to_string(t) + "</text>\n";
    }
    const std::size_t n = h.bins.size();
    const double slot = n ? plot_w / n : plot_w;
    const int label_every = slot < 24 ? 2 : 1;
    for (std::size_t i = 0; i < n; ++i) {
        const Histogram::Bin& b = h.bins[i];
        const double bh = plot_h * b.count / y_top, x = left + i * slot;
        const std::string label = h.whole_points ? points(b.from) : points(b.from) + "–" + points(b.to);
        s += "<g class=\"bin\" data-from=\"" + points(b.from) + "\" data-to=\"" + points(b.to) +
             "\" data-count=\"" + std::to_string(b.count) + "\"><title>" + label + " " + escapeHtml(unit) +
             ": " + std::to_string(b.count) + (b.count == 1 ? " student" : " students") + "</title>";
        s += "<rect class=\"binbar\" x=\"" + px(x + slot * 0.1) + "\" y=\"" + px(top + plot_h - bh) +
             "\" width=\"" + px(slot * 0.8) + "\" height=\"" + px(bh) + "\"/>";
        if (b.count > 0)
            s += "<text class=\"count\" x=\"" + px(x + slot / 2) + "\" y=\"" + px(top + plot_h - bh - 5) +
                 "\" text-anchor=\"middle\">" + std::to_string(b.count) + "</text>";
        if (i % label_every == 0 || i + 1 == n)
            s += "<text class=\"tick\" x=\"" + px(x + slot / 2) + "\" y=\"" + px(top + plot_h + 16) +
                 "\" text-anchor=\"middle\">" + label + "</text>";
        s += "</g>\n";
    }
    s += "<line class=\"axisline\" x1=\"" + px(left) + "\" y1=\"" + px(top + plot_h) + "\" x2=\"" +
         px(width - right) + "\" y2=\"" + px(top + plot_h) + "\"/>\n";
    s += "<text class=\"axis\" x=\"" + px(left + plot_w / 2) + "\" y=\"" + px(height - 6) +
         "\" text-anchor=\"middle\">" + escapeHtml(unit) + "</text>\n";
    return s + "</svg>\n";
}

std::string smallBarSvg(int part, int whole, const char* color) {
    const double share = whole > 0 ? double(part) / whole : 0.0;
    return "<svg class=\"small\" viewBox=\"0 0 200 8\" preserveAspectRatio=\"none\" role=\"img\" "
           "aria-label=\"" +
           std::to_string(part) + " of " + std::to_string(whole) +
           "\"><rect class=\"track\" x=\"0\" y=\"0\" width=\"200\" height=\"8\" rx=\"2\"/><rect x=\"0\" "
           "y=\"0\" "
           "width=\"" +
           px(200 * share) + "\" height=\"8\" rx=\"2\" fill=\"" + color + "\"/></svg>";
}

}  // namespace shaderlab::classview
