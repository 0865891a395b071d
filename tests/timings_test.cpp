// The measuring hooks scripts/bench.sh relies on, and the work grading skips: SHADERLAB_TIMINGS
// records every phase of a grade (parent and render child into one file); a passing lab never
// reads its known-mistake pictures while a failing one does; the reference picture of a graded
// image is the golden file itself; and the program does not load OpenGL (or libLLVM behind it)
// until a command creates a context, so `compare` starts fast.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kSource = SHADERLAB_SOURCE_DIR;

struct TimingLine {
    std::string pid, phase, lab, detail;
    double ms = -1.0;
};

std::vector<TimingLine> readTimings(const fs::path& file) {
    std::vector<TimingLine> out;
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream fields(line);
        TimingLine t;
        std::string ms;
        std::getline(fields, t.pid, '\t');
        std::getline(fields, t.phase, '\t');
        std::getline(fields, t.lab, '\t');
        std::getline(fields, t.detail, '\t');
        std::getline(fields, ms, '\t');
        t.ms = ms.empty() ? -1.0 : std::stod(ms);
        out.push_back(t);
    }
    return out;
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// Grades `submission` (09-procedural-antialiasing only: one pass, quick) against the goldens with
// timings on; returns the lines.
std::vector<TimingLine> gradeWithTimings(const std::string& submission, const std::string& name) {
    const fs::path dir =
        fs::temp_directory_path() / ("shaderlab_timings_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path file = dir / "timings.tsv";
    const std::string cmd = "SHADERLAB_TIMINGS=" + file.string() + " " + SHADERLAB_CLI + " grade " +
                            (kSource / submission).string() +
                            " --lab 09-procedural-antialiasing --no-reference --out " +
                            (dir / "out").string() + " > /dev/null 2>&1";
    const int rc = std::system(cmd.c_str());
    EXPECT_NE(rc, -1) << cmd;
    std::vector<TimingLine> lines = readTimings(file);
    if (submission == "reference_solutions") {
        // The reference picture is the golden PNG, byte for byte.
        EXPECT_EQ(slurp(dir / "out" / "09-procedural-antialiasing" / "aliased_checker" / "reference.png"),
                  slurp(kSource / "labs" / "09-procedural-antialiasing" / "golden" / "aliased_checker.png"));
    }
    fs::remove_all(dir);
    return lines;
}

TEST(Timings, EveryPhaseOfAGradeIsRecordedOnce) {
    const std::vector<TimingLine> lines = gradeWithTimings("reference_solutions", "reference");
    ASSERT_FALSE(lines.empty()) << "SHADERLAB_TIMINGS wrote nothing";
    std::map<std::string, int> count;
    std::set<std::string> pids;
    for (const TimingLine& t : lines) {
        ++count[t.phase];
        pids.insert(t.pid);
        EXPECT_GE(t.ms, 0.0) << t.phase;
        // The context is made before a lab is known; the report files hold every lab.
        if (t.phase != "context" && t.phase != "report_files") {
            EXPECT_EQ(t.lab, "09-procedural-antialiasing") << t.phase;
        }
    }
    for (const char* phase :
         {"context", "compile", "scene", "readback", "render_child", "goldens", "metrics", "images", "lab"})
        EXPECT_GE(count[phase], 1) << phase << " not recorded";
    EXPECT_EQ(count["context"], 1);
    EXPECT_EQ(count["compile"], 1);
    EXPECT_EQ(count["lab"], 1);
    EXPECT_EQ(count["report_files"], 2) << "written after the lab, then once more at the end";
    EXPECT_EQ(count["scene"], count["metrics"]);  // one graded image per scene in this lab
    EXPECT_EQ(pids.size(), 2u) << "the grader and its render child";
    // A lab that passes does not read its known-mistake pictures.
    EXPECT_EQ(count["hints"], 0);
}

TEST(Timings, AFailingLabReadsItsKnownMistakePictures) {
    const std::vector<TimingLine> lines = gradeWithTimings("labs", "starter");
    int loads = 0;
    for (const TimingLine& t : lines) loads += t.phase == "hints" && t.detail == "load";
    EXPECT_EQ(loads, 1);
}

// OSMesa pulls in libLLVM; a command that never draws must not load it (see gl_context.cpp).
TEST(Startup, TheProgramLinksNoOpenGlLibrary) {
    const std::string cmd = std::string("LD_TRACE_LOADED_OBJECTS=1 ") + SHADERLAB_CLI + " 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    std::string out;
    char buf[512];
    while (std::fgets(buf, sizeof buf, pipe)) out += buf;
    pclose(pipe);
    ASSERT_NE(out.find("libc.so"), std::string::npos) << out;  // the listing worked
    for (const char* lib : {"libOSMesa", "libEGL", "libGL", "libLLVM", "libglapi"})
        EXPECT_EQ(out.find(lib), std::string::npos) << lib << " is linked:\n" << out;
}

}  // namespace
