// `shaderlab merge`: the results folders of a batch's shards (--shard K/N) joined into one, with
// one summary sorted by student; see results.h. Every shard records which it is and what it was
// cut from (SummaryShard), so an incomplete or mixed set is refused, naming what is wrong. Reads
// summaries, grades nothing.
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

struct Input {
    fs::path dir;
    Summary summary;
};

// Every input's summary.json, read.
bool readInputs(const std::vector<std::string>& inputs, std::vector<Input>* out, std::string* error) {
    std::error_code ec;
    for (const std::string& input : inputs) {
        Input in;
        in.dir = fs::absolute(input, ec).lexically_normal();
        const fs::path file = in.dir / "summary.json";
        if (!fs::is_directory(in.dir, ec)) {
            *error = in.dir.string() + ": no such results folder";
            return false;
        }
        const std::string text = batch_detail::readText(file);
        std::string err;
        if (text.empty()) {
            *error = file.string() +
                     ": not found: the batch of this folder did not finish (run it again: it resumes)";
            return false;
        }
        if (!summaryFromJson(text, &in.summary, &err)) {
            *error = file.string() + ": " + err;
            return false;
        }
        out->push_back(std::move(in));
    }
    return true;
}

std::string shardName(const SummaryShard& s) {
    return std::to_string(s.index) + "/" + std::to_string(s.count);
}

// Shards of one batch, every one of them: the same plan (N and the list of submissions they were
// cut from), each K once, none missing. Results folders that are not shards (two sections graded
// apart) are merged as they are, but never with shards.
bool checkShards(const std::vector<Input>& inputs, std::string* error) {
    const Input& first = inputs.front();
    std::map<int, const Input*> by_index;
    for (const Input& in : inputs) {
        const SummaryShard& s = in.summary.shard;
        const SummaryShard& f = first.summary.shard;
        if ((s.count > 0) != (f.count > 0)) {
            const Input& shard = s.count > 0 ? in : first;
            const Input& whole = s.count > 0 ? first : in;
            *error = shard.dir.string() + " is shard " + shardName(shard.summary.shard) + " of a batch, " +
                     whole.dir.string() + " a whole batch's results: merge the shards of one batch";
            return false;
        }
        if (s.count == 0) continue;
        if (s.count != f.count || s.list != f.list || s.submissions != f.submissions) {
            *error = in.dir.string() + " (shard " + shardName(s) + " of " + std::to_string(s.submissions) +
                     " submissions) and " + first.dir.string() + " (shard " + shardName(f) + " of " +
                     std::to_string(f.submissions) +
                     ") were not cut from one plan: another shard count or another list of submissions (did "
                     "the submissions folder change between the tasks?); grade every shard again into fresh "
                     "folders";
            return false;
        }
        auto [it, fresh] = by_index.emplace(s.index, &in);
        if (!fresh) {
            *error = "shard " + shardName(s) + " is given twice: " + it->second->dir.string() + " and " +
                     in.dir.string();
            return false;
        }
    }
    const int count = first.summary.shard.count;
    if (count == 0) return true;
    std::string missing;
    int n_missing = 0;
    for (int k = 1; k <= count; ++k)
        if (!by_index.count(k)) {
            missing += (missing.empty() ? "" : ", ") + std::to_string(k);
            ++n_missing;
        }
    if (n_missing > 0) {
        *error = "incomplete: " + std::string(n_missing == 1 ? "shard " : "shards ") + missing + " of " +
                 std::to_string(count) + (n_missing == 1 ? " is" : " are") +
                 " missing (a task that never ran, one cancelled while pending say, leaves no results "
                 "folder): grade " +
                 (n_missing == 1 ? "it" : "them") + " (batch --shard K/" + std::to_string(count) +
                 "; with Slurm, sbatch --array=" + missing +
                 " scripts/slurm-batch.sh with the same arguments) and merge again";
        return false;
    }
    return true;
}

// The rows of every input's summary, each with the results folder it came from; `merged` gets
// the labs and the tool version.
bool collectRows(std::vector<Input>& inputs, Summary* merged,
                 std::vector<std::pair<fs::path, SummaryRow>>* rows, std::string* error) {
    std::map<std::string, std::string> seen;  // student -> results folder
    merged->labs = inputs.front().summary.labs;
    merged->labs_named = inputs.front().summary.labs_named;
    merged->tool_version = inputs.front().summary.tool_version;
    for (Input& in : inputs) {
        if (in.summary.labs != merged->labs) {
            *error = (in.dir / "summary.json").string() +
                     ": graded other labs than the first results folder; merge shards of one batch";
            return false;
        }
        for (SummaryRow& r : in.summary.rows) {
            auto [it, fresh] = seen.emplace(r.student, in.dir.string());
            if (!fresh) {
                *error = printable(r.student) + " is in both " + it->second + " and " + in.dir.string();
                return false;
            }
            rows->emplace_back(in.dir, std::move(r));
        }
    }
    const SummaryShard& shard = inputs.front().summary.shard;
    if (shard.count > 0 && rows->size() != shard.submissions) {
        *error = "the shards hold " + std::to_string(rows->size()) +
                 " submissions, the list they were cut from " + std::to_string(shard.submissions) +
                 ": grade every shard again into fresh folders";
        return false;
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
    std::vector<Input> read;
    if (inputs.empty()) {
        *error = "no results folders to merge";
        return false;
    }
    if (!readInputs(inputs, &read, error) || !checkShards(read, error) ||
        !collectRows(read, &merged, &rows, error))
        return false;
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
