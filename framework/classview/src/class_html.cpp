// The class page (index.html): what to re-teach first, the class at a glance, one section per lab
// (goals met, points, statuses, known mistakes with their pictures) and the students who need
// help most. One file, no script; pictures are relative links into pictures/ beside it.
#include <sstream>

#include "class_markup.h"

namespace shaderlab::classview {

namespace {

const char* const kStyle =
    ":root{--ok:#1a7f37;--bad:#c62828;--warn:#d98e04;--line:#dde1e6;--muted:#5b6470;--ink:#1f2328}\n"
    "*{box-sizing:border-box}\n"
    "body{font:16px/1.45 system-ui,-apple-system,'Segoe UI',sans-serif;margin:0;background:#f3f4f6;"
    "color:var(--ink)}\n"
    "main{max-width:1180px;margin:0 auto;padding:1.2em 1em 2em}\n"
    "h1{font-size:1.7em;margin:.1em 0 .1em}\n"
    "h2{font-size:1.3em;margin:0 0 .5em}\n"
    "h3{font-size:1.02em;margin:0 0 .6em;color:#33393f}\n"
    "a{color:#0b57d0}\n"
    ".meta{color:var(--muted);font-size:.9em;overflow-wrap:anywhere}\n"
    ".card{background:#fff;border:1px solid var(--line);border-radius:8px;padding:1em 1.2em;margin:1em 0}\n"
    ".reteach{border-left:6px solid var(--bad)}\n"
    ".reteach ol{margin:.4em 0 0;padding:0;list-style:none;counter-reset:item}\n"
    ".reteach li{display:flex;gap:1em;align-items:flex-start;padding:.7em 0;border-top:1px solid #eef0f2;"
    "counter-increment:item}\n"
    ".reteach li:first-child{border-top:0}\n"
    ".reteach li::before{content:counter(item);font-weight:700;font-size:1.3em;color:var(--bad);"
    "min-width:1.2em}\n"
    ".reteach .pic{flex:0 0 auto;display:flex;gap:.4em}\n"
    ".reteach .pic img{width:96px}\n"
    ".goaltitle{font-weight:650;font-size:1.05em}\n"
    ".share{font-weight:650}\n"
    ".behind{margin-top:.25em}\n"
    ".grid{display:grid;grid-template-columns:repeat(auto-fit,minmax(420px,1fr));gap:0 1em}\n"
    ".grid>.card{margin:.5em 0}\n"
    "section.lab{margin-top:2.2em}\n"
    "section.lab>h2{border-bottom:2px solid var(--line);padding-bottom:.2em}\n"
    ".labid{color:var(--muted);font-weight:500}\n"
    "nav{display:flex;flex-wrap:wrap;gap:.4em;margin:.6em 0}\n"
    "nav a{background:#fff;border:1px solid var(--line);border-radius:999px;padding:.15em .7em;"
    "text-decoration:none;font-size:.9em}\n"
    "svg.plot{display:block;width:100%;height:auto;overflow:visible}\n"
    "svg.plot text{font:13px system-ui,-apple-system,'Segoe UI',sans-serif;fill:#33393f}\n"
    "svg.plot text.value,svg.plot text.count{font-weight:600}\n"
    "svg.plot text.tick,svg.plot text.axis{fill:var(--muted);font-size:12px}\n"
    "svg.plot text.inbar{fill:#fff;font-weight:700}\n"
    "svg .track{fill:#eceff3}\n"
    "svg .binbar{fill:#3b6fd8}\n"
    "svg .grid{stroke:#e6e8eb;stroke-width:1}\n"
    "svg .axisline{stroke:#8a9199;stroke-width:1}\n"
    "svg.small{display:block;width:100%;height:8px;margin:.25em 0}\n"
    ".legend{display:flex;flex-wrap:wrap;gap:.3em 1em;margin:.6em 0 "
    "0;padding:0;list-style:none;font-size:.92em}\n"
    ".legend i{display:inline-block;width:.8em;height:.8em;border-radius:2px;margin-right:.35em;"
    "vertical-align:-.05em}\n"
    ".mistakes{display:grid;grid-template-columns:repeat(auto-fill,minmax(260px,1fr));gap:1em}\n"
    ".mistake{border:1px solid #eceef1;border-radius:6px;padding:.7em;background:#fcfcfd}\n"
    ".pair{display:flex;gap:.4em;margin-bottom:.5em}\n"
    "figure{margin:0;flex:1 1 0;min-width:0}\n"
    "img{display:block;width:100%;height:auto;image-rendering:pixelated;border:1px solid #9aa0a6;"
    "background:#000;border-radius:3px}\n"
    "figcaption{font-size:.78em;color:var(--muted);margin-top:.2em;text-align:center}\n"
    ".mname{font-family:ui-monospace,Menlo,Consolas,monospace;font-weight:600;font-size:.95em;"
    "overflow-wrap:anywhere}\n"
    ".count{font-weight:650}\n"
    ".about{font-size:.92em;margin:.2em 0}\n"
    "table{border-collapse:collapse;width:100%}\n"
    "th,td{padding:.35em .6em;text-align:left;vertical-align:top;border-bottom:1px solid #eef0f2}\n"
    "th{font-weight:600;border-bottom:2px solid var(--line);font-size:.92em}\n"
    "td.num{white-space:nowrap}\n"
    "td.goals{min-width:9em}\n"
    "details summary{cursor:pointer;color:#0b57d0;margin-top:.6em}\n"
    ".errors{border-left:6px solid var(--warn)}\n"
    ".none{color:var(--muted);font-style:italic}\n"
    "footer{color:var(--muted);font-size:.85em;margin:2em 0 1em}\n"
    "@media (max-width:600px){body{font-size:15px}main{padding:.5em}.grid{grid-template-columns:1fr}"
    ".reteach li{flex-wrap:wrap}}\n";

std::string plural(int n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

std::string legend(const std::vector<StatusCount>& counts) {
    std::string s = "<ul class=\"legend\">";
    for (const StatusCount& c : counts)
        s += "<li data-status=\"" + escapeHtml(c.status) + "\" data-count=\"" + std::to_string(c.count) +
             "\"><i style=\"background:" + statusColor(c.status) + "\"></i>" + escapeHtml(c.status) + " <b>" +
             std::to_string(c.count) + "</b></li>";
    return s + "</ul>\n";
}

std::string picture(const std::string& src, const std::string& alt, const std::string& caption) {
    if (src.empty()) return "";
    return "<figure><img src=\"" + escapeHtml(urlPath(src)) + "\" alt=\"" + escapeHtml(alt) +
           "\"><figcaption>" + escapeHtml(caption) + "</figcaption></figure>";
}

const MistakeTally* findMistake(const ClassReport& r, const std::string& lab, const std::string& mistake) {
    for (const LabClass& l : r.labs)
        if (l.id == lab)
            for (const MistakeTally& t : l.mistakes)
                if (t.mistake == mistake) return &t;
    return nullptr;
}

void reteachSection(const ClassReport& r, std::ostringstream& h) {
    h << "<section class=\"card reteach\" id=\"reteach\">\n<h2>Re-teach first</h2>\n"
      << "<p class=\"meta\">The learning goals that the most of the students who handed the lab in "
         "failed on their own work for it, and the known mistake most often behind each. A goal lost only "
         "because another goal it rests on was not met counts under that goal; goals missed only where a "
         "lab did not render (a compile error, a timeout) are left out: those students are in "
         "&ldquo;Students who need help&rdquo;.</p>\n";
    if (r.reteach.empty()) {
        h << "<p class=\"none\">No student whose lab rendered failed a goal on their own work.</p>\n"
             "</section>\n";
        return;
    }
    h << "<ol>\n";
    for (const ReteachItem& t : r.reteach) {
        const double share = t.of > 0 ? double(t.met) / t.of : 0.0;
        h << "<li class=\"item\" data-lab=\"" << escapeHtml(t.lab) << "\" data-goal=\"" << escapeHtml(t.goal)
          << "\" data-met=\"" << t.met << "\" data-of=\"" << t.of << "\" data-own-failed=\"" << t.own_failed
          << "\">";
        const MistakeTally* m = t.mistake.empty() ? nullptr : findMistake(r, t.lab, t.mistake);
        if (m && !m->mistake_picture.empty())
            h << "<div class=\"pic\">" << picture(m->expected_picture, "expected", "expected")
              << picture(m->mistake_picture, t.mistake,
                         m->mistake_picture_is_students ? "a student's" : "the mistake")
              << "</div>";
        h << "<div><div class=\"goaltitle\">" << escapeHtml(t.goal_title) << "</div>"
          << "<div class=\"meta\"><a href=\"#lab-" << escapeHtml(safeName(t.lab)) << "\">"
          << escapeHtml(t.lab) << "</a> · " << escapeHtml(t.lab_title) << " · goal <code>"
          << escapeHtml(t.goal) << "</code></div>"
          << "<div><span class=\"share\" style=\"color:" << shareColor(share) << "\">met by " << t.met
          << " of " << t.of << " (" << percent(share) << ")</span>; failed on their own work by "
          << plural(t.own_failed, "student", "students") << "</div><div class=\"behind\">";
        if (t.mistake.empty())
            h << "No known mistake was recognised behind it: look at these students' reports.";
        else
            h << "Most often behind it: <span class=\"mname\">" << escapeHtml(t.mistake) << "</span> ("
              << plural(t.mistake_students, "student", "students") << "): " << escapeHtml(t.about);
        h << "</div>";
        if (!t.also_goals.empty()) {
            h << "<div class=\"meta also\">The same mistake is behind ";
            for (std::size_t i = 0; i < t.also_goals.size(); ++i)
                h << (i ? ", " : "") << "<code>" << escapeHtml(t.also_goals[i]) << "</code>";
            h << " too.</div>";
        }
        h << "</div></li>\n";
    }
    h << "</ol>\n</section>\n";
}

void overviewSection(const ClassReport& r, std::ostringstream& h) {
    h << "<div class=\"grid\" id=\"overview\">\n<div class=\"card\"><h3>Submissions</h3>\n"
      << statusBarSvg(r.submission_statuses) << legend(r.submission_statuses)
      << "<p class=\"meta\">graded, or refused as <code>shaderlab batch</code> recorded it: empty (no lab "
         "folder), "
         "bad_archive, unsafe_archive, too_large.</p></div>\n"
      << "<div class=\"card\"><h3>Total points of each submission (of " << points(r.max_total) << ")</h3>\n"
      << histogramSvg(r.totals, "points") << "</div>\n</div>\n";
    if (r.labs.size() > 1) {
        h << "<nav>";
        for (const LabClass& l : r.labs)
            h << "<a href=\"#lab-" << escapeHtml(safeName(l.id)) << "\">" << escapeHtml(l.id) << "</a>";
        h << "</nav>\n";
    }
}

void goalDetails(const LabClass& l, std::ostringstream& h) {
    h << "<details><summary>What is behind the unmet goals</summary>\n<table><thead><tr><th>goal</th>"
         "<th>not met</th><th>own work failed</th><th>known mistakes there (students)</th><th>no known "
         "mistake</th><th>only because of another goal</th><th>did not render</th></tr></thead><tbody>\n";
    for (const GoalShare& g : l.goals) {
        h << "<tr><td><code>" << escapeHtml(g.id) << "</code></td><td class=\"num\">" << g.of - g.met
          << "</td><td class=\"num\">" << g.own_failed << "</td><td>";
        for (std::size_t i = 0; i < g.mistakes.size(); ++i)
            h << (i ? ", " : "") << "<span class=\"mname\">" << escapeHtml(g.mistakes[i].mistake)
              << "</span> " << g.mistakes[i].students;
        h << "</td><td class=\"num\">" << g.unexplained << "</td><td class=\"num\">" << g.failed_because
          << "</td><td class=\"num\">" << g.not_rendered << "</td></tr>\n";
    }
    h << "</tbody></table></details>\n";
}

void mistakesCard(const LabClass& l, std::ostringstream& h) {
    h << "<div class=\"card\"><h3>Known mistakes recognised</h3>\n";
    if (l.mistakes.empty()) {
        h << "<p class=\"none\">No known mistake was recognised in this lab.</p></div>\n";
        return;
    }
    h << "<div class=\"mistakes\">\n";
    for (const MistakeTally& t : l.mistakes) {
        h << "<div class=\"mistake\" data-mistake=\"" << escapeHtml(t.mistake) << "\" data-students=\""
          << t.students << "\">";
        if (!t.expected_picture.empty() || !t.mistake_picture.empty())
            h << "<div class=\"pair\">" << picture(t.expected_picture, "expected: " + t.scene, "expected")
              << picture(t.mistake_picture, t.mistake,
                         t.mistake_picture_is_students ? "a student's picture" : "this mistake")
              << "</div>";
        h << "<div class=\"mname\">" << escapeHtml(t.mistake) << "</div>"
          << "<div><span class=\"count\">" << plural(t.students, "student", "students") << "</span> of "
          << l.handed_in << "</div>" << smallBarSvg(t.students, l.handed_in, "#c62828")
          << "<div class=\"about\">" << escapeHtml(t.about) << "</div><div class=\"meta\">";
        if (!t.goals.empty()) {
            h << "behind ";
            for (std::size_t i = 0; i < t.goals.size(); ++i) h << (i ? ", " : "") << escapeHtml(t.goals[i]);
            h << " · ";
        }
        h << "scene " << escapeHtml(t.scene) << "</div></div>\n";
    }
    h << "</div></div>\n";
}

void labSection(const LabClass& l, std::ostringstream& h) {
    h << "<section class=\"lab\" id=\"lab-" << escapeHtml(safeName(l.id)) << "\" data-lab=\""
      << escapeHtml(l.id) << "\">\n<h2><span class=\"labid\">" << escapeHtml(l.id) << "</span> "
      << escapeHtml(l.title) << "</h2>\n"
      << "<p class=\"meta\">handed in by " << l.handed_in << " of " << l.students;
    if (l.not_attempted > 0) h << " (" << l.not_attempted << " more handed in the starter code untouched)";
    if (l.handed_in > 0)
        h << " · mean " << points(l.mean) << ", median " << points(l.median) << " of " << points(l.max_score)
          << " points";
    h << "</p>\n<div class=\"card\"><h3>Learning goals met, of those who handed it in</h3>\n";
    if (l.goals.empty()) {
        h << "<p class=\"none\">No report lists this lab's goals: no submission rendered it.</p>\n";
    } else {
        h << goalSharesSvg(l.goals);
        goalDetails(l, h);
    }
    h << "</div>\n<div class=\"grid\">\n<div class=\"card\"><h3>Points, of those who handed it in (of "
      << points(l.max_score) << ")</h3>\n"
      << histogramSvg(l.points, "points") << "</div>\n<div class=\"card\"><h3>Statuses</h3>\n"
      << statusBarSvg(l.statuses) << legend(l.statuses)
      << "<p class=\"meta\">passed and failed: rendered and judged; compile_error, link_error: the shaders "
         "did "
         "not build; timeout, crashed: the render was stopped or died; missing: not handed in, or a file "
         "absent; not_attempted: the starter code, untouched (not graded, no known mistake).</p></div>\n"
         "</div>\n";
    mistakesCard(l, h);
    h << "</section>\n";
}

void helpSection(const ClassReport& r, const std::string& results_href, std::ostringstream& h) {
    constexpr std::size_t kShown = 25;
    h << "<section class=\"card\" id=\"help\">\n<h2>Students who need help</h2>\n"
      << "<p class=\"meta\">Those with a lab of the class not handed in, not attempted, not built or not "
         "rendered, or below "
      << percent(kHelpBelowShare)
      << " of its points, or whose archive was refused. "
         "Fewest learning goals met first (a lab not handed in or not rendered meets none), then the most "
         "timeouts.</p>\n";
    if (r.needs_help.empty()) {
        h << "<p class=\"none\">No student: every lab of the class was handed in, rendered and earned at "
             "least "
          << percent(kHelpBelowShare) << " of its points.</p>\n</section>\n";
        return;
    }
    h << "<table><thead><tr><th>student</th><th>goals met</th><th>points</th><th>what went wrong</th></tr>"
         "</thead><tbody>\n";
    for (std::size_t i = 0; i < r.needs_help.size() && i < kShown; ++i) {
        const StudentNeed& n = r.needs_help[i];
        const double share = n.goals_total > 0 ? double(n.goals_met) / n.goals_total : 0.0;
        h << "<tr data-student=\"" << escapeUntrusted(n.student) << "\" data-goals-met=\"" << n.goals_met
          << "\" data-timeouts=\"" << n.timeouts << "\"><td>";
        if (!results_href.empty() && !n.report_html.empty())
            h << "<a href=\"" << escapeHtml(urlPath(results_href + n.report_html)) << "\">"
              << escapeUntrusted(n.student) << "</a>";
        else
            h << escapeUntrusted(n.student);
        h << "</td><td class=\"goals\">" << n.goals_met << " of " << n.goals_total
          << smallBarSvg(n.goals_met, n.goals_total, shareColor(share)) << "</td><td class=\"num\">"
          << points(n.total) << " / " << points(n.max_total) << "</td><td>";
        for (const std::string& reason : n.reasons) h << "<div>" << escapeHtml(reason) << "</div>";
        if (!n.message.empty()) h << "<div class=\"meta\">" << escapeUntrusted(n.message) << "</div>";
        h << "</td></tr>\n";
    }
    h << "</tbody></table>\n";
    if (r.needs_help.size() > kShown)
        h << "<p class=\"meta\">and " << r.needs_help.size() - kShown << " more in class.json.</p>\n";
    h << "</section>\n";
}

}  // namespace

std::string classToHtml(const ClassReport& r, const std::string& results_href) {
    std::ostringstream h;
    h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      << "<title>What the class did not learn: " << plural(r.submissions, "submission", "submissions")
      << "</title>\n<style>\n"
      << kStyle << "</style>\n</head>\n<body>\n<main>\n<header><h1>What the class did not learn</h1>\n"
      << "<p class=\"meta\">" << plural(r.submissions, "submission", "submissions") << " · "
      << plural(int(r.labs.size()), "lab", "labs") << " · from <code>" << escapeUntrusted(r.results_dir)
      << "</code></p></header>\n";
    reteachSection(r, h);
    overviewSection(r, h);
    for (const LabClass& l : r.labs) labSection(l, h);
    helpSection(r, results_href, h);
    if (!r.errors.empty()) {
        h << "<section class=\"card errors\" id=\"errors\"><h2>Reports that could not be read</h2>\n"
          << "<p class=\"meta\">These students are counted in the statuses and points above (from "
             "summary.json), "
             "not in the goals or mistakes.</p><ul>\n";
        for (const std::string& e : r.errors) h << "<li>" << escapeUntrusted(e) << "</li>\n";
        h << "</ul></section>\n";
    }
    h << "<footer>Written by <code>shaderlab class</code>";
    if (!r.tool_version.empty()) h << " (the batch: shaderlab " << escapeHtml(r.tool_version) << ")";
    h << ". The counts are in class.json beside this page.</footer>\n</main>\n</body>\n</html>\n";
    return h.str();
}

}  // namespace shaderlab::classview
