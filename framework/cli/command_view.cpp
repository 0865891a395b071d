// `shaderlab view` (the window, framework/viewer/), `shaderlab serve` (the page, framework/serve/)
// and `shaderlab watch` (check on every save). A
// grader-only build (SHADERLAB_GRADER_ONLY) has no window: `view` then says so and what to use.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <thread>

#include "commands.h"
#include "shaderlab/base/json_messages.h"
#include "shaderlab/lab/lab_catalog.h"
#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/live/file_watch.h"
#include "shaderlab/render/debug_view.h"
#include "shaderlab/serve/serve.h"
#if SHADERLAB_HAVE_VIEWER
#include "shaderlab/viewer/viewer.h"
#endif

namespace fs = std::filesystem;

namespace shaderlab::cli {

namespace {

// True when the course has lab `id`; otherwise says so once, with the lab the student probably
// meant ("phong" and "01-phogn" both mean 01-phong) and every lab the course has.
bool courseHasLab(const std::string& labs_root, const std::string& id) {
    std::error_code ec;
    if (fs::is_regular_file(fs::path(labs_root) / id / "lab.json", ec)) return true;
    const std::vector<std::string> ids = listLabIds(labs_root);
    std::vector<std::string> names, numbers;  // "phong" and "01" of "01-phong"
    for (const std::string& lab : ids) {
        const std::size_t dash = lab.find('-');
        names.push_back(dash == std::string::npos ? lab : lab.substr(dash + 1));
        numbers.push_back(dash == std::string::npos ? std::string() : lab.substr(0, dash));
    }
    std::string guess = closestMatch(id, ids);
    if (guess.empty()) {
        const std::string name = closestMatch(id, names);
        for (std::size_t i = 0; i < ids.size(); ++i)
            if ((!name.empty() && names[i] == name) || numbers[i] == id ||
                (id.size() == 1 && numbers[i] == "0" + id))
                guess = ids[i];
    }
    std::cerr << "shaderlab: the course in " << labs_root << " has no lab '" << id << "'";
    if (!guess.empty()) std::cerr << ": did you mean " << guess << "?";
    std::cerr << "\n";
    if (ids.empty()) {
        std::cerr << "  it has no labs at all (a lab is a folder with a lab.json)\n";
    } else {
        std::cerr << "  its labs:";
        for (const std::string& lab : ids) std::cerr << " " << lab;
        std::cerr << "\n";
    }
    return false;
}

// The student's submission folder (absolute) when it holds the lab's folder, or a message that
// says how to get one.
bool studentLabFolder(const std::string& submission_arg, const std::string& labs_root, const std::string& lab,
                      std::string* submission) {
    *submission = submission_arg.empty() ? workRoot(labs_root) : submission_arg;
    std::error_code ec;
    const fs::path folder = fs::absolute(fs::path(*submission) / lab, ec).lexically_normal();
    if (fs::is_directory(folder, ec)) {
        *submission = fs::absolute(*submission, ec).lexically_normal().string();
        return true;
    }
    std::cerr << "shaderlab: " << folder.string() << " does not exist";
    if (submission_arg.empty())
        std::cerr << ": run `shaderlab start " << lab
                  << "` first; it copies the starter code there for you to edit";
    std::cerr << "\n";
    return false;
}

// The reference solutions the window and the page compare with: --reference, else
// reference_solutions beside labs/, when it has the lab (absolute); "" for the stored goldens.
std::string referenceFolder(const std::string& reference_arg, const std::string& labs_root,
                            const std::string& lab) {
    const std::string root = reference_arg.empty()
                                 ? (fs::path(labs_root).parent_path() / "reference_solutions").string()
                                 : reference_arg;
    std::error_code ec;
    if (!fs::is_directory(fs::path(root) / lab, ec)) return {};
    return fs::absolute(root, ec).lexically_normal().string();
}

}  // namespace

int runView(const ViewArgs& args) {
#if !SHADERLAB_HAVE_VIEWER
    std::cerr << "shaderlab: this shaderlab is a grader-only build, without the window (built with "
                 "SHADERLAB_GRADER_ONLY, or without GLFW or Dear ImGui); `shaderlab watch "
              << args.lab << "` checks your work on every save in the terminal\n";
    return 2;
#else
    std::string labs_root;
    LabSpecResult parsed;
    if (!resolveLabsRoot(args.common, &labs_root) || !courseHasLab(labs_root, args.lab)) return 2;
    if (!loadCommandLab(args.common, args.lab, &labs_root, &parsed)) return 2;
    viewer::ViewerOptions options;
    options.spec = parsed.spec;
    options.labs_root = fs::absolute(labs_root).lexically_normal().string();
    if (!studentLabFolder(args.submission, labs_root, args.lab, &options.submission_root)) return 2;
    if (!args.scene.empty()) {
        bool known = false;
        for (const SceneSpec& s : parsed.spec.scenes) known = known || s.name == args.scene;
        if (!known) {
            std::cerr << "shaderlab: lab " << args.lab << " has no scene '" << args.scene << "'\n";
            return 2;
        }
    }
    if (!args.no_reference)
        options.reference_root = referenceFolder(args.reference_root, labs_root, args.lab);
    options.backend = chooseBackend(args.common.backend);
    options.timeout_s = args.timeout_s;
    options.scene = args.scene;
    options.image = args.image;
    if (args.orbit.size() == 3) {
        options.orbit.yaw_deg = args.orbit[0];
        options.orbit.pitch_deg = args.orbit[1];
        options.orbit.zoom = args.orbit[2];
    }
    options.view_mode = args.mode;
    options.frames = args.frames;
    options.exit_after_reloads = args.exit_after_reloads;
    options.screenshot = args.screenshot;
    options.screenshot_window = args.screenshot_window;
    options.panel_text = args.panel_text;
    parseDebugView(args.debug, &options.debug_view);  // CLI11 let through only known names
    return viewer::runViewer(options);
#endif
}

int runServe(const ServeArgs& args) {
    std::string labs_root;
    LabSpecResult parsed;
    if (!resolveLabsRoot(args.common, &labs_root) || !courseHasLab(labs_root, args.lab)) return 2;
    if (!loadCommandLab(args.common, args.lab, &labs_root, &parsed)) return 2;
    serve::ServeOptions options;
    serve::WorkbenchOptions& w = options.workbench;
    w.spec = parsed.spec;
    w.labs_root = fs::absolute(labs_root).lexically_normal().string();
    if (!studentLabFolder(args.submission, labs_root, args.lab, &w.submission_root)) return 2;
    if (!args.no_reference) w.reference_root = referenceFolder(args.reference_root, labs_root, args.lab);
    w.backend = chooseBackend(args.common.backend);
    w.view_timeout_s = args.timeout_s;
    w.grade_limits = isolationLimits(args.limits);
    options.host = args.host;
    options.port = args.port;
    return serve::runServe(options);
}

int runWatch(const WatchArgs& args) {
    std::string labs_root, submission;
    if (!resolveLabsRoot(args.check.common, &labs_root) || !courseHasLab(labs_root, args.check.lab)) return 2;
    if (!studentLabFolder(args.check.submission, labs_root, args.check.lab, &submission)) return 2;
    viewer::FolderWatch watch((fs::path(submission) / args.check.lab).string());
    int checks = 0;
    for (;;) {
        const int code = runCheck(args.check);
        ++checks;
        if (code == 2 || (args.max_checks > 0 && checks >= args.max_checks)) return code;
        std::printf("watch: waiting for you to save a file in %s (Ctrl-C stops)\n",
                    (fs::path(submission) / args.check.lab).string().c_str());
        std::fflush(stdout);
        while (!watch.poll()) std::this_thread::sleep_for(std::chrono::milliseconds(50));
        std::string names;
        for (const std::string& f : watch.changedFiles()) names += (names.empty() ? "" : ", ") + f;
        std::printf("\nwatch: %s changed; checking again\n", names.c_str());
        std::fflush(stdout);
    }
}

}  // namespace shaderlab::cli
