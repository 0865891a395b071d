// Reading a results folder (summary.json and the report.json of each submission); see
// class_report.h. A report that cannot be read is named and skipped; only a missing or malformed
// summary stops the reading.
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "shaderlab/classview/class_report.h"

namespace fs = std::filesystem;

namespace shaderlab::classview {

namespace {

// Larger files than these are not a batch's: a report of eleven labs is well under a megabyte.
constexpr std::uintmax_t kMaxSummaryBytes = std::uintmax_t(256) << 20;
constexpr std::uintmax_t kMaxReportBytes = std::uintmax_t(64) << 20;

bool readWhole(const fs::path& path, std::uintmax_t max_bytes, std::string* text, std::string* error) {
    std::error_code ec;
    if (!fs::exists(path, ec)) {
        *error = path.string() + ": missing";
        return false;
    }
    if (!fs::is_regular_file(path, ec)) {
        *error = path.string() + ": not a file";
        return false;
    }
    const std::uintmax_t size = fs::file_size(path, ec);
    if (ec || size > max_bytes) {
        *error = path.string() +
                 (ec ? ": cannot read its size" : ": too large (" + std::to_string(size) + " bytes)");
        return false;
    }
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    if (!in) {
        *error = path.string() + ": cannot read";
        return false;
    }
    *text = s.str();
    return true;
}

// A path the summary names, to be read inside the results folder: relative, with no "..".
bool insideResults(const std::string& relative) {
    if (relative.empty() || relative[0] == '/') return false;
    for (const fs::path& part : fs::path(relative))
        if (part == "..") return false;
    return true;
}

// The report of one row; false, with "<file>: <problem>", when there is none to read.
bool readReport(const fs::path& results, const batch::SummaryRow& row, StudentResults* s,
                std::string* error) {
    if (row.report.empty()) {
        *error = (results / "summary.json").string() + ": student \"" + row.student + "\" has no report";
        return false;
    }
    if (!insideResults(row.report)) {
        *error = (results / "summary.json").string() + ": the report of \"" + row.student + "\" (" +
                 row.report + ") is not inside the results folder";
        return false;
    }
    const fs::path path = results / row.report;
    std::string text, why;
    if (!readWhole(path, kMaxReportBytes, &text, error)) return false;
    try {
        if (!grader::reportFromJson(text, &s->report, &why)) {
            *error = path.string() + ": " + why;
            return false;
        }
    } catch (const std::exception& e) {
        // reportFromJson reads fields of the wrong type by throwing.
        *error = path.string() + ": malformed report (" + e.what() + ")";
        return false;
    }
    s->report_dir = path.parent_path().string();
    s->has_report = true;
    return true;
}

}  // namespace

bool readClassResults(const std::string& results_dir, ClassInput* out, std::string* error) {
    std::error_code ec;
    const fs::path results = fs::absolute(results_dir, ec).lexically_normal();
    if (!fs::is_directory(results, ec)) {
        *error = results_dir + ": not a folder (give the results folder of `shaderlab batch` or `merge`)";
        return false;
    }
    const fs::path summary_path = results / "summary.json";
    std::string text, why;
    if (!readWhole(summary_path, kMaxSummaryBytes, &text, &why)) {
        *error = why + " (is " + results_dir + " a results folder of `shaderlab batch` or `merge`?)";
        return false;
    }
    batch::Summary summary;
    bool ok = false;
    try {
        ok = batch::summaryFromJson(text, &summary, &why);
    } catch (const std::exception& e) {
        why = std::string("malformed (") + e.what() + ")";
    }
    if (!ok) {
        *error = summary_path.string() + ": " + why;
        return false;
    }
    ClassInput in;
    in.results_dir = results.string();
    in.tool_version = summary.tool_version;
    in.labs = summary.labs;
    in.labs_named = summary.labs_named;
    for (batch::SummaryRow& row : summary.rows) {
        StudentResults s;
        if (!readReport(results, row, &s, &why)) in.errors.push_back(why);
        s.row = std::move(row);
        in.students.push_back(std::move(s));
    }
    *out = std::move(in);
    return true;
}

}  // namespace shaderlab::classview
