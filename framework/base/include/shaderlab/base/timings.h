// Where the time goes, for `scripts/bench.sh`: when the environment variable SHADERLAB_TIMINGS
// names a file, every timed phase appends one line to it,
//   <pid> TAB <phase> TAB <lab> TAB <detail> TAB <milliseconds>
// with one write() on a file opened O_APPEND, so render children and the grader can share the
// file without tearing lines. Without the variable a phase costs a clock read and a branch. It
// does not aggregate or print anything: bench/timing_report.py does.
//
// Phases: context (creating the GL context), compile (all programs of a lab), scene_load (glTF
// parse and upload), scene (one scene, everything the renderer does for it), readback
// (glReadPixels and row flipping), render_child (a lab's isolated render as the grader waits
// for it), metrics (judgeImage), images (report pictures: encoding and writing PNGs), hints,
// lab (all of gradeLab).
#pragma once

#include <chrono>
#include <string>

namespace shaderlab {

bool timingsEnabled();
void recordTiming(const char* phase, const std::string& lab, const std::string& detail, double ms);

// Records the time from construction to destruction (or to stop()).
class ScopedTiming {
  public:
    ScopedTiming(const char* phase, std::string lab, std::string detail = {})
        : phase_(phase),
          lab_(std::move(lab)),
          detail_(std::move(detail)),
          start_(std::chrono::steady_clock::now()) {}
    ScopedTiming(const ScopedTiming&) = delete;
    ScopedTiming& operator=(const ScopedTiming&) = delete;
    ~ScopedTiming() { stop(); }
    double stop() {
        if (stopped_) return 0.0;
        stopped_ = true;
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
        if (timingsEnabled()) recordTiming(phase_, lab_, detail_, ms);
        return ms;
    }

  private:
    const char* phase_;
    std::string lab_, detail_;
    std::chrono::steady_clock::time_point start_;
    bool stopped_ = false;
};

}  // namespace shaderlab
