#include "shaderlab/live/diagnostic_view.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace shaderlab::viewer {

namespace {

constexpr std::uintmax_t kMaxSourceBytes = 1u << 20;

// The file `name` of the lab folder, absolute and resolved, or "" when it is not a regular file
// inside the folder.
std::string fileInFolder(const std::string& folder, const std::string& name) {
    if (name.empty() || folder.empty()) return {};
    const fs::path rel = fs::path(name).lexically_normal();
    if (rel.is_absolute() || rel.empty() || *rel.begin() == "..") return {};
    std::error_code ec;
    const fs::path root = fs::canonical(folder, ec);
    if (ec) return {};
    const fs::path path = fs::canonical(root / rel, ec);
    if (ec || !fs::is_regular_file(path, ec)) return {};
    const fs::path inside = path.lexically_relative(root);
    if (inside.empty() || *inside.begin() == "..") return {};
    if (fs::file_size(path, ec) > kMaxSourceBytes || ec) return {};
    return path.string();
}

std::vector<std::string> readLines(const std::string& path) {
    std::vector<std::string> lines;
    std::ifstream in(path, std::ios::binary);
    std::string line;
    while (std::getline(in, line)) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        lines.push_back(std::move(line));
    }
    return lines;
}

// The diagnostic's source_line is cut after 240 characters with " ..." added.
bool sameLine(const std::string& file_line, const std::string& quoted) {
    if (quoted == file_line) return true;
    const std::string cut = " ...";
    return quoted.size() > cut.size() && quoted.compare(quoted.size() - cut.size(), cut.size(), cut) == 0 &&
           file_line.compare(0, quoted.size() - cut.size(), quoted, 0, quoted.size() - cut.size()) == 0;
}

// Spaces (and the line's own tabs) up to 1-based `column`, one per character.
std::string caretPad(const std::string& line, int column) {
    std::string pad;
    for (std::size_t i = 0; i + 1 < static_cast<std::size_t>(column) && i < line.size(); ++i) {
        const unsigned char c = static_cast<unsigned char>(line[i]);
        if ((c & 0xC0) == 0x80) continue;  // a UTF-8 continuation byte: the same character
        pad += c == '\t' ? '\t' : ' ';
    }
    return pad;
}

bool shellSafe(const std::string& s) {
    return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) ||
               std::string("/._-+,:@%=").find(c) != std::string::npos;
    });
}

}  // namespace

DiagnosticView viewDiagnostic(const Diagnostic& d, const std::string& lab_folder, int around) {
    DiagnosticView v;
    v.diagnostic = d;
    v.path = fileInFolder(lab_folder, d.file);
    if (v.path.empty() || d.line <= 0) return v;
    const std::vector<std::string> lines = readLines(v.path);
    if (static_cast<std::size_t>(d.line) > lines.size()) return v;
    // Saved again since the render: its lines belong to the next message, not this one.
    if (!d.source_line.empty() && !sameLine(lines[static_cast<std::size_t>(d.line - 1)], d.source_line))
        return v;
    const int first = std::max(1, d.line - around);
    const int last = std::min(static_cast<int>(lines.size()), d.line + around);
    for (int n = first; n <= last; ++n) v.context.push_back({n, lines[static_cast<std::size_t>(n - 1)]});
    return v;
}

std::string formatWithContext(const DiagnosticView& v) {
    const Diagnostic& d = v.diagnostic;
    std::string s =
        d.file + (d.line > 0 ? ":" + std::to_string(d.line) : "") + ": " + d.severity + ": " + d.message;
    std::vector<SourceLine> lines = v.context;
    if (lines.empty() && !d.source_line.empty()) lines.push_back({d.line, d.source_line});
    std::size_t width = 0;
    for (const SourceLine& l : lines) width = std::max(width, std::to_string(l.number).size());
    const std::string gutter = " " + std::string(width, ' ') + " ";
    for (const SourceLine& l : lines) {
        const std::string n = std::to_string(l.number);
        s += "\n " + std::string(width - n.size(), ' ') + n + " | " + l.text;
        if (l.number == d.line && d.column > 0 && static_cast<std::size_t>(d.column) <= l.text.size() + 1)
            s += "\n" + gutter + "| " + caretPad(l.text, d.column) + "^";
    }
    std::string note = d.explanation;
    if (d.follow_on > 0)
        note += std::string(note.empty() ? "" : " ") + "(" + std::to_string(d.follow_on) + " more " +
                (d.follow_on == 1 ? "error" : "errors") + " after this one, probably caused by it)";
    if (!note.empty()) s += "\n" + gutter + "= " + note;
    return s;
}

std::string editorCommand(const DiagnosticView& v) {
    if (v.path.empty()) return {};
    const char* env = std::getenv("EDITOR");
    const std::string editor = env && *env ? env : "vi";
    std::string path = v.path;
    if (!shellSafe(path)) {
        std::string quoted = "'";
        for (char c : path) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
        path = quoted + "'";
    }
    return editor + (v.diagnostic.line > 0 ? " +" + std::to_string(v.diagnostic.line) : "") + " " + path;
}

std::string editorLink(const DiagnosticView& v) {
    if (v.path.empty()) return {};
    std::ostringstream out;
    out << "vscode://file";
    for (unsigned char c : v.path) {
        if (std::isalnum(c) || std::string("/._-~").find(static_cast<char>(c)) != std::string::npos)
            out << static_cast<char>(c);
        else
            out << '%' << "0123456789ABCDEF"[c >> 4] << "0123456789ABCDEF"[c & 15];
    }
    if (v.diagnostic.line > 0) out << ':' << v.diagnostic.line << ':' << std::max(1, v.diagnostic.column);
    return out.str();
}

}  // namespace shaderlab::viewer
