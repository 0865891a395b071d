// `shaderlab class RESULTS --out DIR`: what the class did not learn, from the results folder of
// `shaderlab batch` or `shaderlab merge`. Reads, counts and writes through the classview library
// (framework/classview); this file only finds the course for the mistakes' pictures and says what
// happened. See docs/instructors.md, "What the class did not learn".
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "shaderlab/base/paths.h"
#include "shaderlab/classview/class_report.h"

namespace fs = std::filesystem;

namespace shaderlab::cli {

namespace {

double msSince(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

void printReteach(const classview::ClassReport& r) {
    if (r.reteach.empty()) {
        std::printf("every student who handed a lab in met all of its goals\n");
        return;
    }
    std::printf("re-teach first:\n");
    for (const classview::ReteachItem& t : r.reteach) {
        std::printf("  %s %s: met by %d of %d", t.lab.c_str(), t.goal.c_str(), t.met, t.of);
        if (!t.mistake.empty())
            std::printf("; most often behind it: %s (%d)", t.mistake.c_str(), t.mistake_students);
        std::printf("\n");
    }
}

}  // namespace

int runClass(const ClassArgs& args) {
    const auto t_start = std::chrono::steady_clock::now();
    std::string labs_root = args.labs_root;
    std::error_code ec;
    if (!labs_root.empty() && !fs::is_directory(labs_root, ec)) {
        std::cerr << "shaderlab: --labs " << labs_root << ": not a folder\n";
        return 2;
    }
    classview::ClassInput input;
    std::string error;
    if (!classview::readClassResults(args.results_dir, &input, &error)) {
        std::cerr << "shaderlab: " << error << "\n";
        return 2;
    }
    if (labs_root.empty()) labs_root = defaultLabsRoot();
    if (labs_root.empty())
        std::cerr
            << "shaderlab: no course found here (--labs): the known mistakes are shown with a student's "
               "picture instead of the lab's hint picture\n";
    for (const std::string& e : input.errors)
        std::cerr << "shaderlab: " << e << " (left out of goals and mistakes)\n";
    const double read_ms = msSince(t_start);

    const auto t_count = std::chrono::steady_clock::now();
    const classview::ClassReport report = classview::aggregateClass(input);
    std::vector<std::string> warnings;
    if (!classview::writeClassPage(report, args.out_dir, labs_root, &warnings, &error)) {
        std::cerr << "shaderlab: " << error << "\n";
        return 2;
    }
    for (const std::string& w : warnings) std::cerr << "shaderlab: warning: " << w << "\n";
    const double write_ms = msSince(t_count);

    printReteach(report);
    const fs::path out = fs::absolute(args.out_dir, ec).lexically_normal();
    std::printf("%d submissions, %zu labs, %zu students who need help; %zu reports unreadable\n",
                report.submissions, report.labs.size(), report.needs_help.size(), input.errors.size());
    std::printf("read in %.0f ms, counted and written in %.0f ms\n", read_ms, write_ms);
    std::printf("class page: %s\n            %s\n", (out / "index.html").c_str(),
                (out / "class.json").c_str());
    return input.errors.empty() ? 0 : 1;
}

}  // namespace shaderlab::cli
