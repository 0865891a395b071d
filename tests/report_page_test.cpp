// The report a student reads, end to end: a submission with a known mistake (pow() of a negative
// base: NaN pixels, every goal lost) is graded through the `shaderlab` program, and its
// report.html and Gradescope results.json are checked the way a browser would meet them: every
// picture decodes (embedded data: URIs and linked files alike), the page is valid HTML (HTML
// Tidy, where installed) and renders in headless Chromium (where installed) to a screenshot of the
// expected size that is not blank, at a laptop's and a phone's width. Without Chromium or Tidy
// those checks are skipped with a message; scripts/setup.sh installs both.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "grader/metrics/image.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

const fs::path kRoot = SHADERLAB_SOURCE_DIR;

struct Ran {
    int exit_code = -1;
    std::string output;
};

Ran run(const std::string& cmd) {
    Ran r;
    FILE* pipe = popen((cmd + " 2>&1").c_str(), "r");
    if (!pipe) return r;
    char buf[4096];
    while (std::fgets(buf, sizeof buf, pipe)) r.output += buf;
    const int status = pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

bool installed(const std::string& program) {
    return run("command -v " + program + " > /dev/null").exit_code == 0;
}

std::string base64Decode(const std::string& text) {
    std::string out;
    unsigned buffer = 0;
    int bits = 0;
    for (char c : text) {
        int v = -1;
        if (c >= 'A' && c <= 'Z') v = c - 'A';
        if (c >= 'a' && c <= 'z') v = c - 'a' + 26;
        if (c >= '0' && c <= '9') v = c - '0' + 52;
        if (c == '+') v = 62;
        if (c == '/') v = 63;
        if (v < 0) continue;  // padding
        buffer = (buffer << 6) | static_cast<unsigned>(v);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out += static_cast<char>((buffer >> bits) & 0xFF);
        }
    }
    return out;
}

// The src of every <img> in `html`.
std::vector<std::string> imageSources(const std::string& html) {
    std::vector<std::string> out;
    for (std::size_t at = html.find("<img "); at != std::string::npos; at = html.find("<img ", at + 1)) {
        const std::size_t src = html.find("src=\"", at);
        const std::size_t end = html.find('"', src + 5);
        if (src == std::string::npos || end == std::string::npos) break;
        out.push_back(html.substr(src + 5, end - src - 5));
    }
    return out;
}

// Every picture decodes: a data: URI's PNG bytes, or the file a relative path names.
void expectPicturesDecode(const std::vector<std::string>& sources, const fs::path& root,
                          const fs::path& scratch) {
    int n = 0;
    for (const std::string& src : sources) {
        fs::path file;
        const std::string prefix = "data:image/png;base64,";
        if (src.rfind(prefix, 0) == 0) {
            file = scratch / ("embedded_" + std::to_string(n++) + ".png");
            std::ofstream(file, std::ios::binary) << base64Decode(src.substr(prefix.size()));
        } else {
            ASSERT_EQ(src.find(".."), std::string::npos) << src;
            file = root / src;
        }
        grader::Image image;
        std::string error;
        EXPECT_TRUE(grader::readPng(file.string(), &image, &error)) << src.substr(0, 80) << ": " << error;
        EXPECT_GT(image.width, 0);
    }
}

// A screenshot of `page` by headless Chromium at width x height; empty when it fails.
grader::Image screenshot(const fs::path& page, int width, int height, const fs::path& scratch) {
    const fs::path shot = scratch / ("shot_" + std::to_string(width) + ".png");
    const fs::path profile = scratch / ("profile_" + std::to_string(width));
    fs::remove(shot);
    const std::string cmd =
        "timeout 120 chromium --headless --no-sandbox --disable-gpu --disable-quic "
        "--no-first-run --disable-background-networking --disable-component-update "
        "--disable-sync --hide-scrollbars --user-data-dir=" +
        profile.string() + " --screenshot=" + shot.string() + " --window-size=" + std::to_string(width) +
        "," + std::to_string(height) + " file://" + page.string();
    const Ran r = run(cmd);
    grader::Image image;
    std::string error;
    if (!grader::readPng(shot.string(), &image, &error))
        ADD_FAILURE() << cmd << "\n" << r.output << "\n" << error;
    return image;
}

