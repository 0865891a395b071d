// The student viewer: the folder watch behind hot reload (any way an editor saves), and the
// `view` window and `watch` command end to end. The window tests run `shaderlab view` on an
// Xvfb display of their own and are skipped, saying why, where Xvfb is not installed.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "grader/metrics/image.h"
#include "grader/metrics/scoring.h"
#include "shaderlab/grading/grading.h"
#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/live/file_watch.h"
#include "shaderlab/scene/camera.h"

namespace fs = std::filesystem;
using shaderlab::viewer::FolderWatch;

namespace {

fs::path scratch(const std::string& name) {
    const fs::path p = fs::temp_directory_path() / ("shaderlab_viewer_" + name);
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}

void writeFile(const fs::path& p, const std::string& text) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out << text;
}

std::string readFile(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Polls until the watch reports a change or `limit` passes.
bool changeSeen(FolderWatch& watch, std::chrono::milliseconds limit = std::chrono::milliseconds(3000)) {
    const auto end = std::chrono::steady_clock::now() + limit;
    while (std::chrono::steady_clock::now() < end) {
        if (watch.poll()) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
}

TEST(FolderWatch, SeesWritesInPlaceRenamesAndTruncateThenWrite) {
    const fs::path dir = scratch("watch");
    writeFile(dir / "phong.frag", "one");
    FolderWatch watch(dir.string(), std::chrono::milliseconds(50));
    EXPECT_FALSE(changeSeen(watch, std::chrono::milliseconds(200))) << "nothing changed yet";

    writeFile(dir / "phong.frag", "two");
    ASSERT_TRUE(changeSeen(watch));
    ASSERT_EQ(watch.changedFiles().size(), 1u);
    EXPECT_EQ(watch.changedFiles()[0], "phong.frag");
    EXPECT_GT(watch.changedMtimeNs(), 0);

    // Save by rename: the new contents arrive as another inode.
    writeFile(dir / ".phong.frag.swp", "three");
    writeFile(dir / "phong.frag.tmp~", "three");
    fs::rename(dir / "phong.frag.tmp~", dir / "phong.frag");
    ASSERT_TRUE(changeSeen(watch));
    EXPECT_EQ(watch.changedFiles(), std::vector<std::string>{"phong.frag"})
        << "hidden and backup files are ignored";

    // Truncate, then write a moment later: one change, reported once the file is whole.
    { std::ofstream truncate(dir / "phong.frag", std::ios::trunc); }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    writeFile(dir / "phong.frag", "four, longer");
    ASSERT_TRUE(changeSeen(watch));
    EXPECT_EQ(readFile(dir / "phong.frag"), "four, longer");
    EXPECT_FALSE(changeSeen(watch, std::chrono::milliseconds(200))) << "a change is reported once";
}

TEST(FolderWatch, TouchingWithoutChangingIsNoChange) {
    const fs::path dir = scratch("touch");
    writeFile(dir / "a.frag", "same");
    FolderWatch watch(dir.string(), std::chrono::milliseconds(30));
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    writeFile(dir / "a.frag", "same");
    fs::last_write_time(dir / "a.frag", fs::file_time_type::clock::now());
    EXPECT_FALSE(changeSeen(watch, std::chrono::milliseconds(300)));
    // ... but a save all the same, handed out once, for the student's sign that it was seen.
    EXPECT_EQ(watch.takeSavedUnchanged(), std::vector<std::string>{"a.frag"});
    EXPECT_TRUE(watch.takeSavedUnchanged().empty());
    writeFile(dir / "b.frag", "new file");
    ASSERT_TRUE(changeSeen(watch));
    EXPECT_EQ(watch.changedFiles(), std::vector<std::string>{"b.frag"});
    EXPECT_TRUE(watch.takeSavedUnchanged().empty()) << "a change is not an unchanged save";
    fs::remove(dir / "b.frag");
    ASSERT_TRUE(changeSeen(watch));
    EXPECT_EQ(watch.changedFiles(), std::vector<std::string>{"b.frag"});
}

// The viewer's orbit (RenderOptions::orbit): about the target, distance kept, zoom divides it,
// pitch stops short of the pole.
TEST(CameraOrbit, TurnsAboutTheTargetAndZooms) {
    shaderlab::Scene scene;
    scene.bounds_min = glm::vec3(-1.0f);
    scene.bounds_max = glm::vec3(1.0f);
    shaderlab::Camera base;
    base.position = glm::vec3(0.0f, 0.0f, 4.0f);
    base.target = glm::vec3(0.0f);

    shaderlab::Camera c = base;
    shaderlab::orbitCamera(scene, {}, &c);
    EXPECT_EQ(c.position, base.position) << "the identity leaves the graded view alone";

    c = base;
    shaderlab::orbitCamera(scene, {90.0f, 0.0f, 1.0f}, &c);
    EXPECT_NEAR(glm::length(c.position), 4.0f, 1e-4f);
    EXPECT_NEAR(c.position.x, 4.0f, 1e-4f) << "yaw turns about world +y";
    EXPECT_NEAR(c.position.y, 0.0f, 1e-4f);

    c = base;
    shaderlab::orbitCamera(scene, {0.0f, 30.0f, 2.0f}, &c);
    EXPECT_NEAR(glm::length(c.position), 2.0f, 1e-4f) << "zoom 2 halves the distance";
    EXPECT_NEAR(c.position.y, 2.0f * std::sin(glm::radians(30.0f)), 1e-4f) << "pitch raises the camera";
    EXPECT_LT(c.z_near, 1.0f);
    EXPECT_GT(c.z_far, 3.0f) << "near and far refitted to the scene";

    c = base;
    shaderlab::orbitCamera(scene, {0.0f, 170.0f, 1.0f}, &c);
    EXPECT_LT(c.position.y / glm::length(c.position), std::sin(glm::radians(85.5f)))
        << "stops short of the pole";
}

// ---------------------------------------------------------------------------------------------
// End to end, with a display of our own.

bool onPath(const std::string& program) {
    return std::system(("command -v " + program + " >/dev/null 2>&1").c_str()) == 0;
}

// One Xvfb server for the suite, on the first free display (-displayfd picks it).
class XvfbDisplay {
  public:
    static XvfbDisplay& get() {
        static XvfbDisplay display;
        return display;
    }
    const std::string& name() const { return name_; }
    const std::string& why_not() const { return why_not_; }
    ~XvfbDisplay() {
        if (pid_ > 0) {
            kill(pid_, SIGTERM);
            waitpid(pid_, nullptr, 0);
        }
    }

  private:
    XvfbDisplay() {
        if (!onPath("Xvfb")) {
            why_not_ = "Xvfb is not installed (scripts/setup.sh installs it)";
            return;
        }
        int fds[2];
        if (pipe(fds) != 0) {
            why_not_ = "no pipe";
            return;
        }
        pid_ = fork();
        if (pid_ == 0) {
            close(fds[0]);
            const int devnull = open("/dev/null", O_WRONLY);
            dup2(devnull, STDOUT_FILENO);
            dup2(devnull, STDERR_FILENO);
            const std::string fd = std::to_string(fds[1]);
            execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1280x800x24", "-nolisten",
                   "tcp", static_cast<char*>(nullptr));
            _exit(127);
        }
        close(fds[1]);
        std::string number;
        char c;
        while (read(fds[0], &c, 1) == 1 && c != '\n') number.push_back(c);
        close(fds[0]);
        if (number.empty()) {
            why_not_ = "Xvfb did not start";
            return;
        }
        name_ = ":" + number;
    }
    pid_t pid_ = -1;
    std::string name_, why_not_;
};

struct CommandRun {
    int exit_code = -1;
    std::string output;
};

std::string viewCommand(const std::string& args) {
    return "DISPLAY=" + XvfbDisplay::get().name() + " " + std::string(SHADERLAB_CLI) + " " + args + " 2>&1";
}

CommandRun runCommand(const std::string& cmd) {
    CommandRun r;
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return r;
    char buf[4096];
    while (std::fgets(buf, sizeof buf, pipe)) r.output += buf;
    const int status = pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

// A running command whose output is read line by line, so the test can act in the middle.
class Background {
  public:
    explicit Background(const std::string& cmd) : pipe_(popen(cmd.c_str(), "r")) {}
    ~Background() {
        if (pipe_) finish();
    }
    // Reads until a line containing `text` (true) or the end of the output (false).
    bool waitFor(const std::string& text) {
        char buf[4096];
        while (pipe_ && std::fgets(buf, sizeof buf, pipe_)) {
            output_ += buf;
            if (std::string(buf).find(text) != std::string::npos) return true;
        }
        return false;
    }
    CommandRun finish() {
        waitFor("\x01never");
        CommandRun r;
        r.output = output_;
        if (pipe_) {
            const int status = pclose(pipe_);
            pipe_ = nullptr;
            r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        }
        return r;
    }
    const std::string& output() const { return output_; }

  private:
    FILE* pipe_;
    std::string output_;
};

const fs::path kSource = SHADERLAB_SOURCE_DIR;

// A submission holding a copy of 01-phong's reference shaders, to edit.
fs::path phongSubmission(const std::string& name) {
    const fs::path root = scratch(name);
    fs::copy(kSource / "reference_solutions" / "01-phong", root / "01-phong", fs::copy_options::recursive);
    return root;
}

class ViewerWindow : public ::testing::Test {
  protected:
    void SetUp() override {
        if (!SHADERLAB_HAVE_VIEWER)
            GTEST_SKIP() << "a grader-only build (SHADERLAB_GRADER_ONLY) has no window";
        if (XvfbDisplay::get().name().empty()) GTEST_SKIP() << XvfbDisplay::get().why_not();
    }
    std::string labs() const { return " --labs " + (kSource / "labs").string(); }
};

// The picture the window shows for the graded view is the picture grading renders: the
// screenshot (read back from the window) passes the grader's own judgement against a headless
// render of the same scene, with the lab's thresholds.
TEST_F(ViewerWindow, GradedViewMatchesTheHeadlessRender) {
    const fs::path out = scratch("graded");
    const std::string ref = (kSource / "reference_solutions").string();
    const CommandRun view =
        runCommand(viewCommand("view 01-phong --submission " + ref + labs() +
                               " --scene torus --frames 3 --screenshot " + (out / "view.png").string()));
    ASSERT_EQ(view.exit_code, 0) << view.output;
    const CommandRun render = runCommand(std::string(SHADERLAB_CLI) + " render " + ref + " --lab 01-phong" +
                                         labs() + " --out " + (out / "headless").string() + " 2>&1");
    ASSERT_EQ(render.exit_code, 0) << render.output;

    grader::Image shown, headless;
    std::string err;
    ASSERT_TRUE(grader::readPng((out / "view.png").string(), &shown, &err)) << err << "\n" << view.output;
    ASSERT_TRUE(grader::readPng((out / "headless" / "01-phong" / "torus.png").string(), &headless, &err))
        << err;
    ASSERT_EQ(shown.width, headless.width);
    ASSERT_EQ(shown.height, headless.height);
    const shaderlab::LabSpecResult lab = shaderlab::parseLabSpec((kSource / "labs" / "01-phong").string());
    ASSERT_TRUE(lab.ok);
    const grader::Thresholds t = shaderlab::imageThresholds(lab.spec, "torus", lab.spec.passes.back());
    // Compared over the whole frame (the screenshot has no coverage).
    const grader::ImageVerdict v = grader::judgeImage(headless, {}, shown, {}, t);
    EXPECT_TRUE(v.passed) << "PSNR " << v.frame.psnr_db << " mismatch " << v.frame.mismatch_fraction;
    EXPECT_GT(v.frame.psnr_db, 45.0) << "an 8-bit picture shown 1:1 should be nearly exact";
    // And the window says the scene passes.
    EXPECT_NE(view.output.find("scene torus passes"), std::string::npos) << view.output;
}

// Stepping through passes: an intermediate image of a multi-pass lab, as the window shows it, is
// the image the headless renderer reads back for that pass.
TEST_F(ViewerWindow, IntermediatePassMatchesTheHeadlessRender) {
    const fs::path out = scratch("pass");
    const std::string ref = (kSource / "reference_solutions").string();
    const CommandRun view = runCommand(viewCommand(
        "view 06-bloom --submission " + ref + labs() +
        " --scene cube_white --image bright.color --frames 2 --screenshot " + (out / "view.png").string()));
    ASSERT_EQ(view.exit_code, 0) << view.output;
    const CommandRun render =
        runCommand(std::string(SHADERLAB_CLI) + " render " + ref + " --lab 06-bloom" + labs() +
                   " --all-passes --out " + (out / "headless").string() + " 2>&1");
    ASSERT_EQ(render.exit_code, 0) << render.output;
    grader::Image shown, bright, final_image;
    std::string err;
    ASSERT_TRUE(grader::readPng((out / "view.png").string(), &shown, &err)) << err << "\n" << view.output;
    ASSERT_TRUE(
        grader::readPng((out / "headless" / "06-bloom" / "cube_white.bright.png").string(), &bright, &err));
    ASSERT_TRUE(
        grader::readPng((out / "headless" / "06-bloom" / "cube_white.png").string(), &final_image, &err));
    ASSERT_EQ(shown.width, bright.width);
    const grader::ImageVerdict v = grader::judgeImage(bright, {}, shown, {}, grader::Thresholds());
    EXPECT_TRUE(v.passed) << "PSNR " << v.frame.psnr_db;
    const grader::ImageVerdict other = grader::judgeImage(final_image, {}, shown, {}, grader::Thresholds());
    EXPECT_FALSE(other.passed) << "the bright pass must not look like the final image";
}

// A turned view is rendered (it differs from the graded view) and is never taken for a grade; with
// only the stored goldens there is no reference for it, and the window says so.
TEST_F(ViewerWindow, TurnedViewRendersAndIsNotGraded) {
    const fs::path out = scratch("turned");
    const std::string ref = (kSource / "reference_solutions").string();
    const std::string common =
        "view 01-phong --submission " + ref + labs() + " --no-reference --scene torus --frames 2";
    const CommandRun graded =
        runCommand(viewCommand(common + " --screenshot " + (out / "graded.png").string()));
    ASSERT_EQ(graded.exit_code, 0) << graded.output;
    EXPECT_NE(graded.output.find("scene torus passes"), std::string::npos) << "graded against the goldens\n"
                                                                           << graded.output;
    const CommandRun turned =
        runCommand(viewCommand(common + " --orbit 60 20 1.2 --screenshot " + (out / "turned.png").string() +
                               " --screenshot-window " + (out / "window.png").string()));
    ASSERT_EQ(turned.exit_code, 0) << turned.output;
    EXPECT_EQ(turned.output.find("scene torus passes"), std::string::npos) << turned.output;
    grader::Image a, b;
    std::string err;
    ASSERT_TRUE(grader::readPng((out / "graded.png").string(), &a, &err)) << err;
    ASSERT_TRUE(grader::readPng((out / "turned.png").string(), &b, &err)) << err;
    ASSERT_EQ(a.width, b.width);
    const grader::ImageVerdict v = grader::judgeImage(a, {}, b, {}, grader::Thresholds());
    EXPECT_FALSE(v.passed) << "the turned view looks like the graded one";
}

// The debug view of the vertex data (`--debug VIEW`, V in the window) takes the lab's picture's
// place: what the window shows is, pixel for pixel, what `render --debug` writes; the sphere's
// normal at the centre faces the camera; the window names the view, and says which mesh has no
// tangents, whose picture is grey. The lab is still rendered and judged behind it.
TEST_F(ViewerWindow, DebugViewShowsWhatRenderDebugWrites) {
    const fs::path out = scratch("debug");
    const std::string ref = (kSource / "reference_solutions").string();
    const std::string common = "view 01-phong --submission " + ref + labs() + " --scene sphere --frames 2";
    const CommandRun normals =
        runCommand(viewCommand(common + " --debug normals --screenshot " + (out / "normals.png").string()));
    ASSERT_EQ(normals.exit_code, 0) << normals.output;
    EXPECT_NE(normals.output.find("view: debug view normals: world-space normal"), std::string::npos)
        << normals.output;
    EXPECT_NE(normals.output.find("view: debug view normals of scene sphere drawn in"), std::string::npos)
        << normals.output;
    EXPECT_NE(normals.output.find("scene sphere passes"), std::string::npos)
        << "the lab is judged behind it\n"
        << normals.output;
    const CommandRun render = runCommand(std::string(SHADERLAB_CLI) + " render --lab 01-phong" + labs() +
                                         " --debug normals --out " + (out / "headless").string() + " 2>&1");
    ASSERT_EQ(render.exit_code, 0) << render.output;

    grader::Image shown, headless, lab_picture;
    std::string err;
    ASSERT_TRUE(grader::readPng((out / "normals.png").string(), &shown, &err)) << err << "\n"
                                                                               << normals.output;
    ASSERT_TRUE(grader::readPng((out / "headless" / "01-phong" / "sphere.debug-normals.png").string(),
                                &headless, &err))
        << err;
    ASSERT_EQ(shown.width, headless.width);
    ASSERT_EQ(shown.height, headless.height);
    const grader::ImageVerdict v = grader::judgeImage(headless, {}, shown, {}, grader::Thresholds());
    EXPECT_TRUE(v.passed) << "PSNR " << v.frame.psnr_db;
    EXPECT_GT(v.frame.psnr_db, 45.0) << "an 8-bit picture shown 1:1 should be nearly exact";
    ASSERT_TRUE(grader::readPng((kSource / "labs" / "01-phong" / "golden" / "sphere.png").string(),
                                &lab_picture, &err))
        << err;
    EXPECT_FALSE(grader::judgeImage(lab_picture, {}, shown, {}, grader::Thresholds()).passed)
        << "the window shows the lab's picture, not the debug view";
    // The bundled sphere's camera is at (0, 0.8, 3.6), looking at its centre.
    const glm::vec3 facing = glm::normalize(glm::vec3(0.0f, 0.8f, 3.6f)) * 0.5f + 0.5f;
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(shown.at(shown.width / 2, shown.height / 2, c), facing[c], 0.02f) << "channel " << c;

    const CommandRun tangents =
        runCommand(viewCommand(common + " --debug tangents --screenshot " + (out / "tangents.png").string()));
    ASSERT_EQ(tangents.exit_code, 0) << tangents.output;
    EXPECT_NE(
        tangents.output.find("view: debug view: no tangents in scenes/sphere.gltf, mesh sphere: drawn grey"),
        std::string::npos)
        << tangents.output;
    grader::Image grey;
    ASSERT_TRUE(grader::readPng((out / "tangents.png").string(), &grey, &err)) << err;
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(grey.at(grey.width / 2, grey.height / 2, c), 0.35f, 1.0f / 255.0f);
}

// A shader that does not compile: the window stays up, says where, and the terminal says so too.
TEST_F(ViewerWindow, BrokenShaderShowsTheErrorAndDoesNotCrash) {
    const fs::path sub = phongSubmission("broken");
    std::string frag = readFile(sub / "01-phong" / "phong.frag");
    const std::size_t at = frag.find("vec3 n = normalize(v_world_normal);");
    ASSERT_NE(at, std::string::npos);
    frag.replace(at, std::string("vec3 n = normalize(v_world_normal);").size(),
                 "vec3 n = normalize(v_world_normal)");
    writeFile(sub / "01-phong" / "phong.frag", frag);
    const fs::path out = scratch("broken_out");
    const CommandRun view =
        runCommand(viewCommand("view 01-phong --submission " + sub.string() + labs() +
                               " --frames 3 --screenshot-window " + (out / "window.png").string()));
    EXPECT_EQ(view.exit_code, 0) << view.output;
    EXPECT_NE(view.output.find("does not compile"), std::string::npos) << view.output;
    EXPECT_NE(view.output.find("phong.frag:"), std::string::npos) << view.output;
    EXPECT_NE(view.output.find("^"), std::string::npos) << "the caret under the source line\n" << view.output;
    // The lines around the error, under their numbers, and the command that opens it.
    int line = 1;
    for (std::size_t p = 0; p < at; ++p) line += frag[p] == '\n';
    for (int n = line - 2; n <= line + 2; ++n)
        EXPECT_NE(view.output.find(" " + std::to_string(n) + " | "), std::string::npos)
            << "line " << n << " around the error at " << line << "\n"
            << view.output;
    EXPECT_NE(view.output.find("open it: "), std::string::npos) << view.output;
    EXPECT_NE(view.output.find(" +" + std::to_string(line) + " "), std::string::npos) << view.output;
    grader::Image window;
    std::string err;
    ASSERT_TRUE(grader::readPng((out / "window.png").string(), &window, &err)) << err;
    // The error panel's dark red background is on screen.
    std::size_t reddish = 0;
    for (int y = 0; y < window.height; ++y)
        for (int x = 0; x < window.width; ++x)
            if (window.at(x, y, 0) > 0.2f && window.at(x, y, 0) < 0.3f && window.at(x, y, 1) < 0.08f)
                ++reddish;
    EXPECT_GT(reddish, 10000u) << "no error panel in the window";
}

// Save by rename while the window runs: a later frame shows the new shader.
TEST_F(ViewerWindow, EditingTheShaderChangesTheNextPicture) {
    const fs::path sub = phongSubmission("edit");
    const fs::path out = scratch("edit_out");
    Background view(viewCommand("view 01-phong --submission " + sub.string() + labs() +
                                " --scene sphere --exit-after-reloads 1 --screenshot " +
                                (out / "after.png").string()));
    ASSERT_TRUE(view.waitFor("rendered in")) << view.output();
    // The new shader paints every covered pixel pure red.
    std::string frag = readFile(sub / "01-phong" / "phong.frag");
    const std::size_t at = frag.find("o_color = vec4(color, 1.0);");
    ASSERT_NE(at, std::string::npos);
    frag.replace(at, std::string("o_color = vec4(color, 1.0);").size(),
                 "o_color = vec4(1.0, 0.0, 0.0, 1.0);");
    writeFile(sub / "01-phong" / "phong.frag.new", frag);
    fs::rename(sub / "01-phong" / "phong.frag.new", sub / "01-phong" / "phong.frag");
    const CommandRun r = view.finish();
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("after the save"), std::string::npos) << r.output;
    grader::Image after;
    std::string err;
    ASSERT_TRUE(grader::readPng((out / "after.png").string(), &after, &err)) << err << "\n" << r.output;
    std::size_t red = 0;
    for (int y = 0; y < after.height; ++y)
        for (int x = 0; x < after.width; ++x)
            if (after.at(x, y, 0) > 0.99f && after.at(x, y, 1) < 0.01f && after.at(x, y, 2) < 0.01f) ++red;
    EXPECT_GT(red, std::size_t(after.width) * after.height / 20) << "the sphere is not red after the edit";
    EXPECT_NE(r.output.find("scene sphere FAILS"), std::string::npos) << r.output;
}

// Truncate, then write: the half-saved (empty) file is never rendered.
TEST_F(ViewerWindow, TruncateThenWriteRendersTheWholeFile) {
    const fs::path sub = phongSubmission("truncate");
    Background view(
        viewCommand("view 01-phong --submission " + sub.string() + labs() + " --exit-after-reloads 1"));
    ASSERT_TRUE(view.waitFor("rendered in")) << view.output();
    const std::string frag = readFile(sub / "01-phong" / "phong.frag") + "\n// edited\n";
    { std::ofstream truncate(sub / "01-phong" / "phong.frag", std::ios::trunc); }
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
    writeFile(sub / "01-phong" / "phong.frag", frag);
    const CommandRun r = view.finish();
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("after the save"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("does not compile"), std::string::npos) << r.output;
}

// A shader that never ends: the window keeps drawing frames and names the shader that timed out.
TEST_F(ViewerWindow, HangingShaderTimesOutAndTheWindowStaysResponsive) {
    const fs::path sub = phongSubmission("hang");
    std::string frag = readFile(sub / "01-phong" / "phong.frag");
    const std::size_t at = frag.find("o_color = vec4(color, 1.0);");
    ASSERT_NE(at, std::string::npos);
    // A loop whose end depends on data the compiler cannot see through.
    frag.replace(at, std::string("o_color = vec4(color, 1.0);").size(),
                 "float k = 0.0; while (k >= 0.0) { k += u_ambient + 1.0; } o_color = vec4(color * k, 1.0);");
    writeFile(sub / "01-phong" / "phong.frag", frag);
    const CommandRun view = runCommand(
        viewCommand("view 01-phong --submission " + sub.string() + labs() + " --timeout 1 --frames 5"));
    EXPECT_EQ(view.exit_code, 0) << view.output;
    // The clock stops it, or on a fast machine the loop guard first (EndlessLoopIsNamedAtItsLine).
    EXPECT_TRUE(view.output.find("Timed out: phong.frag") != std::string::npos ||
                view.output.find("Endless loop: phong.frag:") != std::string::npos)
        << view.output;
    // Frames went on while the shader hung (about 30 a second while idle).
    int frames = 0;
    const std::size_t f = view.output.find("view: ");
    for (std::size_t p = f; p != std::string::npos; p = view.output.find("view: ", p + 1))
        std::sscanf(view.output.c_str() + p, "view: %d frames", &frames);
    EXPECT_GE(frames, 15) << view.output;
}

// A loop the guard stops is called an endless loop, at its line, with the lines around it.
TEST_F(ViewerWindow, EndlessLoopIsNamedAtItsLine) {
    const fs::path sub = phongSubmission("loop");
    std::string frag = readFile(sub / "01-phong" / "phong.frag");
    const std::size_t at = frag.find("o_color = vec4(color, 1.0);");
    ASSERT_NE(at, std::string::npos);
    // Only a few pixels loop, so the guard stops it long before the clock.
    frag.replace(at, std::string("o_color = vec4(color, 1.0);").size(),
                 "float k = 0.0; if (gl_FragCoord.x < 130.0 && gl_FragCoord.x > 126.0) while (k >= 0.0) "
                 "{ k += u_ambient + 1.0; } o_color = vec4(color * max(k, 1.0), 1.0);");
    writeFile(sub / "01-phong" / "phong.frag", frag);
    int line = 1;
    for (std::size_t p = 0; p < at; ++p) line += frag[p] == '\n';
    const CommandRun view = runCommand(
        viewCommand("view 01-phong --submission " + sub.string() + labs() + " --timeout 30 --frames 3"));
    EXPECT_EQ(view.exit_code, 0) << view.output;
    EXPECT_NE(view.output.find("Endless loop: phong.frag:" + std::to_string(line) + " (pass 'shade')"),
              std::string::npos)
        << view.output;
    EXPECT_EQ(view.output.find("Timed out"), std::string::npos) << view.output;
    EXPECT_NE(view.output.find(" " + std::to_string(line - 1) + " | "), std::string::npos) << view.output;
}

// The picture's warnings and notes, with the lines around them, in the terminal (and the window).
TEST_F(ViewerWindow, WarningsComeWithTheLinesAroundThem) {
    const fs::path sub = scratch("starter");
    fs::copy(kSource / "labs" / "01-phong", sub / "01-phong", fs::copy_options::recursive);
    const CommandRun view = runCommand(
        viewCommand("view 01-phong --submission " + sub.string() + labs() + " --no-reference --frames 2"));
    EXPECT_EQ(view.exit_code, 0) << view.output;
    const std::size_t at = view.output.find("is declared but never used");
    ASSERT_NE(at, std::string::npos) << view.output;
    EXPECT_NE(view.output.find("warning", at - 200), std::string::npos) << view.output;
    EXPECT_NE(view.output.find("open it: ", at), std::string::npos) << view.output;
}

// What `check` says of a lab: its points as printed ("6.50 / 10.00") and, for each failing
// scene that looks like a known mistake, the scene and the hint sentence.
struct CheckSays {
    std::string points;
    std::vector<std::pair<std::string, std::string>> hints;
};

CheckSays readCheck(const std::string& out, const std::string& lab) {
    CheckSays says;
    std::smatch m;
    if (std::regex_search(out, m, std::regex(lab + R"(\s+([0-9.]+ / [0-9.]+))"))) says.points = m[1];
    std::istringstream lines(out);
    std::string line, scene;
    const std::regex failing(R"(^\s+FAIL (\S+)\s+PSNR)");
    while (std::getline(lines, line)) {
        if (std::regex_search(line, m, failing)) scene = m[1];
        const std::size_t at = line.find("This looks like a known mistake:");
        if (at != std::string::npos) says.hints.emplace_back(scene, line.substr(at));
    }
    return says;
}

// One voice: the window grades the lab as `check` does, at start and after each save, and prints
// the same points and, for each failing scene, the very same known-mistake sentence.
TEST_F(ViewerWindow, GradesTheLabAndSaysWhatCheckSays) {
    const fs::path sub = scratch("hint");
    fs::copy(kSource / "reference_solutions" / "02-toon", sub / "02-toon", fs::copy_options::recursive);
    const fs::path mistake = kSource / "tests" / "corpus" / "02-toon" / "ramp-lambert-coordinate";
    for (const fs::directory_entry& e : fs::directory_iterator(mistake))
        fs::copy_file(e.path(), sub / "02-toon" / e.path().filename(), fs::copy_options::overwrite_existing);
    auto check = [&] {
        return runCommand(std::string(SHADERLAB_CLI) + " check 02-toon --submission " + sub.string() +
                          labs() + " --no-reference --out " + scratch("hint_check").string() + " 2>&1");
    };
    const CommandRun before = check();
    ASSERT_EQ(before.exit_code, 1) << before.output;
    const CheckSays said = readCheck(before.output, "02-toon");
    ASSERT_FALSE(said.points.empty()) << before.output;
    ASSERT_FALSE(said.hints.empty()) << "check gives no hint for this mistake\n" << before.output;

    // A minute at most: a window that never grades never settles, and would wait for ever.
    const std::string view = "timeout 60 env " + viewCommand("view 02-toon --submission " + sub.string() +
                                                             labs() + " --no-reference");
    const fs::path panel = scratch("hint_panel") / "panel.txt";
    const CommandRun first = runCommand(view + " --frames 2 --panel-text " + panel.string());
    ASSERT_EQ(first.exit_code, 0) << first.output;
    // The window lists every goal of the lab, met or not, and the hint, as the terminal says them.
    const std::string listed = readFile(panel);
    const shaderlab::LabSpecResult toon = shaderlab::parseLabSpec((kSource / "labs" / "02-toon").string());
    ASSERT_TRUE(toon.ok);
    for (const shaderlab::GoalSpec& g : toon.spec.goals) {
        const std::size_t goal = listed.find(". " + g.title + " (");
        ASSERT_NE(goal, std::string::npos) << g.id << " is not in the window's list:\n" << listed;
        const std::size_t line_start =
            listed.rfind('\n', goal) == std::string::npos ? 0 : listed.rfind('\n', goal) + 1;
        const bool missed = listed.compare(line_start, 6, "miss: ") == 0;
        const std::size_t not_met = first.output.find("goals not met: ");
        ASSERT_NE(not_met, std::string::npos) << first.output;
        const std::string missing = first.output.substr(not_met, first.output.find('\n', not_met) - not_met);
        EXPECT_EQ(missed, (missing + ",").find(" " + g.id + ",") != std::string::npos) << g.id << "\n"
                                                                                       << listed << "\n"
                                                                                       << missing;
    }
    for (const auto& [scene, sentence] : said.hints) {
        EXPECT_NE(listed.find("scene: FAIL scene " + scene), std::string::npos) << listed;
        EXPECT_NE(listed.find("hint: " + sentence), std::string::npos) << listed;
    }
    const std::size_t grade_line = first.output.find("view: grade " + said.points + "; goals not met: ");
    ASSERT_NE(grade_line, std::string::npos) << "check says " << said.points << "\n" << first.output;
    EXPECT_NE(first.output.find("ramp", grade_line), std::string::npos) << "the goal the mistake misses\n"
                                                                        << first.output;
    for (const auto& [scene, sentence] : said.hints)
        EXPECT_NE(first.output.find("view: scene " + scene + ": " + sentence + "\n"), std::string::npos)
            << "check says, for scene " << scene << ":\n"
            << sentence << "\nthe window says:\n"
            << first.output;

    // Put the reference's file back while the window runs: it grades again, and again agrees
    // with check.
    Background again(view + " --exit-after-reloads 1");
    ASSERT_TRUE(again.waitFor("rendered in")) << again.output();
    for (const fs::directory_entry& e : fs::directory_iterator(mistake)) {
        const fs::path fixed = sub / "02-toon" / (e.path().filename().string() + ".new");
        fs::copy_file(kSource / "reference_solutions" / "02-toon" / e.path().filename(), fixed);
        fs::rename(fixed, sub / "02-toon" / e.path().filename());
    }
    const CommandRun r = again.finish();
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const CommandRun after = check();
    const CheckSays fixed = readCheck(after.output, "02-toon");
    ASSERT_FALSE(fixed.points.empty()) << after.output;
    EXPECT_NE(fixed.points, said.points) << after.output;
    const std::size_t change = r.output.find("changed; rendering again");
    ASSERT_NE(change, std::string::npos) << r.output;
    EXPECT_NE(r.output.find("view: grade " + fixed.points + ";", change), std::string::npos)
        << "check after the fix:\n"
        << after.output << "\nthe window:\n"
        << r.output;
    EXPECT_EQ(r.output.find("This looks like a known mistake", change), std::string::npos) << r.output;
}

// Without a display the viewer says so and points at `watch` (exit 2), and leaves no process behind.
TEST(ViewerWithoutDisplay, SaysWhyAndPointsAtWatch) {
    const CommandRun r = runCommand("env -u DISPLAY -u WAYLAND_DISPLAY " + std::string(SHADERLAB_CLI) +
                                    " view 01-phong --submission " + (kSource / "labs").string() +
                                    " --labs " + (kSource / "labs").string() + " 2>&1");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("shaderlab watch 01-phong"), std::string::npos) << r.output;
}

