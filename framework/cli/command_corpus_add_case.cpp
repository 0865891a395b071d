// `shaderlab corpus add-case LAB NAME`: adds a case to a lab's corpus from a folder of the lab's
// files. Only the student files that differ from the reference solution (byte for byte) are
// stored in tests/corpus/<lab>/<name>/, and the case is appended to cases.json as one more line
// in the file's own layout, then the file is checked against docs/corpus.schema.json and the lab.
// It grades nothing: `shaderlab corpus --lab LAB` says whether the case gets its verdict.
// Refuses, writing nothing, when no file differs, the name is taken, a goal id is unknown, or the
// folder holds a link pointing outside it.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <system_error>
#include <vector>

#include "commands.h"
#include "shaderlab/authoring/corpus_cases.h"
#include "shaderlab/base/json_messages.h"
#include "shaderlab/base/paths.h"
#include "shaderlab/lab/lab_spec.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace shaderlab::cli {

using namespace authoring;

namespace {

constexpr std::size_t kMaxStudentFile = 1u << 20;

bool refuse(const std::string& why) {
    std::cerr << "shaderlab: corpus add-case: " << why << "\n";
    return false;
}

// The exit code of a refusal: the command could not run as asked.
int refused(const std::string& why) {
    refuse(why);
    return 2;
}

// The first link below `dir` (itself included) whose target is not inside `dir`; "" when none.
std::string linkOutside(const fs::path& dir) {
    std::error_code ec;
    const fs::path root = fs::canonical(dir, ec);
    if (ec) return dir.string();
    auto outside = [&](const fs::path& p) {
        const fs::path target = fs::weakly_canonical(p, ec);
        if (ec) return true;
        const fs::path rel = target.lexically_relative(root);
        return rel.empty() || *rel.begin() == "..";
    };
    if (fs::is_symlink(dir, ec) && outside(dir)) return dir.string();
    for (fs::recursive_directory_iterator it(root, fs::directory_options::none, ec), end; !ec && it != end;
         it.increment(ec))
        if (it->is_symlink(ec) && outside(it->path())) return it->path().string();
    return ec ? dir.string() : "";
}

// What the case holds, from the folder the instructor gave.
struct CaseFiles {
    std::vector<std::string> differing;  // student files whose bytes differ from the reference's
    std::vector<std::string> missing;    // student files the folder lacks ("delete")
};

bool compareWithReference(const LabSpec& spec, const fs::path& from, const fs::path& reference,
                          const std::string& kind, CaseFiles* files) {
    std::error_code ec;
    for (const std::string& f : spec.student_files) {
        if (!fs::exists(from / f, ec)) {
            if (kind != "broken")
                return refuse((from / f).string() + " is missing: a " + kind +
                              " provides every student file (a submission without it is "
                              "--kind broken --status missing)");
            files->missing.push_back(f);
            continue;
        }
        if (!fs::is_regular_file(from / f, ec)) return refuse((from / f).string() + " is not a file");
        const FileText mine = readFile((from / f).string(), kMaxStudentFile);
        const FileText theirs = readFile((reference / f).string(), kMaxStudentFile);
        if (!mine.ok) return refuse((from / f).string() + ": " + mine.error);
        if (!theirs.ok) return refuse((reference / f).string() + ": " + theirs.error);
        if (mine.text != theirs.text) files->differing.push_back(f);
    }
    if (files->differing.empty() && files->missing.empty())
        return refuse("every student file of " + from.string() + " (" +
                      std::to_string(spec.student_files.size()) +
                      ") is the reference solution's, byte for byte: there is no case to add");
    return true;
}

// `args` against the lab and its corpus, before anything is written.
bool checkArgs(const CorpusAddCaseArgs& args, const LabSpec& spec, const std::vector<Case>& cases,
               const fs::path& case_dir) {
    std::error_code ec;
    if (!isPlainName(args.name) || args.name.size() > 64)
        return refuse("NAME \"" + args.name +
                      "\" must be 1 to 64 letters, digits, '_' or '-' (it names a folder)");
    for (const Case& c : cases)
        if (c.name == args.name) return refuse(spec.id + " has a case \"" + args.name + "\" already");
    if (fs::exists(case_dir, ec) || fs::is_symlink(case_dir, ec))
        return refuse(case_dir.string() + " exists already");
    if (args.kind == "mistake" && args.fails.empty())
        return refuse("a mistake names with --fails the goals whose idea it breaks");
    if (args.kind == "alternative" && (!args.fails.empty() || !args.status.empty()))
        return refuse("an alternative must pass with full marks: it takes no --fails or --status");
    if (args.kind == "broken" && args.status.empty())
        return refuse("a broken case names with --status the status it must end with");
    if (args.kind == "broken" && !args.fails.empty())
        return refuse("a broken case is judged by its --status, not by goals: it takes no --fails");
    std::vector<std::string> goal_ids;
    for (const GoalSpec& g : spec.goals) goal_ids.push_back(g.id);
    for (const std::string& g : args.fails)
        if (std::find(goal_ids.begin(), goal_ids.end(), g) == goal_ids.end())
            return refuse("--fails " + g + ": " + spec.id + " has no goal \"" + g + "\"" +
                          didYouMean(g, goal_ids));
    if (std::set<std::string>(args.fails.begin(), args.fails.end()).size() != args.fails.size())
        return refuse("--fails names a goal twice");
    return true;
}

std::string quoted(const std::string& s) { return json(s).dump(); }

std::string quotedList(const std::vector<std::string>& items) {
    std::string out = "[";
    for (std::size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + quoted(items[i]);
    return out + "]";
}

// The case as the bundled files write one: its name, kind and verdict on the first line, what it
// is about on the next.
std::string caseText(const CorpusAddCaseArgs& args, const CaseFiles& files, const std::string& indent) {
    std::string head = "{ \"name\": " + quoted(args.name) + ", \"kind\": " + quoted(args.kind);
    if (!args.status.empty()) head += ", \"status\": " + quoted(args.status);
    if (!args.fails.empty()) head += ", \"fails\": " + quotedList(args.fails);
    if (!files.missing.empty()) head += ", \"delete\": " + quotedList(files.missing);
    return indent + head + ",\n" + indent + "  \"about\": " + quoted(args.about) + " }";
}

// Where the top-level "cases" array of a valid cases.json closes, and the indentation of its
// first item; npos when there is no such array.
std::size_t casesArrayEnd(const std::string& text, std::string* indent) {
    int depth = 0, cases_depth = -1;
    std::string last_string;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char ch = text[i];
        if (ch == '"') {
            const std::size_t start = ++i;
            while (i < text.size() && text[i] != '"') i += text[i] == '\\' ? 2 : 1;
            if (depth == 1) last_string = text.substr(start, i - start);
        } else if (ch == '{' || ch == '[') {
            ++depth;
            if (ch == '[' && depth == 2 && last_string == "cases") {
                cases_depth = depth;
                const std::size_t first = text.find_first_not_of(" \t\r\n", i + 1);
                const std::size_t line = text.rfind('\n', first);
                if (first != std::string::npos && line != std::string::npos && line > i)
                    *indent = text.substr(line + 1, first - line - 1);
            }
        } else if (ch == '}' || ch == ']') {
            if (ch == ']' && depth == cases_depth) return i;
            --depth;
        }
    }
    return std::string::npos;
}

// cases.json with the case appended, or a new file holding only it.
bool appendCase(const std::string& old_text, const CorpusAddCaseArgs& args, const CaseFiles& files,
                const std::string& schema_path, std::string* out) {
    if (old_text.empty()) {
        *out = "{\n";
        if (!schema_path.empty()) *out += "  \"$schema\": " + quoted(schema_path) + ",\n";
        *out += "  \"lab\": " + quoted(args.lab) + ",\n  \"cases\": [\n" + caseText(args, files, "    ") +
                "\n  ]\n}\n";
        return true;
    }
    std::string indent = "    ";
    const std::size_t end = casesArrayEnd(old_text, &indent);
    if (end == std::string::npos) return refuse("cannot find the \"cases\" array in cases.json");
    if (indent.find_first_not_of(" \t") != std::string::npos) indent = "    ";
    const std::size_t last = old_text.find_last_not_of(" \t\r\n", end - 1);
    const bool empty = last == std::string::npos || old_text[last] == '[';
    *out = old_text.substr(0, last + 1) + (empty ? "\n" : ",\n") + caseText(args, files, indent) +
           old_text.substr(last + 1);
    return true;
}

bool writeCaseFiles(const fs::path& from, const CaseFiles& files, const fs::path& case_dir) {
    std::error_code ec;
    for (const std::string& f : files.differing) {
        fs::create_directories((case_dir / f).parent_path(), ec);
        const FileText t = readFile((from / f).string(), kMaxStudentFile);
        std::ofstream out(case_dir / f, std::ios::binary);
        out << t.text;
        if (!t.ok || ec || !out.flush()) return refuse((case_dir / f).string() + ": cannot write it");
    }
    return true;
}

// The folder holding the lab's files: `from`, or `from`/<lab> when `from` is a submission holding
// the lab as a folder (reference_solutions/, work/).
fs::path labFolder(const fs::path& from, const LabSpec& spec) {
    std::error_code ec;
    for (const std::string& f : spec.student_files)
        if (fs::exists(from / f, ec)) return from;
    return fs::is_directory(from / spec.id, ec) ? from / spec.id : from;
}

}  // namespace

