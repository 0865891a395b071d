// Both headless backends give a usable core context of at least 3.3.
#include "gl_test_support.h"
#include "shaderlab/gl.h"

#include <gtest/gtest.h>

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

INSTANTIATE_TEST_SUITE_P(Backends, GlContextTest, ::testing::Values(Backend::OSMesa, Backend::Egl),
                         [](const auto& param_info) { return std::string(shaderlab::backendName(param_info.param)); });

}  // namespace