// How many different colours (8-bit RGB) a picture has: a blank or broken page has one or two.
std::size_t colours(const grader::Image& image) {
    std::set<unsigned> seen;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            unsigned key = 0;
            for (int c = 0; c < 3; ++c)
                key = key * 256 +
                      static_cast<unsigned>(image.at(x, y, image.channels >= 3 ? c : 0) * 255.0f + 0.5f);
            seen.insert(key);
        }
    return seen.size();
}

class ReportPage : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        // One folder per process: ctest runs each test in its own, in parallel.
        scratch_ = fs::temp_directory_path() / ("shaderlab_report_page_" + std::to_string(::getpid()));
        fs::remove_all(scratch_);
        // The reference's student files, then the mistake's over them (as `shaderlab corpus` does).
        const fs::path lab = scratch_ / "submission" / "01-phong";
        fs::create_directories(lab);
        for (const auto& e : fs::directory_iterator(kRoot / "reference_solutions/01-phong"))
            fs::copy(e.path(), lab / e.path().filename(), fs::copy_options::recursive);
        for (const auto& e : fs::directory_iterator(kRoot / "tests/corpus/01-phong/pow-negative-base"))
            fs::copy(e.path(), lab / e.path().filename(), fs::copy_options::overwrite_existing);
        out_ = scratch_ / "out";
        grade_ = run(std::string(SHADERLAB_CLI) + " grade " + (scratch_ / "submission").string() +
                     " --lab 01-phong --no-reference --format gradescope --out " + out_.string());
    }
    static void TearDownTestSuite() { fs::remove_all(scratch_); }
    static fs::path scratch_, out_;
    static Ran grade_;
};
fs::path ReportPage::scratch_, ReportPage::out_;
Ran ReportPage::grade_;

TEST_F(ReportPage, ReportRecordsThresholdsPicturesAndTheKnownMistake) {
    ASSERT_EQ(grade_.exit_code, 1) << grade_.output;
    std::ifstream in(out_ / "report.json");
    const json report = json::parse(in, nullptr, false);
    ASSERT_FALSE(report.is_discarded());
    const json& lab = report["labs"][0];
    ASSERT_EQ(lab["status"], "failed");
    int hinted = 0;
    for (const json& scene : lab["scenes"]) {
        for (const json& pass : scene["passes"]) {
            EXPECT_TRUE(pass["thresholds"].is_object()) << pass.dump();
            EXPECT_GT(pass["width"].get<int>(), 0);
            for (const char* picture : {"student", "reference"})
                EXPECT_TRUE(fs::is_regular_file(out_ / pass["images"][picture].get<std::string>()))
                    << picture;
            // A passing image is shown as the student's picture alone: no difference pictures.
            for (const char* picture : {"diff", "signed_difference"})
                EXPECT_EQ(pass["images"].contains(picture), !pass["passed"].get<bool>()) << picture;
            if (!pass["passed"].get<bool>()) {
                for (const char* picture : {"diff", "signed_difference"})
                    EXPECT_TRUE(fs::is_regular_file(out_ / pass["images"][picture].get<std::string>()))
                        << picture;
                EXPECT_TRUE(fs::is_regular_file(out_ / pass["images"]["zoom"].get<std::string>()));
                EXPECT_TRUE(pass["zoom_region"].is_object());
            }
        }
        if (scene["hint"].is_object()) {
            EXPECT_EQ(scene["hint"]["mistake"], "pow-negative-base");
            ++hinted;
        }
    }
    // NaN in the sphere: the student's picture shows it in magenta.
    grader::Image student;
    std::string error;
    ASSERT_TRUE(grader::readPng((out_ / "01-phong/sphere/student.png").string(), &student, &error)) << error;
    bool magenta = false;
    for (int y = 0; y < student.height && !magenta; ++y)
        for (int x = 0; x < student.width && !magenta; ++x)
            magenta =
                student.at(x, y, 0) == 1.0f && student.at(x, y, 1) == 0.0f && student.at(x, y, 2) == 1.0f;
    EXPECT_TRUE(magenta);
    EXPECT_GT(hinted, 0) << "the mistake's own pictures are in labs/01-phong/hints";
}

