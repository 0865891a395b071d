// Starter code handed in untouched; see not_attempted.h.
#include "not_attempted.h"

#include <filesystem>
#include <vector>

#include "shaderlab/base/paths.h"
#include "shaderlab/base/student_files.h"

namespace fs = std::filesystem;

namespace shaderlab::grading_detail {

namespace {

// The text as an editor's "save" may leave it: "\r\n" as "\n", no spaces or tabs at the end of a
// line, no blank lines at the end.
std::string normalised(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    std::string line;
    auto endLine = [&]() {
        while (!line.empty() && (line.back() == ' ' || line.back() == '\t' || line.back() == '\r'))
            line.pop_back();
        out += line;
        out += '\n';
        line.clear();
    };
    for (char c : text) {
        if (c == '\n')
            endLine();
        else
            line += c;
    }
    endLine();
    while (out.size() > 1 && out[out.size() - 1] == '\n' && out[out.size() - 2] == '\n') out.pop_back();
    return out;
}

std::string listed(const std::vector<std::string>& names) {
    std::string out;
    for (std::size_t i = 0; i < names.size(); ++i)
        out += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
    return out;
}

}  // namespace

bool untouchedStarter(const LabSpec& spec, const std::string& submission_dir, std::string* message) {
    constexpr std::size_t kMaxBytes = 1u << 20;  // a starter file is small; a larger file is not one
    // The lab folder itself (the corpus's starter run, `check --submission labs`) is drawn and
    // fails, as a lab's author expects to see it: its files are the starter by definition.
    std::error_code ec;
    if (fs::equivalent(fs::path(submission_dir) / spec.id, spec.lab_dir, ec)) return false;
    std::vector<std::string> present;
    bool work_left = false;  // a TODO(student) marker: the starter asks for work (docs/authoring.md)
    for (const std::string& name : spec.student_files) {
        const FileText mine = readStudentFile(submission_dir, spec.id + "/" + name, name, kMaxBytes);
        if (!mine.ok) {
            if (mine.missing) continue;  // absent: it changes nothing of the others
            return false;                // there but unreadable: the grade says why
        }
        const FileText starter = readFile((fs::path(spec.lab_dir) / name).string(), kMaxBytes);
        if (!starter.ok || normalised(starter.text) != normalised(mine.text)) return false;
        present.push_back(name);
        work_left = work_left || starter.text.find("TODO(student)") != std::string::npos;
    }
    if (present.empty() || !work_left) return false;
    // The status says "not attempted"; the message says why, and what to do.
    *message = listed(present) + (present.size() == 1 ? " is" : " are") +
               " the lab's starter code, unchanged: nothing was drawn or graded (0 points). Write your "
               "solution in " +
               (present.size() == 1 ? "it" : "them") + " and grade again";
    return true;
}

}  // namespace shaderlab::grading_detail
