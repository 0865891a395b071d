// base64 and file reading for embedded images; see embed.h.
#include "embed.h"

#include <fstream>
#include <iterator>
#include <utility>

namespace grader::detail {

std::string base64(const std::string& bytes) {
    static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    std::size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) |
                           (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                           static_cast<unsigned char>(bytes[i + 2]);
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += kAlphabet[(v >> 6) & 63];
        out += kAlphabet[v & 63];
    }
    if (i < bytes.size()) {
        const bool two = i + 1 < bytes.size();
        const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) |
                           (two ? static_cast<unsigned char>(bytes[i + 1]) << 8 : 0u);
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += two ? kAlphabet[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

std::string readFileBytes(const std::string& path, bool* ok) {
    std::ifstream in(path, std::ios::binary);
    *ok = static_cast<bool>(in);
    if (!*ok) return {};
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

namespace {

std::string join(const std::string& root, const std::string& path) {
    return root.empty() || root.back() == '/' ? root + path : root + "/" + path;
}

}  // namespace

AllOrNothing::AllOrNothing(const std::vector<std::string>& paths, const ImageEmbedding& embedding) {
    for (const std::string& p : paths) uris_.emplace(p, p);
    if (embedding.image_root.empty()) return;
    std::map<std::string, std::string> bytes;
    std::size_t total = 0;
    for (const auto& [path, ignored] : uris_) {
        if (path.empty()) continue;
        bool ok = false;
        std::string b = readFileBytes(join(embedding.image_root, path), &ok);
        if (!ok) return;
        total += dataUriSize(b.size());
        if (total > embedding.max_embedded_bytes) return;
        bytes.emplace(path, std::move(b));
    }
    for (auto& [path, b] : bytes) uris_[path] = "data:image/png;base64," + base64(b);
    embedded_ = true;
    bytes_ = total;
}

const std::string& AllOrNothing::src(const std::string& path) const {
    static const std::string kNone;
    const auto it = uris_.find(path);
    return it == uris_.end() ? kNone : it->second;
}

std::string Budget::take(const std::string& path) {
    if (embedding_.image_root.empty() || path.empty()) return {};
    bool ok = false;
    const std::string b = readFileBytes(join(embedding_.image_root, path), &ok);
    if (!ok || spent_ + dataUriSize(b.size()) > embedding_.max_embedded_bytes) {
        ++left_out_;
        return {};
    }
    spent_ += dataUriSize(b.size());
    return "data:image/png;base64," + base64(b);
}

}  // namespace grader::detail
