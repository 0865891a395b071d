// Phase timings appended to $SHADERLAB_TIMINGS; see timings.h.
#include "shaderlab/base/timings.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>

namespace shaderlab {

namespace {

const char* timingsPath() {
    static const char* path = [] {
        const char* p = std::getenv("SHADERLAB_TIMINGS");
        return p && *p ? p : nullptr;
    }();
    return path;
}

}  // namespace

bool timingsEnabled() { return timingsPath() != nullptr; }

void recordTiming(const char* phase, const std::string& lab, const std::string& detail, double ms) {
    const char* path = timingsPath();
    if (!path) return;
    char line[512];
    const int n = std::snprintf(line, sizeof line, "%ld\t%s\t%s\t%s\t%.4f\n", static_cast<long>(getpid()),
                                phase, lab.c_str(), detail.c_str(), ms);
    if (n <= 0) return;
    // Opened per line: a forked child writes through its own descriptor, and a line is a few
    // dozen per lab, so the open costs nothing measurable.
    const int fd = open(path, O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) return;
    const std::size_t len =
        static_cast<std::size_t>(n) < sizeof line ? static_cast<std::size_t>(n) : sizeof line - 1;
    [[maybe_unused]] const ssize_t written = write(fd, line, len);
    close(fd);
}

}  // namespace shaderlab
