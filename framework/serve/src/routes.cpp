#include "shaderlab/serve/routes.h"

#include <cstring>
#include <vector>

namespace shaderlab::serve {

namespace {

std::vector<std::string> split(const std::string& path) {
    std::vector<std::string> parts;
    std::string part;
    for (std::size_t i = 1; i <= path.size(); ++i) {
        if (i == path.size() || path[i] == '/') {
            parts.push_back(part);
            part.clear();
        } else {
            part.push_back(path[i]);
        }
    }
    return parts;
}

// A decimal number of at most `digits` digits, nothing else.
bool number(const std::string& s, std::size_t digits, std::uint64_t* out) {
    if (s.empty() || s.size() > digits) return false;
    std::uint64_t v = 0;
    for (char c : s) {
        if (c < '0' || c > '9') return false;
        v = v * 10 + static_cast<std::uint64_t>(c - '0');
    }
    *out = v;
    return true;
}

}  // namespace

Route routeRequest(const std::string& method, const std::string& path) {
    Route r;
    if (path.empty() || path[0] != '/' || path.size() > 256) return r;
    const bool get = method == "GET" || method == "HEAD";
    auto only = [&](bool allowed, RouteKind kind) {
        r.kind = allowed ? kind : RouteKind::MethodNotAllowed;
        return r;
    };
    if (path == "/" || path == "/index.html") return only(get, RouteKind::Page);
    if (path == "/api/state") return only(get, RouteKind::State);
    if (path == "/events") return only(get, RouteKind::Events);
    if (path == "/api/view") return only(method == "POST", RouteKind::View);
    // Browsers ask for /favicon.ico whatever the page names: the page's own icon.
    if (path == "/favicon.ico") {
        r.asset = "favicon.svg";
        return only(get, RouteKind::Asset);
    }
    const std::vector<std::string> parts = split(path);
    // /assets/<name>: a name from the compiled-in table, compared as a string.
    if (parts.size() == 2 && parts[0] == "assets") {
        if (!findAsset(parts[1])) return r;
        r.asset = parts[1];
        return only(get, RouteKind::Asset);
    }
    // /picture/<seq>/<student|reference|diff|file|debug>/<index>.png
    if (parts.size() == 4 && parts[0] == "picture") {
        std::uint64_t seq = 0, index = 0;
        const std::string& last = parts[3];
        if (!number(parts[1], 18, &seq) || last.size() < 5 || last.compare(last.size() - 4, 4, ".png") != 0 ||
            !number(last.substr(0, last.size() - 4), 4, &index))
            return r;
        const std::string& kind = parts[2];
        if (kind != "student" && kind != "reference" && kind != "diff" && kind != "file" && kind != "debug")
            return r;
        r.seq = seq;
        r.picture = kind;
        r.index = static_cast<int>(index);
        return only(get, RouteKind::Picture);
    }
    // /api/pixel/<seq>/<index>/<x>/<y>
    if (parts.size() == 6 && parts[0] == "api" && parts[1] == "pixel") {
        std::uint64_t seq = 0, index = 0, x = 0, y = 0;
        if (!number(parts[2], 18, &seq) || !number(parts[3], 4, &index) || !number(parts[4], 5, &x) ||
            !number(parts[5], 5, &y))
            return r;
        r.seq = seq;
        r.index = static_cast<int>(index);
        r.x = static_cast<int>(x);
        r.y = static_cast<int>(y);
        return only(get, RouteKind::Pixel);
    }
    return r;
}

}  // namespace shaderlab::serve
