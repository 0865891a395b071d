// `shaderlab gradescope-bundle` and the autograder it writes, unpacked into a folder laid out as
// Gradescope's /autograder: what the zip holds (a program, not sources), what its setup.sh
// installs (Mesa's run-time packages, with apt-get replaced by a recorder), and what its
// run_autograder writes (results.json with the points, no folder of the grader in any text).
// The portable program itself is proved on other systems by scripts/portable-check.sh (chroots,
// by hand); here the bundle carries the program this build made.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "batch_test_support.h"
#include "shaderlab/batch/batch.h"

namespace fs = std::filesystem;
using json = nlohmann::json;
using namespace shaderlab;
using namespace shaderlab::batch_testing;

namespace {

std::string quoted(const fs::path& p) { return "'" + p.string() + "'"; }

CommandRun shaderlab(const std::string& args) { return runCommand(quoted(SHADERLAB_CLI) + " " + args); }

// The bundle of kLab, carrying this build's program, unpacked into <dir>/autograder/source.
fs::path unpackedBundle(const fs::path& dir, const std::string& more = "") {
    const fs::path zip = dir / "autograder.zip";
    const CommandRun r = shaderlab("gradescope-bundle --out " + quoted(zip) + " --lab " + kLab +
                                   " --binary " + quoted(SHADERLAB_CLI) + " " + more);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    // This build is not the portable one, and the bundle says what that means.
    EXPECT_NE(r.output.find("is not a portable build (scripts/portable-build.sh)"), std::string::npos)
        << r.output;
    const fs::path root = dir / "autograder";
    fs::create_directories(root);
    // This build's program is large (debug information): limits beyond a student's upload's.
    batch::ArchiveLimits limits;
    limits.max_total_bytes = limits.max_entry_bytes = std::uint64_t(4) << 30;
    const batch::ExtractResult x = batch::extractZip(zip.string(), (root / "source").string(), limits);
    EXPECT_EQ(x.status, "ok") << x.message;
    return root;
}

TEST(GradescopeBundle, HoldsTheProgramTheLabAndScriptsButNoSources) {
    const fs::path root = unpackedBundle(scratch("gradescope_layout"));
    const fs::path source = root / "source";
    for (const char* file : {"setup.sh", "run_autograder", "bin/shaderlab"}) {
        const fs::path p = source / file;
        ASSERT_TRUE(fs::is_regular_file(p)) << file;
        EXPECT_NE(fs::status(p).permissions() & fs::perms::owner_exec, fs::perms::none) << file;
    }
    for (const char* script : {"setup.sh", "run_autograder"})
        EXPECT_EQ(runCommand("bash -n " + quoted(source / script)).exit_code, 0) << script;
    EXPECT_EQ(readFile(source / "bin" / "shaderlab"), readFile(SHADERLAB_CLI));
    // Only the chosen lab, with its reference solution and the shared scenes.
    EXPECT_TRUE(fs::is_regular_file(source / "labs" / kLab / "lab.json"));
    EXPECT_TRUE(fs::is_directory(source / "labs" / "scenes"));
    EXPECT_FALSE(fs::exists(source / "labs" / "02-toon"));
    EXPECT_TRUE(fs::is_regular_file(source / "reference_solutions" / kLab / "phong.frag"));
    // Nothing to build on Gradescope's image.
    for (const char* absent : {"CMakeLists.txt", "framework", "grader", "cmake", "scripts"})
        EXPECT_FALSE(fs::exists(source / absent)) << absent;
}

TEST(GradescopeBundle, WithoutAPortableProgramSaysHowToBuildOne) {
    const fs::path dir = scratch("gradescope_refusals");
    // This build is not portable: without --binary there is nothing to pack.
    CommandRun r = shaderlab("gradescope-bundle --out " + quoted(dir / "a.zip") + " --lab " + kLab);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("scripts/portable-build.sh"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "a.zip"));
    // Something that is not a program, and a file that is not there.
    writeFile(dir / "notes.txt", "not a program\n");
    r = shaderlab("gradescope-bundle --out " + quoted(dir / "b.zip") + " --lab " + kLab + " --binary " +
                  quoted(dir / "notes.txt"));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(
        r.output.find("notes.txt: --binary must be a shaderlab program (this is not a Linux executable)"),
        std::string::npos)
        << r.output;
    r = shaderlab("gradescope-bundle --out " + quoted(dir / "c.zip") + " --lab " + kLab + " --binary " +
                  quoted(dir / "missing"));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("missing: --binary must be a shaderlab program (file not found)"),
              std::string::npos)
        << r.output;
}

// The packages setup.sh asks apt-get for, with apt-get, apt-cache and sudo replaced by recorders;
// `osmesa_packaged` is what apt-cache answers about libosmesa6 (Mesa 25.1 and later have none).
std::set<std::string> setupInstalls(const fs::path& dir, const fs::path& source, bool osmesa_packaged) {
    const fs::path fake = dir / (osmesa_packaged ? "fake_with_osmesa" : "fake_without_osmesa");
    const fs::path log = fake / "apt.log";
    writeFile(fake / "apt-get", "#!/bin/sh\necho \"$@\" >> " + quoted(log) + "\n");
    writeFile(fake / "apt-cache", std::string("#!/bin/sh\nexit ") + (osmesa_packaged ? "0" : "100") + "\n");
    writeFile(fake / "sudo", "#!/bin/sh\nexec \"$@\"\n");
    for (const char* tool : {"apt-get", "apt-cache", "sudo"})
        fs::permissions(fake / tool, fs::perms::owner_all);
    const CommandRun r =
        runCommand("PATH=" + quoted(fake) + ":\"$PATH\" bash " + quoted(source / "setup.sh"));
    EXPECT_EQ(r.exit_code, 0) << r.output;
    // The last line of setup.sh: the bundled program starts and gets a context.
    EXPECT_NE(r.output.find("renderer"), std::string::npos) << r.output;
    std::set<std::string> packages;
    std::istringstream lines(readFile(log));
    for (std::string line; std::getline(lines, line);) {
        if (line.find("install") == std::string::npos) continue;
        std::istringstream words(line);
        for (std::string w; words >> w;)
            if (w != "install" && w.rfind("-", 0) != 0) packages.insert(w);
    }
    return packages;
}

