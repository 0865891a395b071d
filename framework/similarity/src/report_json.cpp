// pairs.json; see similarity.h and docs/instructors.md ("Who copied").
#include <cmath>
#include <nlohmann/json.hpp>

#include "report_detail.h"

namespace shaderlab::similarity {

namespace detail {

namespace {

using json = nlohmann::ordered_json;

double rounded(double x) { return std::round(x * 10000.0) / 10000.0; }

json student(const StudentRef& s) {
    return json{{"student", s.student}, {"cohort", s.cohort.empty() ? json(nullptr) : json(s.cohort)}};
}

json range(const LineRange& r) {
    return json{{"file", r.file}, {"first_line", r.first_line}, {"last_line", r.last_line}};
}

json pair(const PairResult& p, const SimilarityOptions& options, std::size_t id, const std::string& view) {
    json regions = json::array();
    for (const MatchRegion& r : p.regions)
        regions.push_back(json{{"a", range(r.a)}, {"b", range(r.b)}, {"fingerprints", r.fingerprints}});
    return json{{"id", id},
                {"lab", p.lab},
                {"a", student(p.a)},
                {"b", student(p.b)},
                {"score", rounded(p.score)},
                {"a_in_b", rounded(p.a_in_b)},
                {"b_in_a", rounded(p.b_in_a)},
                {"shared", p.shared},
                {"a_fingerprints", p.a_fingerprints},
                {"b_fingerprints", p.b_fingerprints},
                {"bar", rounded(p.bar)},
                {"flagged", p.flagged},
                {"strong", p.strong},
                {"why", pairVerdict(p, options)},
                {"view", view.empty() ? json(nullptr) : json(view)},
                {"regions", regions}};
}

}  // namespace

std::string pairsJson(const SimilarityReport& report, const std::vector<std::string>& views) {
    const SimilarityOptions& o = report.options;
    json out;
    out["tool"] = "shaderlab similarity";
    out["method"] =
        json{{"paper",
              "Schleimer, Wilkerson, Aiken: Winnowing: local algorithms for document fingerprinting, "
              "SIGMOD 2003"},
             {"k", o.k},
             {"w", o.w},
             {"guaranteed_match_tokens", o.k + o.w - 1},
             {"threshold", o.threshold},
             {"length_margin", o.length_margin},
             {"min_shared", o.min_shared},
             {"list_from", o.list_from},
             {"common_min_documents", o.common_min_documents},
             {"common_share", o.common_share},
             {"score",
              "shared / min(a_fingerprints, b_fingerprints); flagged when score >= bar = threshold + "
              "length_margin / sqrt(min(a_fingerprints, b_fingerprints)) and shared >= min_shared; strong "
              "(joins a cluster) when score >= (bar + 1) / 2"}};
    json labs = json::array();
    for (const LabStats& s : report.labs)
        labs.push_back(json{{"lab", s.lab},
                            {"documents", s.documents},
                            {"empty_documents", s.empty_documents},
                            {"short_documents", s.short_documents},
                            {"fingerprints", s.fingerprints},
                            {"common_fingerprints", s.common_fingerprints},
                            {"common_limit", s.common_limit},
                            {"pairs_listed", s.pairs_listed},
                            {"pairs_flagged", s.pairs_flagged},
                            {"clusters", s.clusters},
                            {"median_closest", rounded(s.median_closest)}});
    out["labs"] = labs;
    json pairs = json::array();
    for (std::size_t i = 0; i < report.pairs.size(); ++i)
        pairs.push_back(pair(report.pairs[i], o, i, i < views.size() ? views[i] : std::string()));
    out["pairs"] = pairs;
    json clusters = json::array();
    for (const Cluster& c : report.clusters) {
        json members = json::array();
        for (const StudentRef& s : c.students) members.push_back(student(s));
        clusters.push_back(json{{"lab", c.lab}, {"students", members}, {"max_score", rounded(c.max_score)}});
    }
    out["clusters"] = clusters;
    out["notes"] = report.notes;
    // Every string from a student was made printable (valid UTF-8) when it was read; "replace"
    // keeps a stray byte from throwing all the same.
    return out.dump(1, ' ', false, json::error_handler_t::replace) + "\n";
}

}  // namespace detail

std::string similarityToJson(const SimilarityReport& report) { return detail::pairsJson(report, {}); }

}  // namespace shaderlab::similarity
