// summary.json and summary.csv of a batch; see batch.h and docs/instructors.md.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "shaderlab/batch/batch.h"

namespace shaderlab::batch {

namespace {

using json = nlohmann::ordered_json;

constexpr int kSummaryVersion = 1;

json number(double v) { return std::isfinite(v) ? json(std::round(v * 1e4) / 1e4) : json(nullptr); }

json rowJson(const SummaryRow& r) {
    json labs = json::object();
    for (const SummaryLab& l : r.labs)
        labs[l.id] = {{"score", number(l.score)}, {"max_score", number(l.max_score)}, {"status", l.status}};
    return {{"student", r.student}, {"source", r.source},       {"status", r.status},
            {"message", r.message}, {"total", number(r.total)}, {"max_total", number(r.max_total)},
            {"labs", labs},         {"report", r.report}};
}

bool rowFrom(const json& j, SummaryRow* r) {
    if (!j.is_object() || !j.contains("student") || !j["student"].is_string()) return false;
    r->student = j.value("student", "");
    r->source = j.value("source", "");
    r->status = j.value("status", "");
    r->message = j.value("message", "");
    r->total = j.value("total", json()).is_number() ? j["total"].get<double>() : 0.0;
    r->max_total = j.value("max_total", json()).is_number() ? j["max_total"].get<double>() : 0.0;
    r->report = j.value("report", "");
    r->labs.clear();
    const json labs = j.value("labs", json::object());
    if (!labs.is_object()) return false;
    for (const auto& [id, l] : labs.items()) {
        if (!l.is_object()) return false;
        SummaryLab lab;
        lab.id = id;
        lab.score = l.value("score", json()).is_number() ? l["score"].get<double>() : 0.0;
        lab.max_score = l.value("max_score", json()).is_number() ? l["max_score"].get<double>() : 0.0;
        lab.status = l.value("status", "");
        r->labs.push_back(std::move(lab));
    }
    return true;
}

std::string dump(const json& j) { return j.dump(2, ' ', false, json::error_handler_t::replace) + "\n"; }

std::string csvField(std::string s, bool text) {
    // A spreadsheet runs a cell that starts like a formula (CWE-1236).
    if (text && !s.empty() && (s[0] == '=' || s[0] == '+' || s[0] == '-' || s[0] == '@')) s = "'" + s;
    if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

std::string fixed2(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", v);
    return buf;
}

}  // namespace

std::string summaryRowToJson(const SummaryRow& row) { return dump(rowJson(row)); }

bool summaryRowFromJson(const std::string& text, SummaryRow* out) {
    const json j = json::parse(text, nullptr, false);
    return !j.is_discarded() && rowFrom(j, out);
}

std::string summaryToJson(const Summary& summary) {
    json rows = json::array();
    for (const SummaryRow& r : summary.rows) rows.push_back(rowJson(r));
    json j = {{"summary_version", kSummaryVersion},
              {"tool", "shaderlab"},
              {"tool_version", summary.tool_version},
              {"labs", summary.labs},
              {"labs_named", summary.labs_named}};
    // Only a shard says so: a whole batch and a merge of its shards write the same bytes.
    if (summary.shard.count > 0)
        j["shard"] = {{"index", summary.shard.index},
                      {"count", summary.shard.count},
                      {"submissions", summary.shard.submissions},
                      {"list", summary.shard.list}};
    j["submissions"] = rows;
    return dump(j);
}

bool summaryFromJson(const std::string& text, Summary* out, std::string* error) {
    const json j = json::parse(text, nullptr, false);
    if (j.is_discarded() || !j.is_object()) {
        *error = "not a JSON object";
        return false;
    }
    if (j.value("summary_version", 0) != kSummaryVersion) {
        *error = "summary_version " + std::to_string(j.value("summary_version", 0)) + ", expected " +
                 std::to_string(kSummaryVersion);
        return false;
    }
    Summary s;
    s.tool_version = j.value("tool_version", "");
    s.labs_named = j.value("labs_named", json()).is_boolean() && j["labs_named"].get<bool>();
    const json labs = j.value("labs", json::array());
    const json rows = j.value("submissions", json::array());
    if (!labs.is_array() || !rows.is_array()) {
        *error = "'labs' and 'submissions' must be arrays";
        return false;
    }
    for (const json& l : labs) {
        if (!l.is_string()) {
            *error = "'labs' must hold lab ids";
            return false;
        }
        s.labs.push_back(l.get<std::string>());
    }
    if (j.contains("shard")) {
        const json& sh = j["shard"];
        if (!sh.is_object() || !sh.value("index", json()).is_number_integer() ||
            !sh.value("count", json()).is_number_integer() ||
            !sh.value("submissions", json()).is_number_unsigned() || !sh.value("list", json()).is_string() ||
            sh["count"].get<int>() < 1 || sh["index"].get<int>() < 1 ||
            sh["index"].get<int>() > sh["count"].get<int>()) {
            *error = "'shard' must hold index and count (1 <= index <= count), submissions and list";
            return false;
        }
        s.shard.index = sh["index"].get<int>();
        s.shard.count = sh["count"].get<int>();
        s.shard.submissions = sh["submissions"].get<std::size_t>();
        s.shard.list = sh["list"].get<std::string>();
    }
    for (const json& r : rows) {
        SummaryRow row;
        if (!rowFrom(r, &row)) {
            *error = "a submission entry is malformed";
            return false;
        }
        s.rows.push_back(std::move(row));
    }
    *out = std::move(s);
    return true;
}

std::string summaryToCsv(const Summary& summary) {
    std::string out = "student,status,total,max_total";
    for (const std::string& id : summary.labs)
        out += "," + csvField(id, true) + "," + csvField(id + " status", true);
    out += ",message\r\n";
    for (const SummaryRow& r : summary.rows) {
        out += csvField(r.student, true) + "," + csvField(r.status, true) + "," + fixed2(r.total) + "," +
               fixed2(r.max_total);
        for (const std::string& id : summary.labs) {
            const SummaryLab* lab = nullptr;
            for (const SummaryLab& l : r.labs)
                if (l.id == id) lab = &l;
            out += lab ? "," + fixed2(lab->score) + "," + csvField(lab->status, true) : std::string(",,");
        }
        out += "," + csvField(r.message, true) + "\r\n";
    }
    return out;
}

}  // namespace shaderlab::batch
