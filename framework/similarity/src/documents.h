// One student's lab as the similarity report sees it: the student's own tokens once the starter
// is masked, cut into pieces, and their winnowed fingerprints. Private to the library.
#pragma once

#include <cstdint>
#include <string>
#include <unordered_set>
#include <utility>
#include <vector>

#include "shaderlab/similarity/similarity.h"
#include "shaderlab/similarity/winnowing.h"

namespace shaderlab::similarity::detail {

// Every k-gram hash of the code the course gives for a lab.
using StarterKgrams = std::unordered_set<std::uint64_t>;

struct DocToken {
    std::uint64_t hash = 0;
    std::uint32_t line = 0;
    std::uint32_t file = 0;  // index into Document::files
};

struct Document {
    StudentRef who;
    bool current = true;
    std::vector<SourceFile> files;
    std::vector<DocToken> tokens;           // the pieces one after the other
    std::vector<Fingerprint> fingerprints;  // positions index `tokens`; a k-gram never leaves its piece
    // The distinct fingerprint hashes, sorted, each with the position of its first occurrence.
    std::vector<std::pair<std::uint64_t, std::uint32_t>> by_hash;
};

// Adds the k-grams of a starter file's text.
void addStarterText(const std::string& text, std::size_t k, StarterKgrams* starter);

// Adds one student file: its tokens, less those the starter covers, cut into pieces, winnowed.
void addStudentFile(const std::string& name, const std::string& text, const StarterKgrams& starter,
                    std::size_t k, std::size_t w, Document* doc);

// Fills `by_hash` once every file is in.
void finishDocument(Document* doc);

// Why `text` is not a shader to compare ("" when it is): binary content.
std::string refuseText(const std::string& text);

}  // namespace shaderlab::similarity::detail
