// `shaderlab merge`: the results folders of a batch's shards (--shard K/N) joined into one, with
// one summary sorted by student; see results.h. Reads summaries, grades nothing.
#include <algorithm>
#include <filesystem>
#include <map>
#include <utility>

#include "batch_detail.h"
#include "shaderlab/batch/batch.h"
#include "shaderlab/batch/results.h"

namespace fs = std::filesystem;

namespace shaderlab::batch {

namespace {

// The rows of every input's summary, each with the results folder it came from; `merged` gets
// the labs and the tool version.
bool readShards(const std::vector<std::string>& inputs, Summary* merged,
                std::vector<std::pair<fs::path, SummaryRow>>* rows, std::string* error) {
    std::map<std::string, std::string> seen;  // student -> results folder
    std::error_code ec;
    for (const std::string& input : inputs) {
        const fs::path in = fs::absolute(input, ec).lexically_normal();
        const std::string text = batch_detail::readText(in / "summary.json");
        Summary s;
        std::string err;
        if (text.empty() || !summaryFromJson(text, &s, &err)) {
            *error = (in / "summary.json").string() + ": " + (text.empty() ? "not found" : err);
            return false;
        }
        if (merged->labs.empty() && merged->rows.empty()) {
            merged->labs = s.labs;
            merged->tool_version = s.tool_version;
        } else if (s.labs != merged->labs) {
            *error = (in / "summary.json").string() +
                     ": graded other labs than the first results folder; merge shards of one batch";
            return false;
        }
        for (SummaryRow& r : s.rows) {
            auto [it, fresh] = seen.emplace(r.student, in.string());
            if (!fresh) {
                *error = printable(r.student) + " is in both " + it->second + " and " + in.string();
                return false;
            }
            rows->emplace_back(in, std::move(r));
        }
    }
    return true;
}

}  // namespace

bool mergeResults(const std::vector<std::string>& inputs, const std::string& out_dir, MergeResult* result,
                  std::string* error) {
    Summary merged;
    std::error_code ec;
    const fs::path out = fs::absolute(out_dir, ec).lexically_normal();
    std::vector<std::pair<fs::path, SummaryRow>> rows;
    if (!readShards(inputs, &merged, &rows, error)) return false;
    fs::create_directories(out, ec);
    std::string write_error;
    if (!fs::is_directory(out, ec) ||
        !writeFileAtomically((out / ".shaderlab-write-test").string(), "ok\n", &write_error)) {
        *error = out.string() + ": cannot write there " + write_error;
        return false;
    }
    fs::remove(out / ".shaderlab-write-test", ec);
    FolderLock lock;
    if (!batch_detail::lockStateFolder(out, &lock, error)) return false;
    std::sort(rows.begin(), rows.end(),
              [](const auto& a, const auto& b) { return a.second.student < b.second.student; });
    for (auto& [in, row] : rows) {
        // The report folders come along (hard links where possible) unless they are already there.
        const std::string folder = fs::path(row.report).parent_path().string();
        if (!folder.empty() && in != out && folder.find("..") == std::string::npos) {
            const fs::path dest = out / folder;
            fs::remove_all(dest, ec);
            if (!linkTree((in / folder).string(), dest.string(), error)) return false;
        }
        merged.rows.push_back(std::move(row));
    }
    std::string summary_error;
    if (!writeSummary(out, merged, &summary_error)) {
        *error = "cannot write the summary: " + summary_error;
        return false;
    }
    result->submissions = merged.rows.size();
    result->summary_csv = (out / "summary.csv").string();
    return true;
}

}  // namespace shaderlab::batch
