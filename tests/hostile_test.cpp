// The hostile corpus (tests/hostile/README.md): every case is a submission holding a correct lab
// (91-steady) beside a hostile one (92-target), graded through the `shaderlab` program with short
// limits. Each must end with its clear status within its limits, and the correct lab must keep
// its verdict. Then the output folder (planted links, a second run, an unwritable folder), the
// grader killed half-way (no child left behind), and the pieces underneath (loop guard, NUL
// bytes, huge driver lines).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <thread>

#include "shaderlab/base/sanitizer.h"
#include "shaderlab/render/shader_program.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

const fs::path kHostile = fs::path(SHADERLAB_SOURCE_DIR) / "tests" / "hostile";

fs::path scratch(const std::string& name) {
    const fs::path p = fs::temp_directory_path() / ("shaderlab_hostile_" + name);
    std::error_code ec;
    fs::remove_all(p, ec);
    fs::create_directories(p);
    return p;
}

// The labs folder the cases are graded against: the two test labs and the bundled scenes.
const fs::path& labsRoot() {
    static const fs::path root = [] {
        const fs::path p = scratch("labs_" + std::to_string(getpid()));
        fs::copy(fs::path(SHADERLAB_SOURCE_DIR) / "labs" / "scenes", p / "scenes",
                 fs::copy_options::recursive);
        fs::copy(kHostile / "labs", p, fs::copy_options::recursive);
        return p;
    }();
    return root;
}

struct CliRun {
    int exit_code = -1;
    std::string output;
    double seconds = 0.0;
};

CliRun runCli(const std::string& args) {
    CliRun r;
    const auto t0 = std::chrono::steady_clock::now();
    FILE* pipe = popen((std::string(SHADERLAB_CLI) + " " + args + " 2>&1").c_str(), "r");
    if (!pipe) return r;
    char buf[4096];
    while (std::fgets(buf, sizeof buf, pipe)) r.output += buf;
    const int status = pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void writeBytes(const fs::path& p, const std::string& bytes) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out << bytes;
}

// A submission: the reference of both labs, then the case applied to 92-target.
fs::path makeSubmission(const std::string& name, const std::function<void(const fs::path&)>& mutate) {
    const fs::path sub = scratch("sub_" + name);
    fs::copy(kHostile / "reference", sub, fs::copy_options::recursive);
    const fs::path overlay = kHostile / "cases" / name;
    if (fs::is_directory(overlay))
        fs::copy(overlay, sub / "92-target",
                 fs::copy_options::recursive | fs::copy_options::overwrite_existing);
    if (mutate) mutate(sub / "92-target");
    return sub;
}

std::string gradeArgs(const fs::path& sub, const fs::path& out, const std::string& limits) {
    return "grade " + sub.string() + " --labs " + labsRoot().string() + " --reference " +
           (kHostile / "reference").string() + " --out " + out.string() + " " + limits;
}

// Under AddressSanitizer (scripts/asan-suite.sh, SHADERLAB_ASAN) the limits are scaled; what the
// cases check is not. A render child there is resident at about 290 MB before it draws (shadow
// memory, and the pages it shares with its ASan parent after fork()), and ASan's allocator never
// grows a block in place and keeps freed ones in a 256 MB quarantine: diagnostics-flood, whose
// 12,000 messages the driver appends to one log with realloc, compiles in 11 s at a peak of 1.2 GB.
#if SHADERLAB_ASAN
constexpr int kSlower = 6, kMemoryMiB = 2048;
#else
constexpr int kSlower = 1, kMemoryMiB = 256;
#endif
constexpr int kTimeout = 4 * kSlower, kCompileTimeout = 3 * kSlower;
const std::string kShortLimits = "--timeout " + std::to_string(kTimeout) + " --compile-timeout " +
                                 std::to_string(kCompileTimeout) + " --memory " + std::to_string(kMemoryMiB);

std::string randomBytes(unsigned seed, std::size_t n, bool with_nul) {
    std::mt19937 random(seed);
    std::string s(n, '\0');
    for (char& c : s) c = static_cast<char>(with_nul ? random() % 256 : 1 + random() % 255);
    return s;
}

struct HostileCase {
    std::string name;
    std::string status;    // of 92-target
    std::string expected;  // in its message or one of its diagnostics
    std::string limit;     // report.json's "limit", or empty; "a|b": either
    std::function<void(const fs::path&)> mutate = {};
};

