// `shaderlab grade`, `check`, `compare` and `goldens`.
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "commands.h"
#include "grader/base/atomic_file.h"
#include "grader/base/untrusted_text.h"
#include "grader/metrics/scoring.h"
#include "grader/reports/report.h"
#include "shaderlab/base/paths.h"
#include "shaderlab/base/timings.h"
#include "shaderlab/batch/reference_cache.h"
#include "shaderlab/grading/grading.h"
#include "shaderlab/lab/lab_catalog.h"
#include "shaderlab/lab/lab_spec.h"

namespace fs = std::filesystem;

namespace shaderlab::cli {

namespace {

std::string defaultReferenceRoot(const std::string& labs_root) {
    const fs::path p = fs::path(labs_root).parent_path() / "reference_solutions";
    std::error_code ec;
    return fs::is_directory(p, ec) ? p.string() : std::string();
}

// The caches kept between runs in `cache_dir` (default: out/.shaderlab beside the labs) unless
// told not to: the reference's images (shaderlab/batch/reference_cache.h), so that a second grade
// or check of a lab reads them instead of rendering the reference, and Mesa's compiled shaders
// (gl_context.h: useShaderCache), so that llvmpipe does not compile an unchanged shader again.
void useCaches(GradeOptions* options, const std::string& cache_dir, bool no_cache) {
    if (no_cache) return;
    const fs::path dir = cache_dir.empty() ? fs::path(options->labs_root).parent_path() / "out" / ".shaderlab"
                                           : fs::path(cache_dir);
    useShaderCache(fs::absolute(dir / "shader-cache").string());
    if (options->reference_root.empty()) return;
    batch::ReferenceCacheSettings cache;
    cache.dir = (dir / "references").string();
    cache.tool_version = SHADERLAB_VERSION;
    cache.labs_root = options->labs_root;
    cache.reference_root = options->reference_root;
    cache.backend = options->backend;
    options->reference_cache = [cache](const LabSpec& spec, const std::string& renderer) {
        std::string error;  // no entry: the grade renders the reference as it always could
        return batch::cachedReference(cache, spec.id, renderer, &error);
    };
    options->reference_cache_guess = [cache](const LabSpec& spec) {
        return batch::guessCachedReference(cache, spec.id);
    };
}

// Every report is written whole or not at all (grader/atomic_file.h).
bool writeText(const fs::path& path, const std::string& text, std::string* error) {
    return grader::writeFileAtomically(path.string(), text, error);
}

// The names a run writes at the top of its output folder.
const char* const kReportNames[] = {"report.json", "report.html", "results.json", "report.junit.xml"};

// Makes the output folder ready before any rendering, so that a folder the reports cannot go to
// costs seconds, not a whole run: created if need be, writable, no link planted at a report's
// name, and no other shaderlab run writing into it. The lock (flock on <out>/.shaderlab.lock) is
// held until the process ends; a second run on the same folder is refused rather than mixing
// its pictures with the first one's. Returns false with the reason printed.
bool prepareOutput(const fs::path& out) {
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec || !fs::is_directory(out, ec)) {
        std::cerr << "shaderlab: " << out.string() << ": cannot create the output folder"
                  << (ec ? " (" + ec.message() + ")" : std::string()) << "\n";
        return false;
    }
    const fs::path lock = out / ".shaderlab.lock";
    // A process that writes into the same folder again (`watch` checks on every save) keeps the
    // lock it already holds: flock would refuse a second descriptor of the same process.
    static std::set<std::string> held;
    const std::string key = fs::weakly_canonical(lock, ec).string();
    const bool already_held = held.count(key) > 0;
    const int fd = already_held ? -1 : ::open(lock.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (!already_held && fd < 0) {
        std::cerr << "shaderlab: " << out.string() << ": the output folder is not writable ("
                  << std::strerror(errno) << ")\n";
        return false;
    }
    if (already_held) {
        // this process took it on an earlier run
    } else if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
        std::cerr << "shaderlab: " << out.string()
                  << ": another shaderlab run is writing into this folder; wait for it to finish or "
                     "give this one another --out\n";
        close(fd);
        return false;
    } else {
        held.insert(key);  // kept open (and locked) until the process exits
    }
    std::string error;
    const fs::path probe = out / ".shaderlab.write-test";
    if (!grader::writeFileAtomically(probe.string(), "shaderlab\n", &error, false)) {
        std::cerr << "shaderlab: " << out.string() << ": the output folder is not writable: " << error
                  << "\n";
        return false;
    }
    fs::remove(probe, ec);
    for (const char* name : kReportNames) {
        struct stat st {};
        if (lstat((out / name).c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
            std::cerr << "shaderlab: " << (out / name).string()
                      << (S_ISLNK(st.st_mode) ? ": is a symbolic link" : ": is not a regular file")
                      << "; reports are never written through one: remove it or choose another --out\n";
            return false;
        }
    }
    return true;
}

struct Palette {
    const char* green = "";
    const char* red = "";
    const char* bold = "";
    const char* reset = "";
};

Palette palette() {
    Palette p;
    const char* no_color = std::getenv("NO_COLOR");
    if (isatty(STDOUT_FILENO) && !(no_color && *no_color)) {
        p.green = "\033[32m";
        p.red = "\033[31m";
        p.bold = "\033[1m";
        p.reset = "\033[0m";
    }
    return p;
}

std::string formatPsnr(double v) {
    if (std::isinf(v)) return "identical";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f dB", v);
    return buf;
}

void printLab(const grader::ReportLab& lab, bool verbose) {
    const Palette c = palette();
    const bool ok = lab.status == "passed";
    std::printf("%s%s%-8s%s %s  %.2f / %.2f", c.bold, ok ? c.green : c.red, ok ? "PASS" : "FAIL", c.reset,
                lab.id.c_str(), lab.score, lab.max_score);
    if (!ok) std::printf("  (%s)", lab.status.c_str());
    std::printf("\n");
    // A build failure's message repeats its first diagnostic, printed below.
    if (!lab.message.empty() && lab.diagnostics.empty())
        std::printf("    %s\n", grader::printableText(lab.message).c_str());
    for (const grader::ReportDiagnostic& d : lab.diagnostics)
        std::printf("%s\n", grader::formatDiagnostic(d, lab.id + "/", "    ").c_str());
    if (!verbose) return;
    for (const grader::ReportScene& s : lab.scenes) {
        const bool pass = s.status == "passed";
        std::printf("  %s%-4s%s %-28s PSNR %-10s SSIM %.4f  FLIP %.4f  mismatch %5.2f%%\n",
                    pass ? c.green : c.red, pass ? "ok" : "FAIL", c.reset, s.name.c_str(),
                    formatPsnr(s.metrics.psnr_db).c_str(), s.metrics.ssim, s.metrics.flip_mean,
                    100.0 * s.metrics.mismatch_fraction);
        if (!pass && !s.message.empty()) std::printf("       %s\n", s.message.c_str());
        // The same known-mistake hint as the HTML report and the workbench.
        if (!pass && !s.hint.mistake.empty())
            std::printf("       %sThis looks like a known mistake:%s %s\n", c.bold, c.reset,
                        grader::printableText(s.hint.about).c_str());
    }
    // What the points are for: each learning goal, met or not, and where it was not.
    for (const grader::ReportGoal& g : lab.goals) {
        std::printf("  %s%-4s%s goal %-62s %5.2f / %.2f\n", g.met ? c.green : c.red, g.met ? "met" : "MISS",
                    c.reset, g.title.c_str(), g.met ? g.points : 0.0, g.points);
        if (!g.met && !g.not_met_because.empty()) {
            std::printf("       not met because %s %s not met\n",
                        grader::goalsNamed(lab, g.not_met_because).c_str(),
                        g.not_met_because.size() > 1 ? "are" : "is");
        } else if (!g.met) {
            std::string where;
            for (const std::string& f : g.failing) where += (where.empty() ? "" : ", ") + f;
            std::printf("       not met in %s\n", where.c_str());
        }
        const std::string judgement = grader::goalJudgement(g);
        if (!judgement.empty()) std::printf("       %s\n", grader::printableText(judgement).c_str());
    }
}

}  // namespace

namespace {

// The labs a command works on, each checked before any rendering: an unknown lab or a broken
// lab.json is the command's problem (exit 2), not something to grade.
bool selectLabs(const CommonOptions& common, const std::vector<std::string>& wanted, std::string* labs_root,
                std::vector<std::string>* ids) {
    if (!resolveLabsRoot(common, labs_root)) return false;
    *ids = wanted.empty() ? listLabIds(*labs_root) : wanted;
    if (ids->empty()) {
        std::cerr << "shaderlab: no labs found in " << *labs_root << "\n";
        return false;
    }
    bool ok = true;
    for (const std::string& id : *ids) {
        const LabSpecResult parsed = parseLabSpec((fs::path(*labs_root) / id).string());
        for (const std::string& e : parsed.errors) std::cerr << e << "\n";
        ok = ok && parsed.ok;
    }
    return ok;
}

// `final`: the run is over. report.html then embeds its pictures (up to 20 MB) so that it opens
// anywhere on its own, and results.json carries the failing ones (up to 2 MB) in its html output;
// the pages written after each lab before that link the pictures beside them instead, since
// embedding every picture again after every lab made a course's run quadratic in its pictures.
bool writeReports(const grader::Report& report, const fs::path& out, const std::vector<std::string>& formats,
                  bool final, std::string* error) {
    ScopedTiming timing("report_files", "", out.string());
    const std::string embed_root = final ? out.string() : std::string();
    bool ok = writeText(out / "report.json", grader::reportToJson(report), error);
    ok = ok && writeText(out / "report.html", grader::reportToHtml(report, {embed_root, 20u << 20}), error);
    for (const std::string& f : formats) {
        if (f == "gradescope")
            ok = ok && writeText(out / "results.json",
                                 grader::reportToGradescope(report, {embed_root, 2u << 20}), error);
        if (f == "junit")
            ok = ok && writeText(out / "report.junit.xml", grader::reportToJunit(report), error);
    }
    return ok;
}

bool allPassed(const grader::Report& report) {
    for (const grader::ReportLab& lab : report.labs)
        if (lab.status != "passed") return false;
    return !report.labs.empty();
}

}  // namespace

IsolationLimits isolationLimits(const LimitArgs& args) {
    IsolationLimits limits;
    limits.timeout_s = args.timeout_s;
    limits.compile_timeout_s = args.compile_timeout_s;
    limits.memory_bytes = static_cast<std::size_t>(args.memory_mib) << 20;
    return limits;
}

int runGrade(const GradeArgs& args) {
    std::error_code ec;
    if (!fs::is_directory(args.submission, ec)) {
        std::cerr << "shaderlab: " << args.submission << ": submission folder not found\n";
        return 2;
    }
    GradeOptions options;
    options.backend = chooseBackend(args.common.backend);
    if (!selectLabs(args.common, args.common.labs, &options.labs_root, &options.labs)) return 2;
    options.out_dir = args.out_dir;
    options.limits = isolationLimits(args.limits);
    if (!args.no_reference)
        options.reference_root =
            args.reference_root.empty() ? defaultReferenceRoot(options.labs_root) : args.reference_root;
    useCaches(&options, args.cache_dir, args.no_cache);
    const fs::path out = args.out_dir;
    if (!prepareOutput(out)) return 2;

    // The reports are rewritten after every lab, so an interrupted run keeps what it finished.
    bool written = true;
    std::string error;
    grader::Report report = gradeSubmission(args.submission, options, [&](const grader::Report& so_far) {
        printLab(so_far.labs.back(), false);
        grader::Report r = so_far;
        r.tool_version = SHADERLAB_VERSION;
        written = written && writeReports(r, out, args.formats, false, &error);
    });
    report.tool_version = SHADERLAB_VERSION;
    if (!written || !writeReports(report, out, args.formats, true, &error)) {
        std::cerr << "shaderlab: cannot write the reports into " << out.string() << ": " << error << "\n";
        return 2;
    }
    std::printf("score %.2f / %.2f\nreport: %s\n", report.score, report.max_score,
                fs::absolute(out / "report.json").string().c_str());
    std::printf("        %s\n", fs::absolute(out / "report.html").string().c_str());
    return allPassed(report) ? 0 : 1;
}

int runCheck(const CheckArgs& args) {
    GradeOptions options;
    options.backend = chooseBackend(args.common.backend);
    if (!selectLabs(args.common, {args.lab}, &options.labs_root, &options.labs)) return 2;
    options.limits = isolationLimits(args.limits);
    if (!args.no_reference) options.reference_root = defaultReferenceRoot(options.labs_root);
    useCaches(&options, args.cache_dir, args.no_cache);
    // The student's own copy (shaderlab start), never the starter code in labs/.
    const std::string submission = args.submission.empty() ? workRoot(options.labs_root) : args.submission;
    std::error_code ec;
    const fs::path lab_folder = fs::absolute(fs::path(submission) / args.lab, ec).lexically_normal();
    if (!fs::is_directory(lab_folder, ec)) {
        std::cerr << "shaderlab: " << lab_folder.string() << " does not exist";
        if (args.submission.empty())
            std::cerr << ": run `shaderlab start " << args.lab
                      << "` first; it copies the starter code there for you "
                      << "to edit";
        std::cerr << "\n";
        return 2;
    }
    options.out_dir = args.out_dir.empty()
                          ? (fs::path(options.labs_root).parent_path() / "out" / "check").string()
                          : args.out_dir;
    if (!prepareOutput(options.out_dir)) return 2;
    const LabSpecResult parsed = parseLabSpec((fs::path(options.labs_root) / args.lab).string());
    std::printf("checking %s (", lab_folder.string().c_str());
    for (std::size_t i = 0; i < parsed.spec.student_files.size(); ++i)
        std::printf("%s%s", i ? ", " : "", parsed.spec.student_files[i].c_str());
    std::printf(") against %s\n",
                options.reference_root.empty() ? "the stored golden images" : "the reference solution");
    // One line per scene as the render goes, so a slow or stuck shader shows where it is.
    const Palette c = palette();
    options.progress = [&](const std::string&, const std::string& event) {
        std::istringstream in(event);
        std::string kind, scene;
        double ms = 0.0;
        in >> kind >> scene >> ms;
        if (kind == "done")
            std::printf("  %srendered%s %-28s %6.1f ms\n", c.bold, c.reset, scene.c_str(), ms);
        std::fflush(stdout);
    };
    grader::Report report = gradeSubmission(submission, options);
    report.tool_version = SHADERLAB_VERSION;
    for (const grader::ReportLab& lab : report.labs) printLab(lab, true);
    std::string error;
    if (!writeReports(report, options.out_dir, {}, true, &error)) {
        std::cerr << "shaderlab: cannot write the report into " << options.out_dir << ": " << error << "\n";
        return 2;
    }
    std::printf("images and report: %s\n",
                fs::absolute(fs::path(options.out_dir) / "report.html").string().c_str());
    return allPassed(report) ? 0 : 1;
}

int runCompare(const CompareArgs& args) {
    grader::Image a, b;
    std::string err;
    if (!grader::readPng(args.a, &a, &err) || !grader::readPng(args.b, &b, &err)) {
        std::cerr << "shaderlab: " << err << "\n";
        return 2;
    }
    if (a.width != b.width || a.height != b.height) {
        std::cerr << "shaderlab: " << args.a << " is " << a.width << "x" << a.height << " but " << args.b
                  << " is " << b.width << "x" << b.height << "\n";
        return 2;
    }
    grader::Thresholds t;
    t.pixel_tolerance = args.tolerance;
    const grader::ImageVerdict v = grader::judgeImage(a, {}, b, {}, t);
    const grader::MetricSet& m = v.frame;
    if (args.json) {
        // SSIM needs an 11x11 window: for a smaller image it is undefined (null), as in grading.
        nlohmann::ordered_json j = {
            {"reference", args.a},
            {"test", args.b},
            {"width", a.width},
            {"height", a.height},
            {"psnr_db",
             std::isfinite(m.psnr_db) ? nlohmann::ordered_json(m.psnr_db) : nlohmann::ordered_json()},
            {"identical", std::isinf(m.psnr_db)},
            {"ssim", m.ssim_defined ? nlohmann::ordered_json(m.ssim) : nlohmann::ordered_json()},
            {"flip_mean", m.flip_mean},
            {"flip_weighted_median", m.flip_weighted_median},
            {"mismatch_fraction", m.mismatch_fraction},
            {"pixel_tolerance", args.tolerance},
            {"nan_count", v.nan_count}};
        std::cout << j.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << "\n";
    } else {
        char ssim[64];
        std::snprintf(ssim, sizeof ssim, "%.6f", m.ssim);
        std::printf(
            "PSNR      %s\nSSIM      %s\nFLIP mean %.6f\nmismatch  %.4f%% (tolerance %.3f, 1-pixel shift "
            "allowed)\n",
            formatPsnr(m.psnr_db).c_str(),
            m.ssim_defined ? ssim : "undefined (the image is smaller than SSIM's 11x11 window)", m.flip_mean,
            100.0 * m.mismatch_fraction, args.tolerance);
    }
    return 0;
}

int runGoldens(const GoldensArgs& args) {
    std::string labs_root;
    if (!resolveLabsRoot(args.common, &labs_root)) return 2;
    const std::string reference_root =
        args.reference_root.empty() ? (fs::path(labs_root).parent_path() / "reference_solutions").string()
                                    : args.reference_root;
    const Backend backend = chooseBackend(args.common.backend);
    std::vector<std::string> errors =
        writeGoldens(reference_root, labs_root, args.common.labs, backend, args.golden_root);
    const std::string where = args.golden_root.empty() ? labs_root : args.golden_root;
    if (errors.empty()) std::printf("goldens written under %s/*/golden/\n", where.c_str());
    // The hints are graded against the goldens just written, so they come second.
    if (errors.empty() && !args.no_hints) {
        const std::string corpus = args.corpus_root.empty()
                                       ? (fs::path(labs_root).parent_path() / "tests" / "corpus").string()
                                       : args.corpus_root;
        errors = writeHints(labs_root, corpus, reference_root, args.common.labs, args.common.backend,
                            args.golden_root);
        if (errors.empty()) std::printf("known-mistake hints written under %s/*/hints/\n", where.c_str());
    }
    for (const std::string& e : errors) std::cerr << "shaderlab: " << e << "\n";
    return errors.empty() ? 0 : 2;
}

}  // namespace shaderlab::cli