int runCorpusAddCase(const CorpusAddCaseArgs& args) {
    std::string labs_root;
    LabSpecResult parsed;
    if (!loadCommandLab(args.common, args.lab, &labs_root, &parsed)) return 2;
    const LabSpec& spec = parsed.spec;
    const fs::path course = fs::path(labs_root).parent_path();
    const fs::path corpus_lab =
        (args.corpus_root.empty() ? course / "tests" / "corpus" : fs::path(args.corpus_root)) / spec.id;
    const fs::path reference =
        (args.reference_root.empty() ? course / "reference_solutions" : fs::path(args.reference_root)) /
        spec.id;
    const fs::path cases_file = corpus_lab / "cases.json";
    const fs::path case_dir = corpus_lab / args.name;
    std::error_code ec;

    // The corpus as it is must be valid: the new file is checked whole.
    std::vector<Case> cases;
    std::vector<std::string> errors;
    std::string old_text;
    if (fs::exists(cases_file, ec)) {
        if (!loadCases(cases_file, spec, &cases, &errors)) {
            for (const std::string& e : errors) std::cerr << e << "\n";
            std::cerr << "shaderlab: corpus add-case: " << cases_file.string()
                      << " is not valid as it is; fix it first\n";
            return 2;
        }
        old_text = readFile(cases_file.string(), 1u << 20).text;
    }
    if (!checkArgs(args, spec, cases, case_dir)) return 2;
    if (!fs::is_directory(args.from, ec)) return refused(args.from + ": no such folder");
    if (const std::string link = linkOutside(args.from); !link.empty())
        return refused(link + " is a link to outside " + args.from + ": a case is the files themselves");
    const fs::path from = labFolder(args.from, spec);
    CaseFiles files;
    if (!compareWithReference(spec, from, reference, args.kind, &files)) return 2;

    const fs::path schema_file = course / "docs" / "corpus.schema.json";
    const std::string schema_path =
        fs::exists(schema_file, ec) ? fs::relative(schema_file, fs::absolute(corpus_lab), ec).generic_string()
                                    : "";
    std::string new_text;
    if (!appendCase(old_text, args, files, schema_path, &new_text)) return 2;

    // Written beside the old file and checked whole before it takes its place.
    fs::create_directories(corpus_lab, ec);
    const fs::path staged = corpus_lab / (".cases.json." + std::to_string(::getpid()));
    auto undo = [&] {
        fs::remove(staged, ec);
        fs::remove_all(case_dir, ec);
    };
    if (!writeCaseFiles(from, files, case_dir)) {
        undo();
        return 2;
    }
    std::ofstream(staged, std::ios::binary) << new_text;
    std::vector<Case> written;
    errors.clear();
    if (!loadCases(staged, spec, &written, &errors) || written.size() != cases.size() + 1) {
        for (std::string e : errors) {
            if (e.rfind(staged.string(), 0) == 0) e = cases_file.string() + e.substr(staged.string().size());
            std::cerr << e << "\n";
        }
        undo();
        return refused("the new cases.json would not be valid; nothing was written");
    }
    fs::rename(staged, cases_file, ec);
    if (ec) {
        undo();
        return refused(cases_file.string() + ": " + ec.message());
    }

    std::string stored;
    for (const std::string& f : files.differing) stored += (stored.empty() ? "" : ", ") + f;
    for (const std::string& f : files.missing) stored += (stored.empty() ? "deletes " : "; deletes ") + f;
    std::printf("added %s (%s): %s\n", case_dir.string().c_str(), args.kind.c_str(), stored.c_str());
    const std::string hints =
        args.kind == "mistake" ? "; `shaderlab goldens --lab " + spec.id + "` then refreshes the lab's hints"
                               : "";
    std::printf("next: `shaderlab corpus --lab %s --out out/corpus` checks its verdict%s\n", spec.id.c_str(),
                hints.c_str());
    return 0;
}

}  // namespace shaderlab::cli
