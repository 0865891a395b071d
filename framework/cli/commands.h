// The subcommands of the `shaderlab` program. Each returns the process exit code:
// 0 success, 1 the work ran but something failed (a lab did not compile, a scene failed), 2 the
// command could not run (bad arguments, malformed lab.json, no GL context).
#pragma once

#include <string>
#include <vector>

namespace shaderlab::cli {

struct CommonOptions {
    std::string backend = "osmesa";
    std::string labs_root;  // empty: defaultLabsRoot()
    std::vector<std::string> labs;  // --lab, repeatable; empty: every lab the labs root has
};

struct RenderArgs {
    CommonOptions common;
    std::string submission;
    std::string out_dir;
    bool all_passes = false;
};
int runRender(const RenderArgs& args);

int runInfo(const std::string& backend);

}  // namespace shaderlab::cli
