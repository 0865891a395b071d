// Both headless backends give a usable core context of at least 3.3.
#include <gtest/gtest.h>

#include "gl_test_support.h"
#include "shaderlab/gl.h"

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

INSTANTIATE_TEST_SUITE_P(Backends, GlContextTest, ::testing::Values(Backend::OSMesa, Backend::Egl),
                         [](const auto& param_info) {
                             return std::string(shaderlab::backendName(param_info.param));
                         });

}  // namespace