// `watch` checks again on every save and prints the verdict per scene.
TEST(ViewerWatch, ChecksAgainOnEverySave) {
    const fs::path sub = phongSubmission("watch_cmd");
    const fs::path out = scratch("watch_out");
    Background watch(std::string(SHADERLAB_CLI) + " watch 01-phong --submission " + sub.string() +
                     " --labs " + (kSource / "labs").string() + " --max-checks 2 --out " + out.string() +
                     " 2>&1");
    ASSERT_TRUE(watch.waitFor("waiting for you to save")) << watch.output();
    EXPECT_NE(watch.output().find("PASS"), std::string::npos) << watch.output();
    std::string frag = readFile(sub / "01-phong" / "phong.frag");
    const std::size_t at = frag.find("o_color = vec4(color, 1.0);");
    ASSERT_NE(at, std::string::npos);
    frag.replace(at, std::string("o_color = vec4(color, 1.0);").size(), "o_color = vec4(color * 0.5, 1.0);");
    writeFile(sub / "01-phong" / "phong.frag", frag);
    const CommandRun r = watch.finish();
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find("phong.frag changed; checking again"), std::string::npos) << r.output;
    const std::size_t second = r.output.find("checking again");
    EXPECT_NE(r.output.find("FAIL", second), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("sphere", second), std::string::npos) << "the verdict per scene\n" << r.output;
}

}  // namespace
