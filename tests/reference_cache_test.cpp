// What `grade` and `check` keep between runs (shaderlab/batch/reference_cache.h and
// gl_context.h's useShaderCache): a second grade of a lab reads the reference images the first
// one rendered, with the same verdicts and metrics; a changed reference solution is rendered
// again; `--no-cache` keeps nothing; and a student's compiler warnings survive Mesa's shader
// cache, which skips the compile of a shader it has seen.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

const fs::path kRoot = SHADERLAB_SOURCE_DIR;

std::string readFile(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

class ReferenceCache : public ::testing::Test {
  protected:
    void SetUp() override {
        tmp_ = fs::temp_directory_path() / ("shaderlab_refcache_" + std::to_string(::getpid()));
        fs::remove_all(tmp_);
        fs::create_directories(tmp_);
    }
    void TearDown() override { fs::remove_all(tmp_); }

    // Runs `shaderlab <args>` with its timings in tmp_/<name>.timings; the output and exit code.
    shaderlab_test::CliRun run(const std::string& name, const std::string& args) {
        const fs::path timings = tmp_ / (name + ".timings");
        return shaderlab_test::runShell("SHADERLAB_TIMINGS=" + timings.string() + " " + SHADERLAB_CLI + " " +
                                        args);
    }

    // The render children run `name` started, by what they drew: "student", "reference", ...
    std::vector<std::string> renderChildren(const std::string& name) {
        std::vector<std::string> kinds;
        std::istringstream in(readFile(tmp_ / (name + ".timings")));
        std::string line;
        while (std::getline(in, line)) {
            std::vector<std::string> f;
            std::istringstream fields(line);
            std::string field;
            while (std::getline(fields, field, '\t')) f.push_back(field);
            if (f.size() >= 4 && f[1] == "render_child") kinds.push_back(f[3]);
        }
        return kinds;
    }

    std::size_t count(const std::vector<std::string>& kinds, const std::string& kind) {
        return static_cast<std::size_t>(std::count(kinds.begin(), kinds.end(), kind));
    }

    std::size_t entries(const std::string& lab) {
        std::size_t n = 0;
        std::error_code ec;
        for (const fs::directory_entry& e : fs::directory_iterator(tmp_ / "cache" / "references", ec))
            if (e.path().filename().string().rfind(lab + "-", 0) == 0) ++n;
        return n;
    }

    json report(const std::string& out) { return json::parse(readFile(tmp_ / out / "report.json")); }

    fs::path tmp_;
};

TEST_F(ReferenceCache, SecondGradeReadsTheReferenceTheFirstRendered) {
    const std::string common = (kRoot / "reference_solutions").string() + " --lab 02-toon --cache " +
                               (tmp_ / "cache").string() + " --out ";
    ASSERT_EQ(run("first", "grade " + common + (tmp_ / "first").string()).exit_code, 0);
    ASSERT_EQ(run("second", "grade " + common + (tmp_ / "second").string()).exit_code, 0);
    EXPECT_EQ(count(renderChildren("first"), "reference"), 1u);
    EXPECT_EQ(count(renderChildren("second"), "reference"), 0u) << "the second grade rendered the reference";
    EXPECT_EQ(count(renderChildren("second"), "student"), 1u);
    EXPECT_EQ(entries("02-toon"), 1u);

    const json a = report("first"), b = report("second");
    EXPECT_EQ(b["labs"][0]["reference_source"], "reference_cache");
    EXPECT_EQ(a["score"], b["score"]);
    ASSERT_EQ(a["labs"][0]["scenes"].size(), b["labs"][0]["scenes"].size());
    for (std::size_t i = 0; i < a["labs"][0]["scenes"].size(); ++i)
        EXPECT_EQ(a["labs"][0]["scenes"][i]["passes"], b["labs"][0]["scenes"][i]["passes"])
            << a["labs"][0]["scenes"][i]["name"];

    // A student's mistake is judged against the kept images as against fresh ones.
    fs::create_directories(tmp_ / "student");
    fs::copy(kRoot / "tests" / "corpus" / "02-toon" / "edges-view-not-normalised",
             tmp_ / "student" / "02-toon", fs::copy_options::recursive);
    for (const fs::directory_entry& e : fs::directory_iterator(kRoot / "reference_solutions" / "02-toon"))
        fs::copy(e.path(), tmp_ / "student" / "02-toon" / e.path().filename(),
                 fs::copy_options::skip_existing);
    const std::string student = (tmp_ / "student").string() + " --lab 02-toon --out ";
    run("kept", "grade " + student + (tmp_ / "kept").string() + " --cache " + (tmp_ / "cache").string());
    run("fresh", "grade " + student + (tmp_ / "fresh").string() + " --no-cache");
    EXPECT_EQ(count(renderChildren("kept"), "reference"), 0u);
    EXPECT_EQ(report("kept")["labs"][0]["goals"], report("fresh")["labs"][0]["goals"]);
    EXPECT_LT(report("kept")["score"].get<double>(), 10.0);
}

TEST_F(ReferenceCache, ChangedReferenceIsRenderedAgainAndNoCacheKeepsNothing) {
    fs::create_directories(tmp_ / "ref");
    fs::copy(kRoot / "reference_solutions" / "01-phong", tmp_ / "ref" / "01-phong",
             fs::copy_options::recursive);
    const std::string common = (kRoot / "reference_solutions").string() + " --lab 01-phong --reference " +
                               (tmp_ / "ref").string() + " --out " + (tmp_ / "out").string();
    const std::string cache = " --cache " + (tmp_ / "cache").string();
    ASSERT_EQ(run("first", "grade " + common + cache).exit_code, 0);
    EXPECT_EQ(count(renderChildren("first"), "reference"), 1u);
    // A comment changes no pixel but is another reference: its images are not trusted to be alike.
    std::ofstream(tmp_ / "ref" / "01-phong" / "phong.frag", std::ios::app) << "// edited\n";
    ASSERT_EQ(run("edited", "grade " + common + cache).exit_code, 0);
    EXPECT_EQ(count(renderChildren("edited"), "reference"), 1u)
        << "a changed reference was not rendered again";
    EXPECT_EQ(entries("01-phong"), 2u);

    ASSERT_EQ(run("off", "grade " + common + cache + " --no-cache").exit_code, 0);
    EXPECT_EQ(count(renderChildren("off"), "reference"), 1u);
    EXPECT_EQ(report("out")["labs"][0]["reference_source"], "reference_solutions");
    EXPECT_EQ(entries("01-phong"), 2u);
}

TEST_F(ReferenceCache, WarningsSurviveTheShaderCache) {
    const fs::path lab = tmp_ / "work" / "01-phong";
    fs::create_directories(lab);
    for (const fs::directory_entry& e : fs::directory_iterator(kRoot / "reference_solutions" / "01-phong"))
        fs::copy(e.path(), lab / e.path().filename());
    std::string frag = readFile(lab / "phong.frag");
    const std::string main_line = "void main() {\n";
    ASSERT_NE(frag.find(main_line), std::string::npos);
    frag.insert(frag.find(main_line) + main_line.size(),
                "    float never_set;\n    float copy = never_set;\n");
    std::ofstream(lab / "phong.frag") << frag;

    const std::string args = "check 01-phong --submission " + (tmp_ / "work").string() + " --cache " +
                             (tmp_ / "cache").string() + " --out ";
    for (const char* name : {"first", "second", "third"}) {
        const shaderlab_test::CliRun r = run(name, args + (tmp_ / name).string());
        EXPECT_NE(r.output.find("never_set"), std::string::npos) << name << " run lost the warning:\n"
                                                                 << r.output;
    }
    // Mesa did keep the shader (else the test shows nothing): its cache folder is there and not
    // empty, and so is the log kept beside it.
    EXPECT_FALSE(fs::is_empty(tmp_ / "cache" / "shader-cache" / "shaderlab-logs"));
    std::size_t mesa_files = 0;
    for (auto it = fs::recursive_directory_iterator(tmp_ / "cache" / "shader-cache"); it != fs::end(it); ++it)
        mesa_files +=
            it->is_regular_file() && it->path().string().find("shaderlab-logs") == std::string::npos;
    EXPECT_GT(mesa_files, 0u);
}

TEST_F(ReferenceCache, ShaderCacheFolderIsMadeEvenWithoutAReference) {
    // Mesa makes only the last folder of its cache path: a --cache folder that does not exist
    // yet, on a run that keeps no reference (the goldens are used), must still get its cache.
    const fs::path cache = tmp_ / "not" / "yet" / "there";
    const shaderlab_test::CliRun r = run("goldens", "grade " + (kRoot / "reference_solutions").string() +
                                                        " --lab 01-phong --no-reference --cache " +
                                                        cache.string() + " --out " + (tmp_ / "out").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(r.output.find("disabling"), std::string::npos) << r.output;
    std::size_t mesa_files = 0;
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(cache / "shader-cache", ec); !ec && it != fs::end(it);
         it.increment(ec))
        mesa_files += it->is_regular_file();
    EXPECT_GT(mesa_files, 0u) << "no shader cache under " << cache;
}

// The kept reference's images are read while the student's render runs, for the renderer the
// cache saw last (last-renderer-<backend>.txt); a guess that names another renderer reads
// nothing early, and the images are read once the render says which renderer drew it. Either
// way the verdicts are those of the first grade.
TEST_F(ReferenceCache, ImagesAreReadDuringTheRenderOnlyForTheRendererLastSeen) {
    const std::string common = (kRoot / "reference_solutions").string() + " --lab 01-phong --cache " +
                               (tmp_ / "cache").string() + " --out ";
    ASSERT_EQ(run("first", "grade " + common + (tmp_ / "first").string()).exit_code, 0);
    // One file per backend (osmesa, or egl where Mesa no longer builds OSMesa).
    fs::path last;
    for (const fs::directory_entry& e : fs::directory_iterator(tmp_ / "cache" / "references"))
        if (e.path().filename().string().rfind("last-renderer-", 0) == 0) last = e.path();
    const std::string renderer = readFile(last);
    ASSERT_NE(renderer.find("OpenGL"), std::string::npos) << "no renderer remembered in " << last;

    // Where the timings put the goldens: before the student's render ends (read meanwhile) or after.
    const auto goldens_during_render = [&](const std::string& name) {
        const std::string t = readFile(tmp_ / (name + ".timings"));
        const std::size_t goldens = t.find("\tgoldens\t"),
                          student = t.find("\trender_child\t01-phong\tstudent");
        EXPECT_NE(goldens, std::string::npos) << t;
        EXPECT_NE(student, std::string::npos) << t;
        return goldens < student;
    };
    ASSERT_EQ(run("second", "grade " + common + (tmp_ / "second").string()).exit_code, 0);
    EXPECT_TRUE(goldens_during_render("second"));
    std::ofstream(last) << "another renderer, OpenGL 9.9";
    ASSERT_EQ(run("third", "grade " + common + (tmp_ / "third").string()).exit_code, 0);
    EXPECT_FALSE(goldens_during_render("third"));
    EXPECT_EQ(readFile(last), renderer) << "the renderer that drew is remembered again";
    const json first = report("first");
    for (const char* name : {"second", "third"}) {
        const json r = report(name);
        EXPECT_EQ(r["labs"][0]["reference_source"], "reference_cache") << name;
        EXPECT_EQ(r["labs"][0]["goals"], first["labs"][0]["goals"]) << name;
        ASSERT_EQ(r["labs"][0]["scenes"].size(), first["labs"][0]["scenes"].size()) << name;
        for (std::size_t i = 0; i < first["labs"][0]["scenes"].size(); ++i)
            EXPECT_EQ(r["labs"][0]["scenes"][i]["passes"], first["labs"][0]["scenes"][i]["passes"]) << name;
    }
}

}  // namespace
