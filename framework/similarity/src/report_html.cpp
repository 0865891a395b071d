// index.html, the side-by-side pages and writeSimilarityReport(); see similarity.h.
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "grader/base/atomic_file.h"
#include "grader/base/untrusted_text.h"
#include "grader/reports/report.h"
#include "report_detail.h"

namespace fs = std::filesystem;

namespace shaderlab::similarity {

namespace detail {

namespace {

const char* const kStyle = R"(<style>
body { font: 14px/1.4 system-ui, sans-serif; margin: 1.5em; color: #222; }
table { border-collapse: collapse; margin: 0.5em 0 1.5em; }
th, td { border: 1px solid #ccc; padding: 2px 8px; text-align: left; }
tr.flagged td { background: #fde8e8; }
.muted { color: #777; }
.columns { display: flex; gap: 1em; align-items: flex-start; }
.column { flex: 1; min-width: 0; }
pre { margin: 0 0 1em; background: #fafafa; border: 1px solid #ddd; overflow-x: auto; }
pre span.l { display: block; white-space: pre; }
pre span.n { display: inline-block; width: 4em; color: #999; user-select: none; }
.r0 { background: #ffd7d7; } .r1 { background: #d7ecff; } .r2 { background: #dcf5d6; }
.r3 { background: #fff2c2; } .r4 { background: #ead9ff; } .r5 { background: #ffe1c7; }
.r6 { background: #cff3f0; } .r7 { background: #f3d4ec; }
</style>
)";

std::string percent(double x) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%.0f%%", x * 100.0);
    return buf;
}

// "1 cluster", "3 clusters".
std::string count(std::size_t n, const std::string& noun) {
    return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

std::string who(const StudentRef& s) {
    return htmlEscape(s.student) +
           (s.cohort.empty() ? "" : " <span class=\"muted\">(" + htmlEscape(s.cohort) + ")</span>");
}

void writeMethod(std::ostringstream& o, const SimilarityOptions& opt) {
    o << "<p>Each student's files of a lab are tokenised (comments, layout and the names they chose do not "
         "count), the starter code is masked, and runs of "
      << opt.k << " tokens are fingerprinted by winnowing (window " << opt.w << "; any common run of "
      << opt.k + opt.w - 1
      << " tokens or more is found), after Schleimer, Wilkerson and Aiken, SIGMOD 2003. The score is the "
         "share of the smaller document's fingerprints found in the other. A pair is flagged at "
      << percent(opt.threshold) << " + " << opt.length_margin
      << " / &radic;n or more, n being the smaller document's fingerprints (short solutions written apart "
         "share "
         "much by chance: a short document needs more of it shared), with at least "
      << opt.min_shared
      << " shared fingerprints; a flagged pair at least halfway from its bar to 100 % is strong, and only "
         "strong pairs join students into clusters. A fingerprint in more than max("
      << opt.common_min_documents << ", " << percent(opt.common_share)
      << " of the documents) is a common idiom and ignored. A flag is a reason to read two solutions side "
         "by side, not a verdict.</p>\n";
}

void writeLab(std::ostringstream& o, const SimilarityReport& report, const LabStats& s,
              const std::vector<std::string>& views) {
    o << "<h2 id=\"" << htmlEscape(s.lab) << "\">" << htmlEscape(s.lab) << "</h2>\n<p>"
      << count(s.documents, "document") << " (" << s.empty_documents
      << " with nothing of their own once the starter is masked";
    if (s.short_documents > 0)
        o << ", " << s.short_documents << " with fewer than " << report.options.min_shared
          << " fingerprints of their own: too little to call a copy, read those by hand";
    o << "), " << count(s.pairs_flagged, "flagged pair") << ", " << count(s.clusters, "cluster")
      << ". A student's closest match here scores " << percent(s.median_closest)
      << " in the median: what work written apart shares in this lab.</p>\n";
    bool any_cluster = false;
    for (const Cluster& c : report.clusters) {
        if (c.lab != s.lab) continue;
        if (!any_cluster) o << "<p>Clusters (students joined by strong pairs):</p>\n<ul>\n";
        any_cluster = true;
        o << "<li>" << c.students.size() << " students, up to " << percent(c.max_score) << ": ";
        for (std::size_t i = 0; i < c.students.size(); ++i) o << (i ? ", " : "") << who(c.students[i]);
        o << "</li>\n";
    }
    if (any_cluster) o << "</ul>\n";
    bool any_pair = false;
    for (std::size_t i = 0; i < report.pairs.size(); ++i) {
        const PairResult& p = report.pairs[i];
        if (p.lab != s.lab) continue;
        if (!any_pair)
            o << "<table>\n<tr><th>#</th><th>A</th><th>B</th><th>score</th><th>A in B</th><th>B in A</th>"
                 "<th>shared</th><th>why</th><th>side by side</th></tr>\n";
        any_pair = true;
        o << "<tr" << (p.flagged ? " class=\"flagged\"" : "") << "><td>" << i << "</td><td>" << who(p.a)
          << "</td><td>" << who(p.b) << "</td><td>" << percent(p.score) << "</td><td>" << percent(p.a_in_b)
          << "</td><td>" << percent(p.b_in_a) << "</td><td>" << p.shared << "</td><td>"
          << htmlEscape(pairVerdict(p, report.options)) << "</td><td>";
        if (i < views.size() && !views[i].empty()) o << "<a href=\"" << htmlEscape(views[i]) << "\">view</a>";
        o << "</td></tr>\n";
    }
    if (any_pair) o << "</table>\n";
}

// One student's files, each line numbered, the lines of region r marked with class r(r mod 8).
void writeColumn(std::ostringstream& o, const std::vector<SourceFile>& files,
                 const std::vector<MatchRegion>& regions, bool side_a, const std::string& anchor) {
    for (std::size_t f = 0; f < files.size(); ++f) {
        std::map<std::uint32_t, std::size_t> region_of;  // line -> region, the first region wins
        for (std::size_t r = 0; r < regions.size(); ++r) {
            const LineRange& range = side_a ? regions[r].a : regions[r].b;
            if (range.file != files[f].name) continue;
            for (std::uint32_t l = range.first_line; l <= range.last_line; ++l) region_of.emplace(l, r);
        }
        o << "<h3>" << htmlEscape(files[f].name) << "</h3>\n<pre>";
        std::istringstream lines(files[f].text);
        std::string line;
        for (std::uint32_t n = 1; std::getline(lines, line); ++n) {
            auto it = region_of.find(n);
            o << "<span class=\"l" << (it != region_of.end() ? " r" + std::to_string(it->second % 8) : "")
              << "\" id=\"" << anchor << f << "-" << n << "\"><span class=\"n\">" << n << "</span>"
              << htmlEscape(grader::printableText(line, 2000)) << "</span>";
        }
        o << "</pre>\n";
    }
}

}  // namespace

std::string htmlEscape(const std::string& s) { return grader::escapeMarkup(s); }

std::string indexHtml(const SimilarityReport& report, const std::vector<std::string>& views) {
    std::ostringstream o;
    o << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>Who copied: similarity "
         "report</title>\n"
      << kStyle << "</head><body>\n<h1>Who copied: similarity across the class</h1>\n";
    writeMethod(o, report.options);
    o << "<ul>\n";
    for (const LabStats& s : report.labs)
        o << "<li><a href=\"#" << htmlEscape(s.lab) << "\">" << htmlEscape(s.lab)
          << "</a>: " << count(s.pairs_flagged, "flagged pair") << ", " << count(s.clusters, "cluster")
          << "</li>\n";
    o << "</ul>\n";
    for (const LabStats& s : report.labs) writeLab(o, report, s, views);
    if (!report.notes.empty()) {
        o << "<h2>Notes</h2>\n<ul>\n";
        for (const std::string& n : report.notes) o << "<li>" << htmlEscape(n) << "</li>\n";
        o << "</ul>\n";
    }
    o << "</body></html>\n";
    return o.str();
}

std::string pairHtml(const SimilarityReport& report, std::size_t index) {
    const PairResult& p = report.pairs[index];
    std::ostringstream o;
    o << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" << htmlEscape(p.lab)
      << ": pair " << index << "</title>\n"
      << kStyle << "</head><body>\n<p><a href=\"../../index.html#" << htmlEscape(p.lab)
      << "\">back</a></p>\n<h1>" << htmlEscape(p.lab) << ": " << who(p.a) << " and " << who(p.b)
      << "</h1>\n<p>score " << percent(p.score) << " (" << p.shared << " shared fingerprints; "
      << percent(p.a_in_b) << " of A's found in B, " << percent(p.b_in_a) << " of B's in A).</p>\n<p>"
      << htmlEscape(pairVerdict(p, report.options)) << ".</p>\n<ol>\n";
    for (std::size_t r = 0; r < p.regions.size(); ++r) {
        const MatchRegion& m = p.regions[r];
        o << "<li class=\"r" << r % 8 << "\">A " << htmlEscape(m.a.file) << " lines " << m.a.first_line << "-"
          << m.a.last_line << ", B " << htmlEscape(m.b.file) << " lines " << m.b.first_line << "-"
          << m.b.last_line << " (" << m.fingerprints << " fingerprints)</li>\n";
    }
    o << "</ol>\n<div class=\"columns\">\n";
    const std::vector<SourceFile> none;
    for (const bool side_a : {true, false}) {
        auto it = report.sources.find(sourceKey(p.lab, side_a ? p.a : p.b));
        o << "<div class=\"column\"><h2>" << (side_a ? "A: " : "B: ") << who(side_a ? p.a : p.b) << "</h2>\n";
        writeColumn(o, it != report.sources.end() ? it->second : none, p.regions, side_a, side_a ? "a" : "b");
        o << "</div>\n";
    }
    o << "</div>\n</body></html>\n";
    return o.str();
}

}  // namespace detail

bool writeSimilarityReport(const SimilarityReport& report, const std::string& out_dir, std::string* error,
                           std::size_t max_views_per_lab) {
    std::error_code ec;
    fs::create_directories(out_dir, ec);
    if (ec) {
        *error = out_dir + ": cannot create the folder: " + ec.message();
        return false;
    }
    // Pages of an earlier run would be stale; the folder is the report's own (not followed if a link).
    const fs::path old_pages = fs::path(out_dir) / "pairs";
    if (fs::is_directory(fs::symlink_status(old_pages, ec))) fs::remove_all(old_pages, ec);
    // The views: flagged pairs (they come first in each lab, highest score first), at most
    // max_views_per_lab per lab. File names are numbers, never a student's name.
    std::vector<std::string> views(report.pairs.size());
    std::map<std::string, std::size_t> per_lab;
    for (std::size_t i = 0; i < report.pairs.size(); ++i) {
        const PairResult& p = report.pairs[i];
        if (!p.flagged || per_lab[p.lab]++ >= max_views_per_lab) continue;
        views[i] = "pairs/" + p.lab + "/" + std::to_string(i) + ".html";
    }
    std::set<std::string> folders;
    for (std::size_t i = 0; i < views.size(); ++i) {
        if (views[i].empty()) continue;
        const std::string folder = "pairs/" + report.pairs[i].lab;
        if (folders.insert(folder).second && !grader::createFoldersInside(out_dir, folder, error))
            return false;
        if (!grader::writeFileAtomically(out_dir + "/" + views[i], detail::pairHtml(report, i), error, false))
            return false;
    }
    return grader::writeFileAtomically(out_dir + "/pairs.json", detail::pairsJson(report, views), error) &&
           grader::writeFileAtomically(out_dir + "/index.html", detail::indexHtml(report, views), error);
}

}  // namespace shaderlab::similarity
