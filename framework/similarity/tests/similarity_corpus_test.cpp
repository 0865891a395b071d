// The report on the course's own solutions: disguised copies are flagged, the corpus's alternative
// solutions are not (but for the few written as an edit of the reference), and starter code alone
// is never flagged. These runs justify the defaults of SimilarityOptions.
#include <gtest/gtest.h>

#include <cstdio>
#include <set>

#include "shaderlab/similarity/similarity.h"
#include "similarity_test_support.h"

namespace shaderlab::similarity {
namespace {

using namespace similarity_testing;

// Alternatives of tests/corpus that are the reference with a line or a function changed, the rest
// of the student's code kept word for word: flagging them against the reference is right.
// (Others are edits too, but change enough to stay under the threshold: 10-particles'
// arithmetic-reordered scores 0.74.)
const std::set<std::string> kEditsOfTheReference = {
    // pattern.frag: only `vec2 w = fwidth(p)` written out as the gradient's length
    "09-procedural-antialiasing/gradient-length",
    // all four files are the reference's, but for the light-space position passed from lit.vert
    "11-shadow-mapping/light-space-in-vertex-shader",
};

// Edits of the reference too short to call a copy: the bar rises for short documents (similarity.h,
// flagBar), since two short solutions written apart to one template share as much (the Blinn-Phong
// pair of tests/planted_class: 21 of 27). They stay listed, for reading, but are not flagged.
const std::set<std::string> kShortEditsUnderTheBar = {
    // pattern.frag: only the stripes' integral, as a triangle wave (15 of 18 shared; bar 0.87)
    "09-procedural-antialiasing/triangle-wave",
    // particles.vert and step.frag: texelFetch swapped for texture lookups (22 of 28; bar 0.84)
    "10-particles/texture-at-texel-centres",
};

// Edits of the reference whose own work, once the starter is masked, holds fewer than min_shared
// fingerprints: never flagged, nor listed (a starter of one function per idea leaves a few lines).
const std::set<std::string> kEditsTooShortToList = {
    // pattern.frag's stripeMask: v_uv swapped for gl_FragCoord.xy / u_resolution in one line
    "04-render-to-texture/alt-fragcoord-pattern",
};

// Alternatives of one lab written from one file, not apart: their shared code is one author's.
const std::set<std::pair<std::string, std::string>> kAlternativesOfOneHand = {
    // 08-gooch: neighbours-unrolled's gooch.frag is view-space's with world space put back
    // (goochTone and whiteHighlight as written there)
    {"08-gooch/neighbours-unrolled", "08-gooch/view-space"},
};

bool editOfTheReference(const std::string& lab, const std::string& name) {
    const std::string id = lab + "/" + name;
    return kEditsOfTheReference.count(id) + kShortEditsUnderTheBar.count(id) +
               kEditsTooShortToList.count(id) >
           0;
}

const PairResult* findPair(const SimilarityReport& r, const std::string& lab, const std::string& x,
                           const std::string& y) {
    for (const PairResult& p : r.pairs)
        if (p.lab == lab &&
            ((p.a.student == x && p.b.student == y) || (p.a.student == y && p.b.student == x)))
            return &p;
    return nullptr;
}

double scoreOf(const PairResult* p) { return p ? p->score : 0.0; }

std::string describe(const PairResult* p) {
    if (!p) return "nothing (not listed)";
    return std::to_string(p->score) + " (" + std::to_string(p->shared) + " shared of " +
           std::to_string(p->a_fingerprints) + " and " + std::to_string(p->b_fingerprints) + ")";
}

// One class: the reference of every lab, each corpus alternative (its own files, the starter for
// the rest), and a disguised copy of each. The common-idiom filter needs a class of strangers to
// be fair; here most documents descend from one reference, so it is off and each pair stands alone.
struct CorpusClass {
    std::vector<SubmissionFolder> submissions;
    std::vector<std::pair<std::string, std::string>> alternatives;  // lab, case
};

CorpusClass buildCorpusClass(const fs::path& root) {
    CorpusClass c;
    auto add = [&](const std::string& student) {
        c.submissions.push_back(SubmissionFolder{student, (root / student).string(), ""});
    };
    for (const std::string& lab : labIds()) {
        const fs::path reference = kSource / "reference_solutions" / lab, starter = fs::path(kLabs) / lab;
        placeLab(root / "reference", lab, {reference});
        placeLab(root / "copy-of-reference", lab, {reference}, disguise);
        for (const std::string& name : corpusCases(lab, "alternative")) {
            const fs::path own = kSource / "tests/corpus" / lab / name;
            placeLab(root / ("alt-" + name), lab, {own, starter});
            placeLab(root / ("copy-of-alt-" + name), lab, {own, starter}, disguise);
            c.alternatives.emplace_back(lab, name);
        }
    }
    add("reference");
    add("copy-of-reference");
    for (const auto& [lab, name] : c.alternatives) {
        add("alt-" + name);
        add("copy-of-alt-" + name);
    }
    return c;
}

TEST(SimilarityCorpus, CopiesAreFlaggedAlternativesAreNot) {
    const fs::path root = scratch("corpus");
    const CorpusClass c = buildCorpusClass(root);
    SimilarityOptions options;
    options.common_min_documents = 1000;
    const SimilarityReport report = analyseSimilarity(kLabs, labIds(), c.submissions, options);
    EXPECT_TRUE(report.notes.empty()) << report.notes.front();

    int copies = 0, copies_flagged = 0, too_small = 0;
    double lowest_copy = 1.0;
    for (const std::string& lab : labIds()) {
        const PairResult* p = findPair(report, lab, "reference", "copy-of-reference");
        // A lab whose work is a few of the README's formulas leaves the reference too few
        // fingerprints of its own to call anything a copy of it; the page says so.
        const auto stats = std::find_if(report.labs.begin(), report.labs.end(),
                                        [&](const LabStats& s) { return s.lab == lab; });
        if (!p && stats != report.labs.end() && stats->short_documents >= 2) {
            ++too_small;
            continue;
        }
        ASSERT_NE(p, nullptr) << lab << ": the reference's disguised copy is not even listed";
        EXPECT_TRUE(p->flagged) << lab << ": the reference's copy scores " << p->score;
        ++copies;
        copies_flagged += p && p->flagged;
        lowest_copy = std::min(lowest_copy, scoreOf(p));
    }
    for (const auto& [lab, name] : c.alternatives) {
        const PairResult* p = findPair(report, lab, "alt-" + name, "copy-of-alt-" + name);
        // An alternative that changes a few lines leaves too little of its own to call a copy of.
        if (!p && report.pairs.end() ==
                      std::find_if(report.pairs.begin(), report.pairs.end(), [&](const PairResult& q) {
                          return q.lab == lab &&
                                 (q.a.student == "alt-" + name || q.b.student == "alt-" + name);
                      })) {
            ++too_small;
            continue;
        }
        ++copies;
        copies_flagged += p && p->flagged;
        EXPECT_TRUE(p && p->flagged) << lab << "/" << name << ": its disguised copy scores " << describe(p);
        lowest_copy = std::min(lowest_copy, scoreOf(p));
    }

    int independent = 0, independent_flagged = 0, edits_flagged = 0;
    double highest_independent = 0.0;
    for (const auto& [lab, name] : c.alternatives) {
        const PairResult* p = findPair(report, lab, "reference", "alt-" + name);
        if (kEditsTooShortToList.count(lab + "/" + name)) {
            EXPECT_EQ(p, nullptr) << lab << "/" << name << " against the reference scores " << describe(p);
            continue;
        }
        if (kShortEditsUnderTheBar.count(lab + "/" + name)) {
            EXPECT_TRUE(p && !p->flagged && p->score >= report.options.list_from)
                << lab << "/" << name << " against the reference scores " << describe(p);
            continue;
        }
        const bool edit = kEditsOfTheReference.count(lab + "/" + name) != 0;
        EXPECT_EQ(p && p->flagged, edit)
            << lab << "/" << name << " against the reference scores " << describe(p)
            << (edit ? " (an edit of the reference: expected flagged)" : "");
        if (edit) {
            edits_flagged += p && p->flagged;
            continue;
        }
        ++independent;
        independent_flagged += p && p->flagged;
        highest_independent = std::max(highest_independent, scoreOf(p));
    }
    // Two alternatives of a lab are written apart unless both are edits of the reference.
    int alt_pairs = 0, alt_pairs_flagged = 0;
    for (const auto& [lab, x] : c.alternatives)
        for (const auto& [lab2, y] : c.alternatives) {
            if (lab != lab2 || x >= y) continue;
            const PairResult* p = findPair(report, lab, "alt-" + x, "alt-" + y);
            if (editOfTheReference(lab, x) && editOfTheReference(lab, y)) continue;
            if (kAlternativesOfOneHand.count({lab + "/" + x, lab + "/" + y})) continue;
            ++alt_pairs;
            alt_pairs_flagged += p && p->flagged;
            EXPECT_FALSE(p && p->flagged) << lab << ": " << x << " and " << y << " score " << describe(p);
            highest_independent = std::max(highest_independent, scoreOf(p));
        }
    std::printf(
        "copies flagged: %d of %d (lowest score %.2f; %d references or alternatives too small to judge)\n",
        copies_flagged, copies, lowest_copy, too_small);
    std::printf(
        "independent pairs flagged: %d of %d against the reference, %d of %d between alternatives "
        "(highest score %.2f); edits of the reference flagged: %d of %zu\n",
        independent_flagged, independent, alt_pairs_flagged, alt_pairs, highest_independent, edits_flagged,
        kEditsOfTheReference.size());
}

TEST(SimilarityCorpus, StarterCodeAloneIsNeverFlagged) {
    const fs::path root = scratch("starter");
    for (const std::string& lab : labIds()) {
        placeLab(root / "starter-only", lab, {fs::path(kLabs) / lab});
        placeLab(root / "starter-disguised", lab, {fs::path(kLabs) / lab}, disguise);
        placeLab(root / "reference", lab, {kSource / "reference_solutions" / lab});
    }
    std::vector<SubmissionFolder> subs;
    for (const char* s : {"starter-only", "starter-disguised", "reference"})
        subs.push_back(SubmissionFolder{s, (root / s).string(), ""});
    const SimilarityReport report = analyseSimilarity(kLabs, labIds(), subs);
    for (const PairResult& p : report.pairs)
        EXPECT_FALSE(p.flagged) << p.lab << ": " << p.a.student << " and " << p.b.student << " score "
                                << p.score;
    for (const LabStats& s : report.labs) {
        EXPECT_EQ(s.documents, 3u) << s.lab;
        // Both starter copies keep nothing of their own; the reference does.
        EXPECT_EQ(s.empty_documents, 2u) << s.lab;
    }
}

}  // namespace
}  // namespace shaderlab::similarity
