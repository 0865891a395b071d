// Who copied: a similarity report across a class, per lab, in the spirit of MOSS (Schleimer,
// Wilkerson and Aiken, "Winnowing: local algorithms for document fingerprinting", SIGMOD 2003).
//
// A document is one student's student files of one lab (lab.json "student_files"), tokenised
// with comments, whitespace and identifier names normalised (glsl_tokens.h). The code the course
// gives is masked first: every token covered by a k-gram that also occurs in the lab's starter
// files (labs/<lab>/ and labs/shared/) is removed, so starter text never counts, however a
// student reorders it. What remains is cut at the masked gaps and after each top-level
// declaration (a '}' or ';' outside any braces, and before each directive), so that reordering
// functions changes no fingerprint, and each piece is winnowed (winnowing.h). An inverted index
// from fingerprint to documents gives, per lab, the fingerprints two documents share, without
// comparing any two texts; a fingerprint in too many documents (a common idiom) is ignored.
//
// score = shared / min(|A|, |B|): the share of the smaller document's fingerprints found in the
// other (|X| counts X's distinct fingerprints, common ones left out). A pair is flagged when it
// shares at least min_shared fingerprints (a small document cannot be called a copy on a handful)
// and its score reaches the bar for its length, flagBar(): threshold + length_margin / sqrt(n),
// n = min(|A|, |B|). A share measured on n fingerprints is uncertain by about 1 / sqrt(n), and
// short solutions of a lab written apart share much by chance (the README dictates the formulas:
// two Blinn-Phong solutions of 01-phong written apart share 21 of 26 fingerprints), so a short
// document needs more of it shared. Clusters are the connected components of strong pairs, those
// at least halfway from their bar to 1: a cluster never chains two groups through one pair near
// the bar. Earlier classes (cohorts) are candidates: a pair is reported only when one side is of
// the current class.
//
// Does not: grade, render, unpack zips (the command does, with the batch library), or decide
// that anyone cheated; it points an instructor at pairs to read side by side.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace shaderlab::similarity {

// The defaults are justified by the tests (similarity_corpus_test.cpp), bench/similarity_class.py
// and docs/instructors.md ("Who copied"): on the course's own solutions, disguised copies (names,
// order of functions, comments and layout changed) score 0.83 and more; solutions written apart
// score at most 0.74.
struct SimilarityOptions {
    // k: the noise threshold in tokens. 12 normalised tokens are about one and a half GLSL
    // statements ("vec3 $id = normalize ( $id ) ;" is 8): shorter matches are what any two
    // solutions of a lab share. w: the window; any shared run of t = w + k - 1 = 17 tokens or
    // more (about two statements) is found.
    std::size_t k = 12;
    std::size_t w = 6;
    double threshold = 0.75;
    // The bar rises by length_margin / sqrt(n) above threshold for documents of n fingerprints:
    // 0.85 for 26 (01-phong's solutions), 0.80 for 100, 0.775 for 400.
    double length_margin = 0.5;
    std::size_t min_shared = 10;
    double list_from = 0.4;  // unflagged pairs scoring at least this (and min_shared) are listed too
    // A fingerprint in more than max(common_min_documents, common_share x documents of the lab)
    // documents is a common idiom, not evidence (MOSS's -m, 10 by default). Higher than MOSS's:
    // the starter is masked already, and a solution passed round a class (a leaked one copied by
    // fifteen students of forty) must not vanish as an "idiom".
    std::size_t common_min_documents = 20;
    double common_share = 0.2;
    std::size_t max_file_bytes = 256u << 10;  // a larger student file is refused with a note
    int jobs = 0;                             // labs analysed at once; 0: the number of cores
};

struct SubmissionFolder {
    std::string student;  // the name shown (made printable here)
    std::string root;     // the folder that holds <lab>/<student files>
    std::string cohort;   // "" for the current class, else the earlier class's name
};

struct StudentRef {
    std::string student;
    std::string cohort;  // "" for the current class

    bool operator<(const StudentRef& o) const {
        return cohort != o.cohort ? cohort < o.cohort : student < o.student;
    }
    bool operator==(const StudentRef& o) const { return cohort == o.cohort && student == o.student; }
};

