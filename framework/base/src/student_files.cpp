// Student files found without regard to case, and read with messages in the student's names; see
// student_files.h.
#include "shaderlab/base/student_files.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <system_error>
#include <vector>

namespace fs = std::filesystem;

namespace shaderlab {

namespace {

std::string lowered(std::string s) {
    for (char& c : s)
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return s;
}

// A name from a student's folder, safe to put in a message: control characters and bytes past
// ASCII as \xNN (a message may end up on a terminal), at most 60 bytes.
std::string shownName(const std::string& name) {
    std::string out;
    for (unsigned char c : name) {
        if (out.size() >= 60) return out + "...";
        if (c < 0x20 || c == 0x7f) {
            char hex[8];
            std::snprintf(hex, sizeof hex, "\\x%02X", c);
            out += hex;
        } else {
            out += static_cast<char>(c);
        }
    }
    return out;
}

// Whether `p` lies inside `root`, links resolved: a folder that is a link out is not listed.
bool inside(const fs::path& root, const fs::path& p) {
    std::error_code ec;
    const fs::path r = fs::canonical(root, ec), q = fs::canonical(p, ec);
    if (ec) return false;
    auto a = r.begin(), b = q.begin();
    for (; a != r.end(); ++a, ++b)
        if (b == q.end() || *a != *b) return false;
    return true;
}

// "its folder holds: a.frag, notes.txt" (at most six names), or "its folder is empty".
std::string folderContents(const fs::path& root, const fs::path& dir) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec) || !inside(root, dir)) return "its folder is not there";
    std::vector<std::string> names;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
        names.push_back(it->path().filename().string());
    if (names.empty()) return "its folder is empty";
    std::sort(names.begin(), names.end());
    std::string out = "its folder holds: ";
    for (std::size_t i = 0; i < names.size() && i < 6; ++i) out += (i ? ", " : "") + shownName(names[i]);
    if (names.size() > 6) out += ", and " + std::to_string(names.size() - 6) + " more";
    return out;
}

// `text` with every `from` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
    if (from.empty()) return text;
    for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
        text.replace(at, from.size(), to);
    return text;
}

}  // namespace

std::string findIgnoringCase(const std::string& root, const std::string& relative) {
    const fs::path wanted(relative);
    if (relative.empty() || wanted.is_absolute()) return {};
    fs::path dir(root), found;
    std::error_code ec;
    for (const fs::path& part : wanted) {
        // Never through a link: what it leads to may lie outside the root, and is not listed.
        if (part == "." || part == ".." || (!found.empty() && fs::is_symlink(dir, ec))) return {};
        const std::string key = lowered(part.string());
        std::string match;
        int matches = 0;
        for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
            const std::string name = it->path().filename().string();
            if (lowered(name) == key) {
                match = name;
                ++matches;
            }
        }
        if (ec || matches != 1) return {};
        dir /= match;
        found /= match;
    }
    return found == wanted ? std::string() : found.generic_string();
}

std::string caseNote(const std::string& found, const std::string& expected) {
    return "found " + found + "; the lab expects " + expected;
}

bool isCaseNote(const std::string& message) {
    return message.rfind("found ", 0) == 0 && message.find("; the lab expects ") != std::string::npos;
}

FileText readStudentFile(const std::string& root, const std::string& relative, const std::string& shown,
                         std::size_t max_bytes, std::string* case_note) {
    FileText t = readFileInside(root, relative, max_bytes);
    if (!t.ok && t.missing) {
        const std::string other = findIgnoringCase(root, relative);
        if (!other.empty()) {
            FileText by_case = readFileInside(root, other, max_bytes);
            if (by_case.ok || !by_case.missing) {
                // The found file's name as the student sees it: `shown`'s folders, its own name.
                const std::string found =
                    (fs::path(shown).parent_path() / fs::path(other).filename()).generic_string();
                if (case_note) *case_note = caseNote(found, shown);
                t = std::move(by_case);
            }
        }
    }
    if (t.ok) return t;
    // The resolver names the file by its absolute path (a submission unpacked into a results
    // folder, a temporary folder): the student knows it by its name in the lab.
    std::error_code ec;
    t.error = replaced(t.error, (fs::path(root) / relative).string(), shown);
    const fs::path canonical_root = fs::canonical(root, ec);
    if (!ec) t.error = replaced(t.error, "outside " + canonical_root.string(), "outside the submission");
    if (root.size() > 1) t.error = replaced(t.error, root, "the submission");
    if (t.missing && t.error == shown + ": file not found")
        t.error += " (" + folderContents(root, (fs::path(root) / relative).parent_path()) + ")";
    t.path = shown;
    return t;
}

}  // namespace shaderlab