TEST(GradescopeBundle, SetupInstallsMesasRunTimePackagesOnly) {
    const fs::path dir = scratch("gradescope_setup");
    const fs::path source = unpackedBundle(dir) / "source";
    // Mesa's EGL and drivers, and OSMesa where it is packaged. The names are the same on Debian
    // 11 to 13 and on Ubuntu 22.04 and 24.04 (Gradescope's images): all four are in Ubuntu 22.04's
    // main archive. No compiler, no -dev package: the program in bin/ is already built.
    const std::set<std::string> with = setupInstalls(dir, source, true);
    EXPECT_EQ(with, (std::set<std::string>{"libegl1", "libegl-mesa0", "libgl1-mesa-dri", "libosmesa6"}));
    const std::set<std::string> without = setupInstalls(dir, source, false);
    EXPECT_EQ(without, (std::set<std::string>{"libegl1", "libegl-mesa0", "libgl1-mesa-dri"}));
    // This machine's apt knows every name (Debian's names are Ubuntu's for these packages).
    for (const std::string& p : with)
        EXPECT_EQ(runCommand("dpkg-query -W " + p + " || apt-cache show " + p + " >/dev/null").exit_code, 0)
            << p;
}

// Its run_autograder grades an upload (flat files, in a folder, as students upload a one-lab
// assignment) into results/results.json per Gradescope's specification, with the chosen
// visibility and tests, using the program in bin/.
TEST(GradescopeBundle, RunAutograderWritesResultsInASimulatedLayout) {
    const fs::path dir = scratch("gradescope_run");
    const fs::path root = unpackedBundle(dir, "--visibility after_published --tests scenes --timeout 20");
    auto grade = [&](const std::string& from, const std::vector<std::string>& files) {
        fs::remove_all(root / "submission");
        fs::remove_all(root / "results");
        fs::create_directories(root / "submission");
        for (const std::string& f : files)
            writeFile(root / "submission" / "my upload" / f, readFile(fs::path(from) / f));
        const CommandRun run = runCommand("SHADERLAB_AUTOGRADER_ROOT=" + quoted(root) + " bash " +
                                          quoted(root / "source" / "run_autograder"));
        EXPECT_EQ(run.exit_code, 0) << run.output;
        const std::string text = readFile(root / "results" / "results.json");
        // No folder of the grader's in anything a student reads: not the staging folder under
        // /tmp, not the autograder's root.
        EXPECT_EQ(text.find("/tmp/"), std::string::npos) << text.substr(0, 4000);
        EXPECT_EQ(text.find(root.string()), std::string::npos) << text.substr(0, 4000);
        return json::parse(text, nullptr, false);
    };
    const json good = grade((kSource / "reference_solutions" / kLab).string(), {"phong.vert", "phong.frag"});
    ASSERT_TRUE(good.is_object());
    EXPECT_DOUBLE_EQ(good["score"].get<double>(), 10.0);
    EXPECT_EQ(good["visibility"], "after_published");
    EXPECT_TRUE(good["execution_time"].is_number());
    ASSERT_GT(good["tests"].size(), 8u);  // one per scene, more than the lab's goals
    double sum = 0;
    for (const json& t : good["tests"]) {
        EXPECT_EQ(t["visibility"], "after_published");
        EXPECT_EQ(t["status"], "passed") << t.dump();
        EXPECT_EQ(t["name"].get<std::string>().rfind(kLab + " / ", 0), 0u);
        sum += t["max_score"].get<double>();
    }
    EXPECT_NEAR(sum, 10.0, 1e-9);
    // The starter handed in untouched is not attempted: nothing drawn, nothing to show.
    const json starter = grade((kSource / "labs" / kLab).string(), {"phong.vert", "phong.frag"});
    EXPECT_DOUBLE_EQ(starter["score"].get<double>(), 0.0);
    ASSERT_EQ(starter["tests"].size(), 1u) << starter.dump();
    EXPECT_NE(
        starter["tests"][0]["output"].get<std::string>().find("not_attempted: phong.vert and phong.frag are "
                                                              "the lab's starter code, unchanged"),
        std::string::npos)
        << starter.dump(1);
    const json wrong =
        grade((kSource / "tests/corpus" / kLab / "gouraud").string(), {"phong.vert", "phong.frag"});
    EXPECT_LT(wrong["score"].get<double>(), 10.0);
    bool failed = false;
    for (const json& t : wrong["tests"]) {
        if (t["status"] != "failed") continue;
        failed = true;
        // A failing scene shows the pictures: the student's, the reference's, the difference.
        EXPECT_EQ(t["output_format"], "html");
        EXPECT_NE(t["output"].get<std::string>().find("<img src=\"data:image/png;base64,iVBORw0KGgo"),
                  std::string::npos)
            << t["output"];
    }
    EXPECT_TRUE(failed);
    // One file of two: the message names the lab's file as the student knows it.
    const json half = grade((kSource / "reference_solutions" / kLab).string(), {"phong.vert"});
    EXPECT_DOUBLE_EQ(half["score"].get<double>(), 0.0);
    EXPECT_NE(half.dump().find("phong.frag: file not found (its folder holds: phong.vert)"),
              std::string::npos)
        << half.dump().substr(0, 4000);
}

}  // namespace