std::ostream& operator<<(std::ostream& os, const HostileCase& c) { return os << c.name; }

std::string everything(const json& lab) {
    std::string s = lab.value("message", "");
    for (const json& d : lab["diagnostics"])
        s += "\n" + d.value("message", "") + " " + d.value("explanation", "");
    return s;
}

class Hostile : public ::testing::TestWithParam<HostileCase> {};

TEST_P(Hostile, EndsWithAClearStatusAndLeavesTheOtherLabAlone) {
    const HostileCase& c = GetParam();
    const fs::path sub = makeSubmission(c.name, c.mutate);
    const fs::path out = scratch("out_" + c.name);
    const CliRun run = runCli(gradeArgs(sub, out, kShortLimits));
    ASSERT_EQ(run.exit_code, c.status == "passed" ? 0 : 1) << run.output;
    // Within its limits: the two labs' compile and draw limits and the references' renders.
    EXPECT_LT(run.seconds, 25.0 * kSlower) << run.output;
    const json report = json::parse(slurp(out / "report.json"), nullptr, false);
    ASSERT_FALSE(report.is_discarded()) << run.output;
    ASSERT_EQ(report["labs"].size(), 2u);
    const json& steady = report["labs"][0];
    EXPECT_EQ(steady["id"], "91-steady");
    EXPECT_EQ(steady["status"], "passed") << steady.dump(1);
    EXPECT_EQ(steady["score"], 1.0);
    const json& target = report["labs"][1];
    // A case that may meet either of two limits first (how fast memory grows depends on the
    // machine's load) has the status of the one it met.
    const std::string limit = target.value("limit", "");
    EXPECT_NE(("|" + c.limit + "|").find("|" + limit + "|"), std::string::npos) << limit;
    EXPECT_EQ(target["status"], limit == "memory" ? "crashed" : c.status) << target.dump(1).substr(0, 4000);
    if (c.status != "passed") {
        EXPECT_EQ(target["score"], 0.0);
    }
    EXPECT_NE(everything(target).find(c.expected), std::string::npos) << everything(target).substr(0, 4000);
    // Nothing from the student's file reaches a terminal or a report as a control character, and
    // no diagnostic flood makes the report large.
    for (const std::string& text : {run.output, slurp(out / "report.json"), slurp(out / "report.html")})
        EXPECT_EQ(text.find('\x1b'), std::string::npos);
    EXPECT_LT(fs::file_size(out / "report.json"), 200u * 1024);
    EXPECT_LE(target["diagnostics"].size(), 51u);
    for (const json& d : target["diagnostics"]) EXPECT_LT(d.value("message", "").size(), 4200u);
}

