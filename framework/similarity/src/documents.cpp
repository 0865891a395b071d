// Documents: starter masking, pieces and fingerprints; see documents.h and similarity.h.
#include "documents.h"

#include <algorithm>

#include "shaderlab/similarity/glsl_tokens.h"

namespace shaderlab::similarity::detail {

namespace {

bool isPunct(const std::string& text, const Token& t, char c) {
    return t.kind == TokenKind::Operator && t.end == t.begin + 1 && text[t.begin] == c;
}

}  // namespace

void addStarterText(const std::string& text, std::size_t k, StarterKgrams* starter) {
    const std::vector<std::uint64_t> hashes = normalisedHashes(text, lexGlsl(text));
    for (std::uint64_t h : kgramHashes(hashes, k)) starter->insert(h);
}

void addStudentFile(const std::string& name, const std::string& text, const StarterKgrams& starter,
                    std::size_t k, std::size_t w, Document* doc) {
    const std::uint32_t file = static_cast<std::uint32_t>(doc->files.size());
    doc->files.push_back(SourceFile{name, text});
    const std::vector<Token> tokens = lexGlsl(text);
    const std::vector<std::uint64_t> hashes = normalisedHashes(text, tokens);

    // Starter text: every token inside a k-gram the starter has too.
    std::vector<bool> masked(tokens.size(), false);
    const std::vector<std::uint64_t> kgrams = kgramHashes(hashes, k);
    for (std::size_t i = 0; i < kgrams.size(); ++i)
        if (starter.count(kgrams[i]) != 0) std::fill(masked.begin() + i, masked.begin() + i + k, true);

    std::vector<std::uint64_t> piece;
    std::vector<std::uint32_t> piece_lines;
    auto flush = [&]() {
        if (piece.size() >= k) {
            const std::uint32_t offset = static_cast<std::uint32_t>(doc->tokens.size());
            for (std::size_t i = 0; i < piece.size(); ++i)
                doc->tokens.push_back(DocToken{piece[i], piece_lines[i], file});
            for (Fingerprint f : winnow(kgramHashes(piece, k), w)) {
                f.position += offset;
                doc->fingerprints.push_back(f);
            }
        }
        piece.clear();
        piece_lines.clear();
    };
    int depth = 0;  // of braces, over the whole file, masked tokens included
    for (std::size_t i = 0; i < tokens.size(); ++i) {
        const Token& t = tokens[i];
        if (t.kind == TokenKind::Preprocessor) flush();
        if (masked[i]) {
            flush();
        } else {
            piece.push_back(hashes[i]);
            piece_lines.push_back(t.line);
        }
        if (isPunct(text, t, '{')) {
            ++depth;
        } else if (isPunct(text, t, '}')) {
            depth = std::max(0, depth - 1);
            if (depth == 0) flush();
        } else if (depth == 0 && isPunct(text, t, ';')) {
            flush();
        }
    }
    flush();
}

void finishDocument(Document* doc) {
    doc->by_hash.clear();
    doc->by_hash.reserve(doc->fingerprints.size());
    for (const Fingerprint& f : doc->fingerprints) doc->by_hash.emplace_back(f.hash, f.position);
    // Sorted by hash, then position: the first of equal hashes is the first occurrence.
    std::sort(doc->by_hash.begin(), doc->by_hash.end());
    doc->by_hash.erase(std::unique(doc->by_hash.begin(), doc->by_hash.end(),
                                   [](const auto& a, const auto& b) { return a.first == b.first; }),
                       doc->by_hash.end());
}

std::string refuseText(const std::string& text) {
    // A NUL never appears in a shader; a compiled object, an image or a zip has them at once.
    if (text.find('\0') != std::string::npos) return "binary content (NUL bytes), not a shader";
    return {};
}

}  // namespace shaderlab::similarity::detail
