// The workbench's routes: every path a request may carry maps to something the program made, and
// nothing else; hostile paths (traversal, absolute, encoded, overlong) get nothing.
#include "shaderlab/serve/routes.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

namespace shaderlab::serve {
namespace {

TEST(Routes, ThePageItsAssetsAndTheApi) {
    EXPECT_EQ(routeRequest("GET", "/").kind, RouteKind::Page);
    EXPECT_EQ(routeRequest("GET", "/index.html").kind, RouteKind::Page);
    EXPECT_EQ(routeRequest("GET", "/api/state").kind, RouteKind::State);
    EXPECT_EQ(routeRequest("GET", "/events").kind, RouteKind::Events);
    EXPECT_EQ(routeRequest("POST", "/api/view").kind, RouteKind::View);
    const Route a = routeRequest("GET", "/assets/workbench.js");
    EXPECT_EQ(a.kind, RouteKind::Asset);
    EXPECT_EQ(a.asset, "workbench.js");
    // The icon a browser asks for by its usual name is the page's own, not a 404.
    const Route icon = routeRequest("GET", "/favicon.ico");
    EXPECT_EQ(icon.kind, RouteKind::Asset);
    EXPECT_EQ(icon.asset, "favicon.svg");
    ASSERT_NE(findAsset(icon.asset), nullptr);
    EXPECT_STREQ(findAsset(icon.asset)->content_type, "image/svg+xml");
}

TEST(Routes, PicturesAndPixelsByNumber) {
    const Route p = routeRequest("GET", "/picture/17/diff/3.png");
    ASSERT_EQ(p.kind, RouteKind::Picture);
    EXPECT_EQ(p.seq, 17u);
    EXPECT_EQ(p.picture, "diff");
    EXPECT_EQ(p.index, 3);
    const Route d = routeRequest("GET", "/picture/18/debug/0.png");
    ASSERT_EQ(d.kind, RouteKind::Picture);
    EXPECT_EQ(d.picture, "debug");
    EXPECT_EQ(d.seq, 18u);
    const Route q = routeRequest("GET", "/api/pixel/5/2/100/37");
    ASSERT_EQ(q.kind, RouteKind::Pixel);
    EXPECT_EQ(q.seq, 5u);
    EXPECT_EQ(q.index, 2);
    EXPECT_EQ(q.x, 100);
    EXPECT_EQ(q.y, 37);
}

TEST(Routes, WrongMethodsAreRefused) {
    EXPECT_EQ(routeRequest("POST", "/api/state").kind, RouteKind::MethodNotAllowed);
    EXPECT_EQ(routeRequest("GET", "/api/view").kind, RouteKind::MethodNotAllowed);
    EXPECT_EQ(routeRequest("DELETE", "/").kind, RouteKind::MethodNotAllowed);
}

TEST(Routes, HostilePathsReachNothing) {
    for (const char* path : {"/../etc/passwd",
                             "/assets/../../etc/passwd",
                             "//etc/passwd",
                             "/etc/passwd",
                             "/assets/",
                             "/assets/..",
                             "/assets/./workbench.js",
                             "/assets/workbench.js/",
                             "/assets//workbench.js",
                             "/assets/%2e%2e/x",
                             "/picture/1/student/../../../etc/passwd",
                             "/picture/1/student/-1.png",
                             "/picture/1/student/1.png.png",
                             "/picture/1/student/1",
                             "/picture/1/source/1.png",
                             "/picture/1/debug/../0.png",
                             "/picture/1/normals/0.png",
                             "/picture/x/student/1.png",
                             "/picture/1/student/99999.png",
                             "/picture/1234567890123456789/student/1.png",
                             "/api/pixel/1/1/1",
                             "/api/pixel/1/1/1/1/1",
                             "/api/pixel/1/1/-1/2",
                             "/api/state/",
                             "/api/state/../x",
                             "/index.html/..",
                             "",
                             "relative",
                             "/\\..\\etc\\passwd",
                             "/picture/1/file/../../lab.json"}) {
        const Route r = routeRequest("GET", path);
        EXPECT_EQ(r.kind, RouteKind::NotFound) << path;
    }
    EXPECT_EQ(routeRequest("GET", "/" + std::string(300, 'a')).kind, RouteKind::NotFound);
}

TEST(Routes, TheAssetsAreCompiledIn) {
    int n = 0;
    for (const Asset* a = allAssets(); a->name; ++a) {
        ++n;
        EXPECT_GT(a->size, 100u) << a->name;
        EXPECT_EQ(findAsset(a->name), a);
        // The page fetches nothing from elsewhere (an SVG's namespace is a name, not an address).
        std::string text(reinterpret_cast<const char*>(a->data), a->size);
        for (std::size_t at; (at = text.find("http://www.w3.org/2000/svg")) != std::string::npos;)
            text.erase(at, 26);
        EXPECT_EQ(text.find("http://"), std::string::npos) << a->name;
        EXPECT_EQ(text.find("https://"), std::string::npos) << a->name;
    }
    EXPECT_EQ(n, 4);  // the page, its script, its style, its icon
    ASSERT_NE(findAsset("index.html"), nullptr);
    EXPECT_EQ(std::strncmp(findAsset("index.html")->content_type, "text/html", 9), 0);
    EXPECT_EQ(findAsset("../index.html"), nullptr);
}

}  // namespace
}  // namespace shaderlab::serve
