// Test support for the similarity tests: scratch folders, the course's labs, and the disguises a
// student who copies puts on a file (names, order of functions, comments, layout).
#pragma once

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "shaderlab/similarity/glsl_tokens.h"

namespace shaderlab::similarity_testing {

namespace fs = std::filesystem;

inline const fs::path kSource = SHADERLAB_SOURCE_DIR;
inline const std::string kLabs = (kSource / "labs").string();

// Scratch folders, removed when the test program ends.
struct ScratchFolders {
    std::vector<fs::path> made;
    ~ScratchFolders() {
        std::error_code ec;
        for (const fs::path& p : made) fs::remove_all(p, ec);
    }
};
inline ScratchFolders scratch_folders;

inline fs::path scratch(const std::string& name) {
    const fs::path p =
        fs::temp_directory_path() / ("shaderlab_similarity_" + name + "_" + std::to_string(getpid()));
    fs::remove_all(p);
    fs::create_directories(p);
    scratch_folders.made.push_back(p);
    return p;
}

inline std::string readText(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

inline void writeText(const fs::path& p, const std::string& text) {
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
}

inline std::vector<std::string> labIds() {
    std::vector<std::string> ids;
    for (const auto& e : fs::directory_iterator(kLabs))
        if (fs::exists(e.path() / "lab.json")) ids.push_back(e.path().filename().string());
    std::sort(ids.begin(), ids.end());
    return ids;
}

inline std::vector<std::string> studentFiles(const std::string& lab) {
    const nlohmann::json spec = nlohmann::json::parse(readText(fs::path(kLabs) / lab / "lab.json"));
    return spec.at("student_files").get<std::vector<std::string>>();
}

// The corpus cases of `lab` of one kind ("alternative", "mistake").
inline std::vector<std::string> corpusCases(const std::string& lab, const std::string& kind) {
    const nlohmann::json cases =
        nlohmann::json::parse(readText(kSource / "tests/corpus" / lab / "cases.json"));
    std::vector<std::string> out;
    for (const auto& c : cases.at("cases"))
        if (c.at("kind") == kind) out.push_back(c.at("name").get<std::string>());
    return out;
}

// A student's copy of a lab: each student file taken from the first of `sources` that has it.
inline void placeLab(const fs::path& student_root, const std::string& lab,
                     const std::vector<fs::path>& sources,
                     std::string (*disguise)(const std::string&) = nullptr) {
    for (const std::string& f : studentFiles(lab)) {
        for (const fs::path& dir : sources) {
            if (!fs::exists(dir / f)) continue;
            const std::string text = readText(dir / f);
            writeText(student_root / lab / f, disguise ? disguise(text) : text);
            break;
        }
    }
}

// What a student who copies does to a file: every name of their own renamed, the functions in the
// opposite order, the comments gone and new ones written, and a layout of their own.
inline std::string disguise(const std::string& text) {
    using similarity::Token;
    using similarity::TokenKind;
    const std::vector<Token> tokens = similarity::lexGlsl(text);
    auto spelled = [&](const Token& t) { return text.substr(t.begin, t.end - t.begin); };
    std::map<std::string, std::string> names;
    // Top-level pieces: ended by a '}' or ';' outside braces or by a directive's line.
    std::vector<std::string> declarations, functions;
    std::string piece;
    int depth = 0;
    std::uint32_t line = 0;
    for (std::size_t i = 0; i < tokens.size(); ++i) {
        const Token& t = tokens[i];
        std::string s = spelled(t);
        if (t.kind == TokenKind::Identifier) {
            auto it = names.find(s);
            if (it == names.end()) it = names.emplace(s, "q" + std::to_string(names.size()) + "_mine").first;
            s = it->second;
        }
        if (t.kind == TokenKind::Preprocessor) {
            if (!piece.empty()) declarations.push_back(piece);
            piece.clear();
            // A directive's own line, with the rest of that line.
            std::string directive = s;
            while (i + 1 < tokens.size() && tokens[i + 1].line == t.line)
                directive += " " + spelled(tokens[++i]);
            declarations.push_back(directive + "\n");
            continue;
        }
        piece += (piece.empty() ? "" : t.line != line ? "\n" + std::string(depth * 3, ' ') : " ") + s;
        line = t.line;
        if (s == "{") ++depth;
        if (s == "}" && --depth == 0) {
            functions.push_back(piece + "\n");
            piece.clear();
        } else if (s == ";" && depth == 0) {
            declarations.push_back(piece + "\n");
            piece.clear();
        }
    }
    std::string out = "/* my own work */\n";
    for (const std::string& d : declarations) out += d;
    for (auto it = functions.rbegin(); it != functions.rend(); ++it) out += "\n// helper\n" + *it;
    return out + piece;
}

}  // namespace shaderlab::similarity_testing
