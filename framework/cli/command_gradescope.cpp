// `shaderlab gradescope-bundle` (the autograder zip an instructor uploads to Gradescope) and
// `shaderlab gradescope-run` (what its run_autograder runs for each submission).
//
// The bundle holds a portable shaderlab (scripts/portable-build.sh: one file that runs on any
// x86-64 Linux with glibc 2.31 or later, Gradescope's Ubuntu 22.04 image among them), the chosen
// labs and their reference solutions. Its setup.sh installs Mesa's run-time libraries and nothing
// else: the autograder's image is ready in the time apt takes, with nothing to compile. Gradescope's
// layout (its autograder specification, "Autograder Specifications"): the zip is unpacked into
// /autograder/source, setup.sh runs once, then run_autograder runs for each submission with the
// student's files in /autograder/submission and must write /autograder/results/results.json.
// $SHADERLAB_AUTOGRADER_ROOT stands for /autograder, so that a test can simulate the layout.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "grader/reports/report.h"
#include "shaderlab/batch/batch.h"
#include "shaderlab/grading/grading.h"
#include "shaderlab/lab/lab_catalog.h"
#include "shaderlab/lab/lab_spec.h"

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

namespace shaderlab::cli {

namespace {

// Every regular file below `dir` (symlinks neither followed nor kept), as zip items under `prefix`.
void addFolder(const fs::path& dir, const std::string& prefix, std::vector<batch::ZipItem>* items,
               const std::vector<std::string>& skip = {}) {
    std::error_code ec;
    std::vector<batch::ZipItem> found;
    for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (std::find(skip.begin(), skip.end(), name) != skip.end() || name.rfind(".", 0) == 0) {
            if (it->is_directory(ec)) it.disable_recursion_pending();
            continue;
        }
        if (!it->is_symlink(ec) && it->is_regular_file(ec)) {
            batch::ZipItem item;
            item.name = prefix + it->path().lexically_relative(dir).generic_string();
            item.source_path = it->path().string();
            item.executable =
                (fs::status(it->path(), ec).permissions() & fs::perms::owner_exec) != fs::perms::none;
            found.push_back(std::move(item));
        }
    }
    std::sort(found.begin(), found.end(),
              [](const batch::ZipItem& a, const batch::ZipItem& b) { return a.name < b.name; });
    items->insert(items->end(), found.begin(), found.end());
}

std::string shellQuote(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

const char* kSetupScript = R"sh(#!/usr/bin/env bash
# Gradescope runs this once, when it builds the autograder's image (Ubuntu 22.04): Mesa's run-time
# libraries, which the portable shaderlab in bin/ opens when it renders (llvmpipe, on the CPU).
# Nothing is compiled. Written by `shaderlab gradescope-bundle`.
set -euo pipefail
cd "$(dirname "$0")"
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
# libEGL (glvnd) with Mesa's EGL and drivers: every Debian and Ubuntu names them alike.
packages=(libegl1 libegl-mesa0 libgl1-mesa-dri)
# OSMesa where the distribution still has it (Mesa 25.1 and later do not: EGL draws the same).
if apt-cache show libosmesa6 >/dev/null 2>&1; then packages+=(libosmesa6); fi
$sudo apt-get install -y -qq --no-install-recommends "${packages[@]}"
chmod 755 bin/shaderlab
# The context shaderlab gets: proof, in the image's build log, that it starts and that Mesa renders.
bin/shaderlab info
)sh";

// The marker a portable build carries (cmake/Portable.cmake defines SHADERLAB_PORTABLE_BUILD), in
// two halves, so that only a portable build holds it whole; gradescope-bundle looks for it in the
// program it packs.
constexpr char kMarkerHead[] = "shaderlab-build:";
constexpr char kMarkerTail[] = "portable-glibc-2.31";

bool isPortableProgram() {
#if SHADERLAB_PORTABLE_BUILD
    // Read through a volatile pointer so that the whole marker stays in the program.
    static const char* volatile marker = "shaderlab-build:portable-glibc-2.31";
    return marker[0] != '\0';
#else
    return false;
#endif
}

// The program to put in the bundle: `--binary`, or this program when it is a portable build.
// Empty, with the reason in `error`, when there is none; `warning` when the one given may not run
// on Gradescope's image.
std::string bundledProgram(const std::string& requested, std::string* error, std::string* warning) {
    std::error_code ec;
    if (requested.empty()) {
        if (isPortableProgram()) return fs::read_symlink("/proc/self/exe", ec).string();
        *error =
            "this shaderlab is built for this machine and would not start on Gradescope's image (Ubuntu "
            "22.04): build the portable one (sudo bash scripts/portable-build.sh OUT) and pass --binary "
            "OUT/shaderlab, or run gradescope-bundle with it (docs/instructors.md, \"Gradescope\")";
        return {};
    }
    std::ifstream in(requested, std::ios::binary);
    if (!fs::is_regular_file(requested, ec) || !in) {
        *error = requested + ": --binary must be a shaderlab program (file not found)";
        return {};
    }
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    if (bytes.compare(0, 4,
                      "\x7f"
                      "ELF") != 0) {
        *error = requested + ": --binary must be a shaderlab program (this is not a Linux executable)";
        return {};
    }
    if (bytes.find(std::string(kMarkerHead) + kMarkerTail) == std::string::npos)
        *warning = requested +
                   " is not a portable build (scripts/portable-build.sh): it starts on Gradescope only if "
                   "the libraries it was linked with are there";
    return requested;
}

// A lab's student files, found anywhere in an upload that does not mirror labs/ (a student who
// uploads phong.vert and phong.frag of a one-lab assignment), copied into <into>/<lab>/.
bool stageFlatUpload(const fs::path& upload, const LabSpec& spec, const fs::path& into) {
    bool any = false;
    std::error_code ec;
    for (const std::string& file : spec.student_files) {
        std::vector<fs::path> candidates;
        for (fs::recursive_directory_iterator it(upload, ec), end; !ec && it != end; it.increment(ec)) {
            if (it->path().filename() == fs::path(file).filename() && !it->is_symlink(ec) &&
                it->is_regular_file(ec))
                candidates.push_back(it->path());
        }
        if (candidates.empty()) continue;
        std::sort(candidates.begin(), candidates.end());  // the shallowest first, then by name
        std::stable_sort(candidates.begin(), candidates.end(), [](const fs::path& a, const fs::path& b) {
            return std::distance(a.begin(), a.end()) < std::distance(b.begin(), b.end());
        });
        const fs::path dest = into / spec.id / file;
        fs::create_directories(dest.parent_path(), ec);
        fs::copy_file(candidates.front(), dest, fs::copy_options::overwrite_existing, ec);
        any = any || !ec;
    }
    return any;
}

std::string escapeHtml(const std::string& text) {
    std::string out;
    for (char c : batch::printable(text, 4000)) {
        switch (c) {
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '&':
                out += "&amp;";
                break;
            case '"':
                out += "&quot;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

// A PNG file as a data: URI (RFC 2397, base64 per RFC 4648), while `budget` bytes of URI are left;
// empty when the file is missing or the budget is spent.
std::string pngDataUri(const fs::path& png, std::size_t* budget) {
    std::ifstream in(png, std::ios::binary);
    if (!in) return {};
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    const std::size_t size = 22 + (bytes.size() + 2) / 3 * 4;
    if (bytes.empty() || size > *budget) return {};
    *budget -= size;
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out = "data:image/png;base64,";
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::uint32_t n = static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << 16 |
                                (i + 1 < bytes.size() ? static_cast<unsigned char>(bytes[i + 1]) << 8 : 0) |
                                (i + 2 < bytes.size() ? static_cast<unsigned char>(bytes[i + 2]) : 0);
        out += digits[(n >> 18) & 63];
        out += digits[(n >> 12) & 63];
        out += i + 1 < bytes.size() ? digits[(n >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? digits[n & 63] : '=';
    }
    return out;
}

// Folders the student never named (the staging folder under /tmp, Gradescope's
// /autograder/submission) taken out of every text of the results, so that a message reads
// "01-phong/phong.frag: file not found". `folders` longest first.
void forgetFolders(json* j, const std::vector<std::string>& folders) {
    if (j->is_structured()) {
        for (json& child : *j) forgetFolders(&child, folders);
        return;
    }
    if (!j->is_string()) return;
    std::string text = j->get<std::string>();
    for (const std::string& folder : folders) {
        if (folder.empty()) continue;
        for (const auto& [from, to] :
             {std::pair<std::string, std::string>{folder + "/", ""}, {folder, "your upload"}}) {
            for (std::size_t at = text.find(from); at != std::string::npos;
                 at = text.find(from, at + to.size()))
                text.replace(at, from.size(), to);
        }
    }
    *j = text;
}

}  // namespace

int runGradescopeBundle(const GradescopeBundleArgs& args) {
    std::string labs_root;
    if (!resolveLabsRoot(args.common, &labs_root)) return 2;
    std::string error, warning;
    const std::string program = bundledProgram(args.binary, &error, &warning);
    if (program.empty()) {
        std::cerr << "shaderlab: " << error << "\n";
        return 2;
    }
    if (!warning.empty()) std::cerr << "shaderlab: warning: " << warning << "\n";
    std::error_code ec;
    const std::vector<std::string> all_ids = listLabIds(labs_root);
    const std::vector<std::string> ids = args.common.labs.empty() ? all_ids : args.common.labs;
    for (const std::string& id : ids) {
        const LabSpecResult parsed = parseLabSpec((fs::path(labs_root) / id).string());
        for (const std::string& e : parsed.errors) std::cerr << e << "\n";
        if (!parsed.ok) return 2;
    }
    const fs::path reference = args.reference_root.empty()
                                   ? fs::path(labs_root).parent_path() / "reference_solutions"
                                   : fs::path(args.reference_root);

    std::vector<batch::ZipItem> items;
    items.push_back({"setup.sh", "", kSetupScript, true});
    std::string run = R"sh(#!/usr/bin/env bash
# Gradescope runs this for each submission: the student's files are in /autograder/submission, the
# results go to /autograder/results/results.json. Written by `shaderlab gradescope-bundle`.
# SHADERLAB_AUTOGRADER_ROOT replaces /autograder and SHADERLAB_BIN the program (for tests).
set -uo pipefail
root="${SHADERLAB_AUTOGRADER_ROOT:-/autograder}"
source_dir="$root/source"
bin="${SHADERLAB_BIN:-$source_dir/bin/shaderlab}"
if [ ! -x "$bin" ]; then
  echo "run_autograder: $bin is missing or not executable: was the autograder's zip unpacked whole?" >&2
  exit 2
fi
exec "$bin" gradescope-run --root "$root" --labs "$source_dir/labs" --reference "$source_dir/reference_solutions" \
)sh";
    for (const std::string& id : ids) run += "  --lab " + shellQuote(id) + " \\\n";
    char timeout[32];
    std::snprintf(timeout, sizeof timeout, "%g", args.timeout_s);
    run += "  --visibility " + shellQuote(args.visibility) + " --tests " + shellQuote(args.tests) +
           " --timeout " + timeout + "\n";
    items.push_back({"run_autograder", "", run, true});
    items.push_back({"bin/shaderlab", program, "", true});

    // The labs chosen, the folders they share (scenes, textures), and their reference solutions.
    for (const fs::directory_entry& e : fs::directory_iterator(labs_root, ec)) {
        const std::string name = e.path().filename().string();
        const bool is_lab = std::find(all_ids.begin(), all_ids.end(), name) != all_ids.end();
        if (e.is_regular_file(ec))
            items.push_back({"labs/" + name, e.path().string(), "", false});
        else if (e.is_directory(ec) && (!is_lab || std::find(ids.begin(), ids.end(), name) != ids.end()))
            addFolder(e.path(), "labs/" + name + "/", &items);
    }
    for (const std::string& id : ids)
        if (fs::is_directory(reference / id, ec))
            addFolder(reference / id, "reference_solutions/" + id + "/", &items);

    if (!batch::writeZip(args.out_zip, items, &error)) {
        std::cerr << "shaderlab: " << error << "\n";
        return 2;
    }
    std::printf("%s: %zu files, labs", args.out_zip.c_str(), items.size());
    for (const std::string& id : ids) std::printf(" %s", id.c_str());
    std::printf(
        "\nupload it as the autograder of a Gradescope programming assignment (docs/instructors.md)\n");
    return 0;
}

int runGradescopeRun(const GradescopeRunArgs& args) {
    const auto t0 = std::chrono::steady_clock::now();
    std::string labs_root;
    if (!resolveLabsRoot(args.common, &labs_root)) return 2;
    const fs::path root = args.root;
    const fs::path upload = root / "submission";
    const fs::path results = root / "results";
    std::error_code ec;
    fs::create_directories(results, ec);
    const std::vector<std::string> all_ids = listLabIds(labs_root);
    GradeOptions options;
    options.labs_root = labs_root;
    options.labs = args.common.labs.empty() ? all_ids : args.common.labs;
    options.reference_root = args.reference_root;
    options.limits.timeout_s = args.timeout_s;
    options.backend = chooseBackend(args.common.backend);

    char tmpl[] = "/tmp/shaderlab-gradescope-XXXXXX";
    if (!mkdtemp(tmpl)) {
        std::cerr << "shaderlab: cannot make a temporary folder\n";
        return 2;
    }
    const fs::path work = tmpl;
    options.out_dir = (work / "out").string();
    fs::create_directories(options.out_dir, ec);
    // The upload mirrors labs/ (perhaps inside a folder), or, for one lab, holds its files anywhere.
    std::string submission = batch::unwrapSubmissionRoot(upload.string(), all_ids);
    bool mirrors = false;
    for (const std::string& id : options.labs)
        mirrors = mirrors || fs::is_directory(fs::path(submission) / id, ec);
    if (!mirrors && options.labs.size() == 1) {
        const LabSpecResult parsed = parseLabSpec((fs::path(labs_root) / options.labs[0]).string());
        if (parsed.ok && stageFlatUpload(upload, parsed.spec, work / "staged"))
            submission = (work / "staged").string();
    }
    grader::Report report = gradeSubmission(submission, options);
    report.tool_version = SHADERLAB_VERSION;

    json out = json::parse(grader::reportToGradescope(report, {options.out_dir, 2u << 20}), nullptr, false);
    if (args.tests == "scenes") {
        // One test per scene instead of per goal: the goal's points shared among its scenes.
        // (Goals' outputs are written by grader::reportToGradescope; these are simpler.)
        json tests = json::array();
        for (const json& t : out["tests"])
            if (t.value("output_format", "") == "text") tests.push_back(t);  // a lab that did not render
        std::size_t budget = 2u << 20;  // of embedded pictures in all, as for the goals' tests
        for (const grader::ReportLab& lab : report.labs) {
            for (const grader::ReportScene& s : lab.scenes) {
                std::string html = "<p>" + escapeHtml(s.status == "passed" ? "passed" : s.message) + "</p>\n";
                if (!s.hint.mistake.empty())
                    html += "<p>This looks like a known mistake: " + escapeHtml(s.hint.about) + "</p>\n";
                // A failing scene shows its first wrong image: the student's picture beside the
                // reference's and the difference (a passing image has no difference pictures).
                if (s.status != "passed") {
                    const grader::ReportPass* wrong = nullptr;
                    for (const grader::ReportPass& p : s.passes)
                        if (!p.passed && (wrong == nullptr || p.name == s.first_failing_pass)) wrong = &p;
                    std::string pictures;
                    for (const auto& [label, file] :
                         {std::pair<std::string, std::string>{"yours",
                                                              wrong ? wrong->student_image : s.student_image},
                          {"reference", wrong ? wrong->reference_image : s.reference_image},
                          {"difference (FLIP)", wrong ? wrong->diff_image : s.diff_image}}) {
                        const std::string uri = pngDataUri(fs::path(options.out_dir) / file, &budget);
                        if (!file.empty() && !uri.empty())
                            pictures += "<figure><img src=\"" + uri + "\" alt=\"" + label +
                                        "\" width=\"160\"><figcaption>" + label + "</figcaption></figure>\n";
                    }
                    html += pictures;
                }
                tests.push_back({{"name", lab.id + " / " + s.name},
                                 {"score", s.score},
                                 {"max_score", s.max_score},
                                 {"status", s.status == "passed" ? "passed" : "failed"},
                                 {"output", html},
                                 {"output_format", "html"}});
            }
        }
        out["tests"] = tests;
    }
    std::vector<std::string> folders = {submission, fs::absolute(upload, ec).lexically_normal().string(),
                                        upload.string(), work.string()};
    std::sort(folders.begin(), folders.end(),
              [](const std::string& a, const std::string& b) { return a.size() > b.size(); });
    forgetFolders(&out, folders);
    out["visibility"] = args.visibility;
    out["stdout_visibility"] = "hidden";
    for (json& t : out["tests"]) t["visibility"] = args.visibility;
    out["execution_time"] =
        static_cast<int>(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() + 0.5);
    std::string error;
    const bool ok =
        batch::writeFileAtomically((results / "results.json").string(),
                                   out.dump(2, ' ', false, json::error_handler_t::replace) + "\n", &error);
    fs::remove_all(work, ec);
    if (!ok) {
        std::cerr << "shaderlab: " << error << "\n";
        return 2;
    }
    std::printf("score %.2f / %.2f\n", report.score, report.max_score);
    return 0;
}

}  // namespace shaderlab::cli