TEST_F(ReportPage, EveryPictureDecodesAndThePageIsSelfContained) {
    ASSERT_EQ(grade_.exit_code, 1) << grade_.output;
    const std::string html = slurp(out_ / "report.html");
    const std::vector<std::string> sources = imageSources(html);
    ASSERT_GT(sources.size(), 40u);
    for (const std::string& src : sources) EXPECT_EQ(src.rfind("data:image/png;base64,", 0), 0u) << src;
    expectPicturesDecode(sources, out_, scratch_);
    EXPECT_NE(html.find("Look here first"), std::string::npos);
    EXPECT_NE(html.find("This looks like a known mistake"), std::string::npos);
    EXPECT_EQ(html.find("<script"), std::string::npos);
    // Moved away from its folder it still shows everything.
    fs::copy_file(out_ / "report.html", scratch_ / "moved.html", fs::copy_options::overwrite_existing);
    EXPECT_EQ(imageSources(slurp(scratch_ / "moved.html")), sources);
}

TEST_F(ReportPage, GradescopeResultsCarryThePictures) {
    ASSERT_EQ(grade_.exit_code, 1) << grade_.output;
    std::ifstream in(out_ / "results.json");
    const json results = json::parse(in, nullptr, false);
    ASSERT_FALSE(results.is_discarded());
    std::vector<std::string> sources;
    for (const json& test : results["tests"]) {
        EXPECT_EQ(test["output_format"], "html");
        const std::vector<std::string> s = imageSources(test["output"].get<std::string>());
        sources.insert(sources.end(), s.begin(), s.end());
    }
    // The failing goal's first wrong image: yours, the reference and the two difference pictures.
    EXPECT_GE(sources.size(), 4u);
    expectPicturesDecode(sources, out_, scratch_);
    // Within the 2 MB the writer allows for pictures, plus the text.
    EXPECT_LT(fs::file_size(out_ / "results.json"), 3u << 20);
}

TEST_F(ReportPage, HtmlTidyFindsNoProblem) {
    ASSERT_EQ(grade_.exit_code, 1) << grade_.output;
    if (!installed("tidy"))
        GTEST_SKIP() << "HTML Tidy is not installed (apt-get install tidy; scripts/setup.sh does)";
    const Ran tidy = run("tidy -errors -quiet -utf8 " + (out_ / "report.html").string());
    EXPECT_EQ(tidy.exit_code, 0) << tidy.output;  // 1: warnings, 2: errors
}

TEST_F(ReportPage, ChromiumRendersItOnALaptopAndAPhone) {
    ASSERT_EQ(grade_.exit_code, 1) << grade_.output;
    if (!installed("chromium"))
        GTEST_SKIP() << "Chromium is not installed (apt-get install chromium; scripts/setup.sh does)";
    for (const auto& [width, height] : {std::make_pair(1280, 2000), std::make_pair(390, 2000)}) {
        const grader::Image shot = screenshot(out_ / "report.html", width, height, scratch_);
        ASSERT_EQ(shot.width, width);
        ASSERT_EQ(shot.height, height);
        // Text, badges and the pictures: far more than a blank or unstyled page has.
        EXPECT_GT(colours(shot), 500u) << width;
        // Nothing wider than the screen: the rightmost column of pixels is the page's margin,
        // its background (#f6f6f6) from top to bottom.
        int covered = 0;
        for (int y = 0; y < height; ++y)
            for (int c = 0; c < 3; ++c)
                covered += std::abs(shot.at(width - 1, y, c) - 246.0f / 255.0f) > 0.02f;
        EXPECT_EQ(covered, 0) << "at " << width << " pixels something is wider than the page";
    }
}

}  // namespace
