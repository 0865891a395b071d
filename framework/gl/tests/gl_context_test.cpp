// Both headless backends give a usable core context of at least 3.3 (and, in the ASan build, a
// leak of ours beside them is still reported).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>

#include "gl_test_support.h"
#include "shaderlab/base/sanitizer.h"
#include "shaderlab/gl/gl.h"

namespace {

using shaderlab::Backend;

class GlContextTest : public ::testing::TestWithParam<Backend> {};

TEST_P(GlContextTest, CoreContextOfAtLeast33) {
    std::string err;
    shaderlab::GlContext* ctx = shaderlab::testing::sharedContext(GetParam(), &err);
    ASSERT_NE(ctx, nullptr) << err;
    const auto& info = ctx->info();
    EXPECT_TRUE(info.major > 3 || (info.major == 3 && info.minor >= 3)) << info.version;
    EXPECT_FALSE(info.renderer.empty());
    GLint mask = 0;
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
    EXPECT_TRUE(mask & GL_CONTEXT_CORE_PROFILE_BIT);
}

TEST(GlContextNames, ParseBackend) {
    Backend b{};
    EXPECT_TRUE(shaderlab::parseBackend("egl", &b));
    EXPECT_EQ(b, Backend::Egl);
    EXPECT_TRUE(shaderlab::parseBackend("osmesa", &b));
    EXPECT_EQ(b, Backend::OSMesa);
    EXPECT_FALSE(shaderlab::parseBackend("vulkan", &b));
}

// "auto" is OSMesa, silently, where libOSMesa opens, and EGL with a note saying why where it does not.
TEST(GlContextNames, AutoIsOSMesaWhereItOpensElseEglWithANote) {
    Backend b{};
    std::string note = "stale";
    ASSERT_TRUE(shaderlab::parseBackend("auto", &b, &note));
    if (b == Backend::OSMesa) {
        EXPECT_EQ(note, "");
    } else {
        EXPECT_EQ(b, Backend::Egl);
        EXPECT_NE(note.find("rendering with EGL (surfaceless) instead"), std::string::npos) << note;
    }
    ASSERT_TRUE(shaderlab::parseBackend("egl", &b, &note));
    EXPECT_EQ(note, "") << "an explicit backend needs no note";
}

// A context that is too old is refused with a message naming the version it has. The fake
// driver answers only glGetString, as an OpenGL 2.1 implementation would.
const GLubyte* fakeGetString(GLenum name) {
    switch (name) {
        case GL_VERSION:
            return reinterpret_cast<const GLubyte*>("2.1 Mesa 9.0");
        case GL_RENDERER:
            return reinterpret_cast<const GLubyte*>("fake renderer");
        case GL_VENDOR:
            return reinterpret_cast<const GLubyte*>("fake vendor");
        default:
            return reinterpret_cast<const GLubyte*>("");
    }
}

shaderlab::GlProc fakeGetProc(const char* name) {
    if (std::string(name) == "glGetString") return reinterpret_cast<shaderlab::GlProc>(&fakeGetString);
    return nullptr;
}

TEST(GlContextVersion, TooOldContextNamesTheVersionFound) {
    shaderlab::GlInfo info;
    std::string error;
    EXPECT_FALSE(shaderlab::loadGl(&fakeGetProc, &info, &error));
    EXPECT_EQ(info.major, 2);
    EXPECT_EQ(info.minor, 1);
    EXPECT_NE(error.find("3.3"), std::string::npos) << error;
    EXPECT_NE(error.find("2.1 Mesa 9.0"), std::string::npos) << error;
}

#if SHADERLAB_ASAN
// The sanitizer build suppresses the GL driver's own leaks (tests/asan/lsan.supp, and
// keepLoadedLibrariesMapped in gl_context.cpp so that LSan can name the driver). A leak of ours
// beside a context of each backend must still be reported, and be the only one: this test runs
// itself again in a child process that leaks 4242 bytes on purpose, and reads LSan's report.
char* volatile g_lost = nullptr;  // volatile: the compiler keeps the allocation

TEST(LeakSanitizer, OurLeakIsReportedAndTheDriversAreNot) {
    if (std::getenv("SHADERLAB_LEAK_ON_PURPOSE")) {
        for (Backend b : {Backend::OSMesa, Backend::Egl}) {
            shaderlab::ContextResult r = shaderlab::createHeadlessContext(b);
            ASSERT_NE(r.context, nullptr) << r.error;
            GLuint texture = 0;  // make the driver allocate
            glGenTextures(1, &texture);
            glDeleteTextures(1, &texture);
        }  // each context destroyed: the DRI driver is closed by now, as at the end of a grade
        g_lost = new char[4242];
        g_lost = nullptr;
        return;
    }
    char self[4096] = {};
    ASSERT_GT(readlink("/proc/self/exe", self, sizeof self - 1), 0);
    const std::string command = std::string("SHADERLAB_LEAK_ON_PURPOSE=1 LSAN_OPTIONS=suppressions=") +
                                SHADERLAB_SOURCE_DIR + "/tests/asan/lsan.supp:print_suppressions=0 " + self +
                                " --gtest_filter=LeakSanitizer.OurLeakIsReportedAndTheDriversAreNot 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    std::string output;
    char buf[4096];
    while (std::fgets(buf, sizeof buf, pipe)) output += buf;
    const int status = pclose(pipe);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) != 0) << output;
    EXPECT_NE(output.find("[  PASSED  ] 1 test"), std::string::npos) << output;
    EXPECT_NE(output.find("Direct leak of 4242 byte(s) in 1 object(s)"), std::string::npos) << output;
    EXPECT_NE(output.find("gl_context_test.cpp"), std::string::npos) << output;
    EXPECT_NE(output.find("SUMMARY: AddressSanitizer: 4242 byte(s) leaked in 1 allocation(s)."),
              std::string::npos)
        << output;
    EXPECT_EQ(output.find("<unknown module>"), std::string::npos) << output;
}
#endif

INSTANTIATE_TEST_SUITE_P(Backends, GlContextTest, ::testing::Values(Backend::OSMesa, Backend::Egl),
                         [](const auto& param_info) {
                             return std::string(shaderlab::backendName(param_info.param));
                         });

}  // namespace
