// What the workbench's server answers, decided from a request's method and path alone. A path
// names the page, one of its assets compiled into the program, the state, the event stream, a
// picture by number or a pixel by number: nothing in a path is ever used as a file name, so a
// request cannot reach the file system, whatever it holds ("/../", "%2e%2e", "//etc/passwd").
#pragma once

#include <cstdint>
#include <string>

namespace shaderlab::serve {

enum class RouteKind { NotFound, Page, Asset, State, Events, View, Picture, Pixel, MethodNotAllowed };

struct Route {
    RouteKind kind = RouteKind::NotFound;
    std::string asset;      // Asset: the asset's name ("workbench.js")
    std::uint64_t seq = 0;  // Picture, Pixel: the snapshot
    std::string picture;    // Picture: student | reference | diff | file | debug
    int index = 0;          // Picture, Pixel: the image (or input file)
    int x = 0, y = 0;       // Pixel
};

// `path` is the request's path as the HTTP library decoded it (no query string).
Route routeRequest(const std::string& method, const std::string& path);

// The assets compiled into the program (framework/serve/assets/).
struct Asset {
    const char* name;
    const char* content_type;
    const unsigned char* data;
    std::size_t size;
};
const Asset* findAsset(const std::string& name);
// Every asset, for the page weight and the tests; ends with a null name.
const Asset* allAssets();

}  // namespace shaderlab::serve
