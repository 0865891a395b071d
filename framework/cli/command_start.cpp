// Finding the course a command works on, and `shaderlab start`: a student's own copy of a lab's
// starter files in <course>/work/<lab>/, so the starter code in labs/ stays the starter and
// `check` grades the student's files, in this course folder, wherever the program was built.
#include <filesystem>
#include <iostream>
#include <system_error>

#include "commands.h"
#include "shaderlab/base/paths.h"
#include "shaderlab/lab/lab_spec.h"

namespace fs = std::filesystem;

namespace shaderlab::cli {

bool resolveLabsRoot(const CommonOptions& common, std::string* labs_root) {
    std::error_code ec;
    if (!common.labs_root.empty()) {
        *labs_root = fs::absolute(common.labs_root, ec).lexically_normal().string();
        if (!fs::is_directory(*labs_root, ec)) {
            std::cerr << "shaderlab: " << common.labs_root << ": labs folder not found\n";
            return false;
        }
        return true;
    }
    *labs_root = defaultLabsRoot();
    if (labs_root->empty()) {
        std::cerr << "shaderlab: no course here: neither " << fs::current_path(ec).string()
                  << " nor a folder above it has a labs/ folder with a lab in it. Run this inside the course "
                     "folder, or pass --labs DIR\n";
        return false;
    }
    return true;
}

bool loadCommandLab(const CommonOptions& common, const std::string& id, std::string* labs_root,
                    LabSpecResult* out) {
    if (!resolveLabsRoot(common, labs_root)) return false;
    *out = parseLabSpec((fs::path(*labs_root) / id).string());
    for (const std::string& e : out->errors) std::cerr << e << "\n";
    return out->ok;
}

std::string workRoot(const std::string& labs_root) {
    return (fs::path(labs_root).parent_path() / "work").string();
}

int runStart(const StartArgs& args) {
    std::string labs_root;
    LabSpecResult parsed;
    if (!loadCommandLab(args.common, args.lab, &labs_root, &parsed)) return 2;
    const fs::path into = fs::path(args.into.empty() ? workRoot(labs_root) : args.into) / args.lab;
    std::error_code ec;
    if (!args.force) {
        for (const std::string& f : parsed.spec.student_files) {
            if (fs::exists(into / f, ec)) {
                std::cerr << "shaderlab: " << (into / f).string()
                          << " exists already: your work is kept. Use --force to start over from the starter "
                             "code\n";
                return 2;
            }
        }
    }
    for (const std::string& f : parsed.spec.student_files) {
        fs::create_directories((into / f).parent_path(), ec);
        fs::copy_file(fs::path(parsed.spec.lab_dir) / f, into / f, fs::copy_options::overwrite_existing, ec);
        if (ec) {
            std::cerr << "shaderlab: cannot copy " << f << " into " << into.string() << ": " << ec.message()
                      << "\n";
            return 2;
        }
        std::cout << "  " << (into / f).string() << "\n";
    }
    std::cout << "Your copy of " << args.lab << " is in " << into.string() << ".\n"
              << "Read " << (fs::path(parsed.spec.lab_dir) / "README.md").string()
              << ", edit the files above, then run\n    shaderlab check " << args.lab << "\n";
    return 0;
}

}  // namespace shaderlab::cli
