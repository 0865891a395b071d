// Running a command line from a test, the way the tests that drive the shaderlab program do:
// stdout and stderr together, and the exit code (-1 when it did not exit normally).
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace shaderlab_test {

struct CliRun {
    std::string output;
    int exit_code = -1;
};

inline CliRun runShell(const std::string& cmd) {
    CliRun r;
    FILE* pipe = popen((cmd + " 2>&1").c_str(), "r");
    if (!pipe) return r;
    char buf[4096];
    while (std::fgets(buf, sizeof buf, pipe)) r.output += buf;
    const int status = pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

}  // namespace shaderlab_test