const HostileCase kCases[] = {
    // Loops that never end: stopped by the loop guard in both stages, even where the loop's
    // result is unused (the driver would delete it) or converges (its cap would give a right
    // picture).
    {"endless-loop-fragment", "timeout", "endless loop: in pass 'scene' of scene 'torus'", "loop"},
    {"endless-loop-fragment-unused", "timeout", "for one pixel", "loop"},
    {"endless-loop-vertex", "timeout", "for one vertex", "loop"},
    {"nan-everywhere", "failed", "", ""},
    {"every-fragment-discarded", "failed", "", ""},
    // Our own former crashes.
    {"version-overflow", "compile_error", "is not supported", ""},
    {"line-overflow", "compile_error", "undeclared_name", ""},
    {"long-compiler-message", "compile_error", "AAAA [...]", ""},
    {"macro-bomb", "timeout", "while compiling scene.vert and scene.frag", "memory|compile_timeout"},
    {"huge-array", "timeout",
     "compile timeout: not ready to draw within " + std::to_string(kCompileTimeout) +
         (kCompileTimeout < 10 ? ".0 s" : " s"),
     "compile_timeout"},
    {"diagnostics-flood", "compile_error", "left out", ""},
    {"too-large", "compile_error", "more than the limit of 262144", "",
     [](const fs::path& lab) {
         writeBytes(lab / "scene.frag",
                    slurp(lab / "scene.frag") + "//" + std::string(50u << 20, 'x') + "\n");
     }},
    {"nul-byte", "compile_error", "holds a NUL byte (byte ", "",
     [](const fs::path& lab) {
         writeBytes(lab / "scene.frag",
                    "#version 330 core\nout vec4 o_color;\nvoid main() { o_color = vec4(1.0); }\n" +
                        std::string("\0// the rest of the file", 24));
     }},
    {"ansi-escape", "compile_error", "\\x1B[2J\\x1B[31mPWNED", "",
     [](const fs::path& lab) {
         writeBytes(lab / "scene.frag", "#version 330 core\n#error \x1b[2J\x1b[31mPWNED\x07\n");
     }},
    {"binary-garbage", "compile_error", "NUL byte", "",
     [](const fs::path& lab) { writeBytes(lab / "scene.frag", randomBytes(10, 4096, true)); }},
    {"binary-garbage-without-nul", "compile_error", "", "",
     [](const fs::path& lab) { writeBytes(lab / "scene.frag", randomBytes(11, 4096, false)); }},
    {"empty-file", "compile_error", "", "", [](const fs::path& lab) { writeBytes(lab / "scene.frag", ""); }},
    {"missing-file", "missing", "scene.frag: file not found", "",
     [](const fs::path& lab) { fs::remove(lab / "scene.frag"); }},
    {"missing-lab", "missing", "the submission has no folder for this lab", "",
     [](const fs::path& lab) { fs::remove_all(lab); }},
    {"extra-files", "passed", "", ""},
    {"symlink-outside", "missing", "resolves outside", "",
     [](const fs::path& lab) {
         fs::remove(lab / "scene.frag");
         fs::create_symlink("/etc/passwd", lab / "scene.frag");
     }},
    {"symlink-loop", "missing", "broken link", "",
     [](const fs::path& lab) {
         fs::remove(lab / "scene.frag");
         fs::create_symlink("loop.frag", lab / "scene.frag");
         fs::create_symlink("scene.frag", lab / "loop.frag");
     }},
    {"directory-as-file", "compile_error", "not a regular file", "",
     [](const fs::path& lab) {
         fs::remove(lab / "scene.frag");
         fs::create_directory(lab / "scene.frag");
     }},
};

INSTANTIATE_TEST_SUITE_P(Corpus, Hostile, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<HostileCase>& param) {
                             std::string n = param.param.name;
                             for (char& ch : n)
                                 if (ch == '-') ch = '_';
                             return n;
                         });

// ---- the output folder ----------------------------------------------------------------------

TEST(HostileOutput, RefusesALinkPlantedAtAReportBeforeRendering) {
    const fs::path sub = makeSubmission("out_link", {});
    const fs::path out = scratch("out_link"), elsewhere = scratch("out_link_elsewhere");
    writeBytes(elsewhere / "precious.txt", "precious");
    fs::create_symlink(elsewhere / "precious.txt", out / "report.json");
    const CliRun run = runCli(gradeArgs(sub, out, kShortLimits));
    EXPECT_EQ(run.exit_code, 2) << run.output;
    EXPECT_NE(run.output.find("report.json: is a symbolic link"), std::string::npos) << run.output;
    EXPECT_EQ(run.output.find("PASS"), std::string::npos) << "rendered before refusing:\n" << run.output;
    EXPECT_EQ(slurp(elsewhere / "precious.txt"), "precious");
}

TEST(HostileOutput, RefusesALinkedLabFolderForItsImages) {
    const fs::path sub = makeSubmission("out_lab_link", [](const fs::path& lab) {
        writeBytes(lab / "scene.frag",
                   "#version 330 core\nout vec4 o_color;\nvoid main() { o_color = vec4(1.0); }\n");
    });
    const fs::path out = scratch("out_lab_link"), elsewhere = scratch("out_lab_link_elsewhere");
    fs::create_directory_symlink(elsewhere, out / "92-target");
    const CliRun run = runCli(gradeArgs(sub, out, kShortLimits));
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_TRUE(fs::is_empty(elsewhere)) << "pictures were written through the link";
    const json report = json::parse(slurp(out / "report.json"), nullptr, false);
    ASSERT_FALSE(report.is_discarded());
    EXPECT_NE(report["labs"][1].value("message", "").find("is a symbolic link, refused"), std::string::npos)
        << report["labs"][1].value("message", "");
}