struct LineRange {
    std::string file;  // as in the submission: "<lab>/<file>"
    std::uint32_t first_line = 0, last_line = 0;
};

// A passage the two share: where in each, and how many shared fingerprints it holds.
struct MatchRegion {
    LineRange a, b;
    std::size_t fingerprints = 0;
};

struct PairResult {
    std::string lab;
    StudentRef a, b;  // a < b, except that a current student comes first
    double score = 0.0;
    double a_in_b = 0.0, b_in_a = 0.0;  // shared / |A| and shared / |B|
    std::size_t shared = 0, a_fingerprints = 0, b_fingerprints = 0;
    double bar = 0.0;                  // flagBar() for min(a_fingerprints, b_fingerprints)
    bool flagged = false;              // score >= bar and shared >= min_shared
    bool strong = false;               // flagged and score >= (bar + 1) / 2: it joins a cluster
    std::vector<MatchRegion> regions;  // in a's order
};

// The score a pair whose smaller document holds `fingerprints` must reach to be flagged.
double flagBar(const SimilarityOptions& options, std::size_t fingerprints);

// Why the pair is flagged, or listed without a flag, in one sentence for the page and pairs.json.
std::string pairVerdict(const PairResult& pair, const SimilarityOptions& options);

// Students joined by strong pairs (PairResult::strong).
struct Cluster {
    std::string lab;
    std::vector<StudentRef> students;  // sorted
    double max_score = 0.0;
};

struct LabStats {
    std::string lab;
    std::size_t documents = 0;        // students (all cohorts) who hand in something for the lab
    std::size_t empty_documents = 0;  // nothing of their own once the starter is masked
    // Some of their own, but fewer than min_shared fingerprints: too little to call a copy of
    // anything (a lab whose work is a few lines of the README's formulas), so never flagged.
    std::size_t short_documents = 0;
    std::size_t fingerprints = 0;  // distinct, over the lab
    std::size_t common_fingerprints = 0;
    std::size_t common_limit = 0;  // documents a fingerprint may be in before it counts as common
    std::size_t pairs_listed = 0, pairs_flagged = 0, clusters = 0;
    // The class's own level: the median, over its documents, of each one's closest match's score
    // (0 for a document that shares nothing). Work written apart in this lab shares about this much.
    double median_closest = 0.0;
};

struct SourceFile {
    std::string name;  // "<lab>/<file>"
    std::string text;
};

struct SimilarityReport {
    SimilarityOptions options;
    std::vector<LabStats> labs;
    std::vector<PairResult> pairs;   // by lab, flagged first, then by score, highest first
    std::vector<Cluster> clusters;   // by lab, largest first
    std::vector<std::string> notes;  // files refused or unreadable, labs that cannot be read
    // The student files of each student in a flagged pair, for the side-by-side view, by
    // sourceKey().
    std::map<std::string, std::vector<SourceFile>> sources;
};

std::string sourceKey(const std::string& lab, const StudentRef& who);

// The report over `submissions` for `lab_ids` (folders of `labs_root`). Never throws on bad
// student input: a file that is too large, binary, unreadable or a symlink out of its submission
// is left out with a note naming it.
SimilarityReport analyseSimilarity(const std::string& labs_root, const std::vector<std::string>& lab_ids,
                                   const std::vector<SubmissionFolder>& submissions,
                                   const SimilarityOptions& options = {});

// pairs.json (the format is in docs/instructors.md, "Who copied").
std::string similarityToJson(const SimilarityReport& report);

// Writes <out_dir>/pairs.json, <out_dir>/index.html and, for flagged pairs (at most
// `max_views_per_lab` per lab, highest scores first), the side-by-side pages
// <out_dir>/pairs/<lab>/<n>.html. Files are written atomically; false with the reason otherwise.
bool writeSimilarityReport(const SimilarityReport& report, const std::string& out_dir, std::string* error,
                           std::size_t max_views_per_lab = 200);

}  // namespace shaderlab::similarity
