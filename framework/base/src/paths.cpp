#include "shaderlab/base/paths.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

namespace fs = std::filesystem;

namespace shaderlab {

namespace {

bool isWithin(const fs::path& root, const fs::path& p) {
    auto r = root.begin();
    auto q = p.begin();
    for (; r != root.end(); ++r, ++q) {
        if (q == p.end() || *r != *q) return false;
    }
    return true;
}

}  // namespace

PathResult resolveInside(const std::string& root, const std::string& relative) {
    PathResult res;
    const std::string shown = (fs::path(root) / relative).string();
    if (relative.empty()) {
        res.error = root + ": empty file name";
        return res;
    }
    if (fs::path(relative).is_absolute()) {
        res.error = shown + ": absolute paths are not allowed here";
        return res;
    }
    std::error_code ec;
    const fs::path canon_root = fs::canonical(root, ec);
    if (ec) {
        res.error = root + ": folder not found";
        return res;
    }
    const fs::path joined = canon_root / relative;
    if (!fs::exists(fs::symlink_status(joined, ec))) {
        res.missing = true;
        res.error = shown + ": file not found";
        return res;
    }
    const fs::path canon = fs::canonical(joined, ec);
    if (ec) {
        res.missing = true;
        res.error = shown + ": broken link or unreadable path";
        return res;
    }
    if (!isWithin(canon_root, canon)) {
        res.missing = true;
        res.error = shown + ": resolves outside " + canon_root.string() + " (symlink or ..), refused";
        return res;
    }
    if (!fs::is_regular_file(canon, ec)) {
        res.error = shown + ": not a regular file";
        return res;
    }
    res.ok = true;
    res.path = canon.string();
    return res;
}

FileText readFile(const std::string& path, std::size_t max_bytes) {
    FileText out;
    out.path = path;
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
        out.missing = !fs::exists(path, ec);
        out.error = path + (out.missing ? ": file not found" : ": not a regular file");
        return out;
    }
    const auto size = fs::file_size(path, ec);
    if (ec) {
        out.error = path + ": cannot read size";
        return out;
    }
    if (size > max_bytes) {
        out.error = path + ": file is " + std::to_string(size) + " bytes, more than the limit of " +
                    std::to_string(max_bytes);
        return out;
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        out.error = path + ": cannot open";
        return out;
    }
    std::ostringstream ss;
    ss << in.rdbuf();
    out.text = ss.str();
    out.ok = true;
    return out;
}

FileText readFileInside(const std::string& root, const std::string& relative, std::size_t max_bytes) {
    const PathResult p = resolveInside(root, relative);
    if (!p.ok) {
        FileText out;
        out.path = (fs::path(root) / relative).string();
        out.error = p.error;
        out.missing = p.missing;
        return out;
    }
    return readFile(p.path, max_bytes);
}

std::string defaultLabsRoot(const std::string& start) {
    if (const char* env = std::getenv("SHADERLAB_LABS"); env && *env) return env;
    std::error_code ec;
    fs::path dir = start.empty() ? fs::current_path(ec) : fs::absolute(start, ec);
    if (ec) return {};
    // Like git finding its repository: the nearest folder, from here upward, whose labs/ holds
    // a lab. So a copied course grades its own files, wherever the program was built.
    for (;;) {
        const fs::path labs = dir / "labs";
        if (fs::is_directory(labs, ec)) {
            for (const auto& entry : fs::directory_iterator(labs, ec))
                if (fs::is_regular_file(entry.path() / "lab.json", ec)) return labs.string();
        }
        if (!dir.has_parent_path() || dir.parent_path() == dir) return {};
        dir = dir.parent_path();
    }
}

}  // namespace shaderlab