TEST(HostileOutput, AnUnusableOutputFolderIsFoundBeforeRendering) {
    const fs::path sub = makeSubmission("out_file", {});
    const fs::path dir = scratch("out_file");
    writeBytes(dir / "a-file", "x");
    const CliRun run = runCli(gradeArgs(sub, dir / "a-file" / "out", kShortLimits));
    EXPECT_EQ(run.exit_code, 2) << run.output;
    EXPECT_NE(run.output.find("cannot create the output folder"), std::string::npos) << run.output;
    EXPECT_EQ(run.output.find("PASS"), std::string::npos) << "it rendered first:\n" << run.output;
}

TEST(HostileOutput, ASecondRunOnTheSameFolderIsRefused) {
    const fs::path sub = makeSubmission("out_lock", {});
    const fs::path out = scratch("out_lock");
    // Another run holds the folder (as a grader in progress does).
    const int fd = ::open((out / ".shaderlab.lock").c_str(), O_RDWR | O_CREAT, 0644);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(flock(fd, LOCK_EX | LOCK_NB), 0);
    const CliRun refused = runCli(gradeArgs(sub, out, kShortLimits));
    EXPECT_EQ(refused.exit_code, 2) << refused.output;
    EXPECT_NE(refused.output.find("another shaderlab run is writing into this folder"), std::string::npos)
        << refused.output;
    EXPECT_FALSE(fs::exists(out / "report.json"));
    close(fd);
    const CliRun later = runCli(gradeArgs(sub, out, kShortLimits));  // free again
    EXPECT_EQ(later.exit_code, 0) << later.output;
    for (const auto& e : fs::recursive_directory_iterator(out))
        EXPECT_NE(e.path().extension(), ".tmp") << e.path();
}

// ---- the grader killed half-way -------------------------------------------------------------

std::vector<pid_t> childrenOf(pid_t parent) {
    std::vector<pid_t> out;
    for (const auto& e : fs::directory_iterator("/proc")) {
        const std::string name = e.path().filename();
        if (name.find_first_not_of("0123456789") != std::string::npos) continue;
        std::istringstream stat(slurp(e.path() / "stat"));
        std::string pid, comm, state;
        pid_t ppid = 0;
        // "pid (comm) state ppid": comm has no spaces for shaderlab
        stat >> pid >> comm >> state >> ppid;
        if (ppid == parent) out.push_back(static_cast<pid_t>(std::stoi(pid)));
    }
    return out;
}

bool alive(pid_t pid) {
    const std::string stat = slurp("/proc/" + std::to_string(pid) + "/stat");
    if (stat.empty()) return false;
    const std::size_t close = stat.rfind(')');
    return close != std::string::npos && close + 2 < stat.size() && stat[close + 2] != 'Z';
}

// What the process `pid` has open, as /proc shows it.
std::vector<std::string> openFiles(pid_t pid) {
    std::vector<std::string> out;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator("/proc/" + std::to_string(pid) + "/fd", ec)) {
        const fs::path target = fs::read_symlink(e.path(), ec);
        if (!ec) out.push_back(target.string());
    }
    return out;
}

// Starts a grade of an endless compile (huge-array, generous limits) and kills the grader with
// `sig` once its render child runs; the child must go with it. Its images go to an anonymous
// memory file, never to /tmp, so nothing can be left there.
void killGraderHalfWay(int sig) {
    const fs::path sub = makeSubmission("huge-array", {});
    const fs::path out = scratch("out_kill_" + std::to_string(sig));
    const pid_t grader = fork();
    ASSERT_GE(grader, 0);
    if (grader == 0) {
        const std::string labs = labsRoot().string(), ref = (kHostile / "reference").string();
        const int null = ::open("/dev/null", O_WRONLY);
        dup2(null, 1);
        dup2(null, 2);
        execl(SHADERLAB_CLI, SHADERLAB_CLI, "grade", sub.c_str(), "--labs", labs.c_str(), "--reference",
              ref.c_str(), "--out", out.c_str(), "--lab", "92-target", "--compile-timeout", "60", nullptr);
        _exit(127);
    }
    std::vector<pid_t> children;
    for (int i = 0; i < 400 && children.empty(); ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(25));
        children = childrenOf(grader);
    }
    ASSERT_EQ(children.size(), 1u) << "no render child appeared";
    std::this_thread::sleep_for(std::chrono::milliseconds(300));  // compiling by now
    bool memfd = false;
    for (const std::string& f : openFiles(children[0])) {
        memfd = memfd || f.rfind("/memfd:shaderlab-render", 0) == 0;
        EXPECT_EQ(f.find("shaderlab-render-"), std::string::npos) << f;
    }
    EXPECT_TRUE(memfd);
    kill(grader, sig);
    int status = 0;
    waitpid(grader, &status, 0);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << status;
    bool gone = false;
    for (int i = 0; i < 200 && !gone; ++i) {
        gone = !alive(children[0]);
        if (!gone) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    EXPECT_TRUE(gone) << "render child " << children[0] << " outlived the grader";
    if (!gone) kill(children[0], SIGKILL);
}

TEST(HostileSignals, SigkillOfTheGraderLeavesNoChild) { killGraderHalfWay(SIGKILL); }
TEST(HostileSignals, SigtermOfTheGraderLeavesNoChild) { killGraderHalfWay(SIGTERM); }
TEST(HostileSignals, SigintOfTheGraderLeavesNoChild) { killGraderHalfWay(SIGINT); }

// ---- underneath -----------------------------------------------------------------------------

TEST(HostilePieces, GuardLoopsPutsAGuardInEveryLoopConditionAndKeepsLines) {
    using shaderlab::guardLoops;
    EXPECT_EQ(guardLoops("while (i < 3) i++;"), "while (shaderlab_loop_tick() && (i < 3)) i++;");
    EXPECT_EQ(guardLoops("for (int i = 0; i < n; ++i) {}"),
              "for (int i = 0;shaderlab_loop_tick() && ( i < n); ++i) {}");
    EXPECT_EQ(guardLoops("for (;;) {}"), "for (; shaderlab_loop_tick() ;) {}");
    EXPECT_EQ(guardLoops("do { x(); } while(f(a, b));"),
              "do { x(); } while(shaderlab_loop_tick() && (f(a, b)));");
    EXPECT_EQ(guardLoops("for (int i = 0; i < a[min(1, 2)]; i++)"),
              "for (int i = 0;shaderlab_loop_tick() && ( i < a[min(1, 2)]); i++)");
    // Comments, names that merely contain the words, and multi-line conditions.
    EXPECT_EQ(guardLoops("// while (1)\n/* for (;;) */ float forward, whiles;"),
              "// while (1)\n/* for (;;) */ float forward, whiles;");
    const std::string multi = "while (a &&\n       b)\n{}\n";
    EXPECT_EQ(guardLoops(multi), "while (shaderlab_loop_tick() && (a &&\n       b))\n{}\n");
    // Not a loop it understands (no closing bracket): left for the compiler to reject.
    EXPECT_EQ(guardLoops("while (a"), "while (a");
}

TEST(HostilePieces, PrepareSourceRejectsANulByteWithItsPlace) {
    const std::string text = std::string("#version 330 core\nvoid main() {\n  x\0y\n}\n", 39);
    const shaderlab::PreparedSource p = shaderlab::prepareSource(text, "", "a.frag");
    EXPECT_TRUE(p.rejected);
    ASSERT_EQ(p.errors.size(), 1u);
    EXPECT_EQ(p.errors[0].file, "a.frag");
    EXPECT_EQ(p.errors[0].line, 3);
    EXPECT_NE(p.errors[0].message.find("byte 35 of the file, line 3"), std::string::npos)
        << p.errors[0].message;
    EXPECT_FALSE(shaderlab::prepareSource("#version 330 core\nvoid main() {}\n", "", "a.frag").rejected);
}

TEST(HostilePieces, HugeNumbersAndLinesInDriverLogsDoNotCrash) {
    // std::stoi would throw on these, std::regex would overflow the stack on the long line.
    const std::vector<shaderlab::Diagnostic> big =
        shaderlab::parseInfoLog("0:99999999999(2147483648): error: x\n", "a.frag");
    ASSERT_EQ(big.size(), 1u);
    EXPECT_EQ(big[0].line, 2147483647);
    const std::string long_line = "0:3(1): error: #error " + std::string(45000, 'A');
    const std::vector<shaderlab::Diagnostic> cut = shaderlab::parseInfoLog(long_line, "a.frag");
    ASSERT_EQ(cut.size(), 1u);
    EXPECT_EQ(cut[0].line, 3);
    EXPECT_LT(cut[0].message.size(), 2100u);
    const shaderlab::PreparedSource v =
        shaderlab::prepareSource("#version 99999999999\n#line 2147483646\n", "", "a");
    EXPECT_NE(v.text.find("#version 99999999999"), std::string::npos);
}

}  // namespace
