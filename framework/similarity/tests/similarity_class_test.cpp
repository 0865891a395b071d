// The report over a class: hostile files, earlier classes, clusters, common idioms, the files
// it writes.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "shaderlab/similarity/similarity.h"
#include "similarity_test_support.h"

namespace shaderlab::similarity {
namespace {

using namespace similarity_testing;

const std::string kPhong = "01-phong";

fs::path reference(const std::string& lab) { return kSource / "reference_solutions" / lab; }

SubmissionFolder student(const fs::path& root, const std::string& name, const std::string& cohort = "") {
    return SubmissionFolder{name, (root / name).string(), cohort};
}

bool anyNoteHas(const SimilarityReport& r, const std::string& a, const std::string& b) {
    for (const std::string& n : r.notes)
        if (n.find(a) != std::string::npos && n.find(b) != std::string::npos) return true;
    return false;
}

TEST(SimilarityClass, SymlinksOutOfASubmissionAreRefused) {
    const fs::path root = scratch("symlink"), outside = scratch("symlink_outside");
    placeLab(root / "alice", kPhong, {reference(kPhong)});
    placeLab(outside / "stolen", kPhong, {reference(kPhong)});
    // mallory's fragment shader is a link to alice's work outside mallory's folder; eve's whole
    // lab folder is.
    placeLab(root / "mallory", kPhong, {fs::path(kLabs) / kPhong});
    fs::remove(root / "mallory" / kPhong / "phong.frag");
    fs::create_symlink(outside / "stolen" / kPhong / "phong.frag", root / "mallory" / kPhong / "phong.frag");
    fs::create_directories(root / "eve");
    fs::create_directory_symlink(outside / "stolen" / kPhong, root / "eve" / kPhong);
    const SimilarityReport r = analyseSimilarity(
        kLabs, {kPhong}, {student(root, "alice"), student(root, "mallory"), student(root, "eve")});
    EXPECT_TRUE(anyNoteHas(r, "mallory", "01-phong/phong.frag left out"))
        << ::testing::PrintToString(r.notes);
    EXPECT_TRUE(anyNoteHas(r, "eve", "01-phong/phong.vert left out")) << ::testing::PrintToString(r.notes);
    EXPECT_TRUE(anyNoteHas(r, "eve", "outside")) << ::testing::PrintToString(r.notes);
    for (const PairResult& p : r.pairs) EXPECT_FALSE(p.flagged) << p.a.student << " " << p.b.student;
}

TEST(SimilarityClass, BinaryAndHugeFilesGetANoteNotACrash) {
    const fs::path root = scratch("junk");
    placeLab(root / "alice", kPhong, {reference(kPhong)});
    placeLab(root / "bob", kPhong, {reference(kPhong)});
    std::string binary = readText(reference(kPhong) / "phong.frag");
    binary[100] = '\0';
    writeText(root / "bob" / kPhong / "phong.frag", binary);
    placeLab(root / "carol", kPhong, {reference(kPhong)});
    writeText(root / "carol" / kPhong / "phong.frag", std::string(300 << 10, 'x'));
    fs::create_directories(root / "dan" / kPhong / "phong.frag");  // a folder where a file should be
    const SimilarityReport r = analyseSimilarity(
        kLabs, {kPhong},
        {student(root, "alice"), student(root, "bob"), student(root, "carol"), student(root, "dan")});
    EXPECT_TRUE(anyNoteHas(r, "bob: 01-phong/phong.frag", "binary")) << ::testing::PrintToString(r.notes);
    EXPECT_TRUE(anyNoteHas(r, "carol: 01-phong/phong.frag", "limit")) << ::testing::PrintToString(r.notes);
    EXPECT_TRUE(anyNoteHas(r, "dan: 01-phong/phong.frag", "not a regular file"))
        << ::testing::PrintToString(r.notes);
}

TEST(SimilarityClass, EarlierClassesAreCandidatesOnly) {
    const std::string lab = "02-toon";
    const fs::path root = scratch("earlier");
    placeLab(root / "now" / "dan", lab, {reference(lab)}, disguise);
    placeLab(root / "2023" / "erin", lab, {reference(lab)});
    placeLab(root / "2023" / "fay", lab, {reference(lab)});
    const SimilarityReport r =
        analyseSimilarity(kLabs, {lab},
                          {student(root / "now", "dan"), student(root / "2023", "erin", "2023"),
                           student(root / "2023", "fay", "2023")});
    ASSERT_EQ(r.pairs.size(), 2u);  // erin and fay, both of 2023, are not compared
    for (const PairResult& p : r.pairs) {
        EXPECT_TRUE(p.flagged);
        EXPECT_EQ(p.a, (StudentRef{"dan", ""}));
        EXPECT_EQ(p.b.cohort, "2023");
    }
}

TEST(SimilarityClass, ClustersJoinFlaggedPairs) {
    const std::string lab = "06-bloom";
    const fs::path root = scratch("clusters");
    for (const char* s : {"x", "y", "z"}) placeLab(root / s, lab, {reference(lab)}, disguise);
    placeLab(root / "w", lab, {kSource / "tests/corpus" / lab / "blur-unrolled", fs::path(kLabs) / lab});
    const SimilarityReport r = analyseSimilarity(
        kLabs, {lab}, {student(root, "w"), student(root, "x"), student(root, "y"), student(root, "z")});
    ASSERT_EQ(r.clusters.size(), 1u);
    EXPECT_EQ(r.clusters[0].students, (std::vector<StudentRef>{{"x", ""}, {"y", ""}, {"z", ""}}));
    EXPECT_EQ(r.labs[0].pairs_flagged, 3u);
    EXPECT_EQ(r.labs[0].clusters, 1u);
}

// Two Blinn-Phong solutions written apart to the starter's template (tests/planted_class/blinn-a,
// blinn-b) are not flagged, at the bar for short documents nor at the old flat bar of 0.75 (on the
// starter of one function per idea, what the two share is masked as the starter's). A disguised
// copy of one of them is flagged, and a cluster it makes does not reach the other.
TEST(SimilarityClass, ShortSolutionsToOneTemplateAreNoCopyAndClustersDoNotChain) {
    const fs::path root = scratch("template");
    const fs::path planted = kSource / "tests/planted_class";
    placeLab(root / "quinn", kPhong, {planted / "blinn-a", reference(kPhong)});
    placeLab(root / "rosa", kPhong, {planted / "blinn-b", reference(kPhong)});
    placeLab(root / "nina", kPhong, {planted / "blinn-a", reference(kPhong)}, disguise);
    const std::vector<SubmissionFolder> subs = {student(root, "nina"), student(root, "quinn"),
                                                student(root, "rosa")};
    const auto pair = [](const SimilarityReport& r, const std::string& x, const std::string& y) {
        for (const PairResult& p : r.pairs)
            if ((p.a.student == x && p.b.student == y) || (p.a.student == y && p.b.student == x)) return p;
        return PairResult{};
    };
    SimilarityOptions old_bar;
    old_bar.length_margin = 0.0;
    const SimilarityReport before = analyseSimilarity(kLabs, {kPhong}, subs, old_bar);
    const PairResult apart_before = pair(before, "quinn", "rosa");
    EXPECT_FALSE(apart_before.flagged) << apart_before.score << " against a bar of " << apart_before.bar;
    // Even at the old bar, the cluster is the copy and its source only.
    ASSERT_EQ(before.clusters.size(), 1u);
    EXPECT_EQ(before.clusters[0].students, (std::vector<StudentRef>{{"nina", ""}, {"quinn", ""}}));

    const SimilarityReport r = analyseSimilarity(kLabs, {kPhong}, subs);
    const PairResult apart = pair(r, "quinn", "rosa");
    EXPECT_FALSE(apart.flagged) << apart.score << " against a bar of " << apart.bar;
    // Listed or not, the pair is said to be under the bar.
    if (!apart.a.student.empty()) {
        EXPECT_EQ(pairVerdict(apart, r.options).rfind("not flagged: ", 0), 0u)
            << pairVerdict(apart, r.options);
    }
    const PairResult copy = pair(r, "nina", "quinn");
    EXPECT_TRUE(copy.flagged) << copy.score << " against a bar of " << copy.bar;
    EXPECT_EQ(pairVerdict(copy, r.options).rfind("flagged: shares ", 0), 0u) << pairVerdict(copy, r.options);
    EXPECT_FALSE(pair(r, "nina", "rosa").flagged);
    // A cluster, where the copy is strong enough to make one, is the copy and its source only.
    ASSERT_LE(r.clusters.size(), 1u);
    EXPECT_EQ(r.clusters.empty(), !copy.strong);
    if (!r.clusters.empty()) {
        EXPECT_EQ(r.clusters[0].students, (std::vector<StudentRef>{{"nina", ""}, {"quinn", ""}}));
    }
}

TEST(SimilarityClass, TheBarRisesForShortDocuments) {
    SimilarityOptions o;
    EXPECT_DOUBLE_EQ(flagBar(o, 100), 0.80);
    EXPECT_DOUBLE_EQ(flagBar(o, 400), 0.775);
    EXPECT_NEAR(flagBar(o, 26), 0.848, 1e-3);
    EXPECT_DOUBLE_EQ(flagBar(o, 0), 1.0);  // capped: nothing of one's own is never a copy by share
    o.length_margin = 0.0;
    EXPECT_DOUBLE_EQ(flagBar(o, 26), 0.75);
}

TEST(SimilarityClass, FingerprintsInTooManyDocumentsAreCommonIdioms) {
    const fs::path root = scratch("common");
    std::vector<SubmissionFolder> subs;
    for (int i = 0; i < 12; ++i) {
        const std::string name = "s" + std::to_string(i);
        placeLab(root / name, kPhong, {reference(kPhong)});
        subs.push_back(student(root, name));
    }
    SimilarityOptions options;
    options.common_min_documents = 11;  // what 12 documents share is an idiom
    SimilarityReport r = analyseSimilarity(kLabs, {kPhong}, subs, options);
    EXPECT_TRUE(r.pairs.empty());
    EXPECT_GT(r.labs[0].common_fingerprints, 0u);
    options.common_min_documents = 12;
    r = analyseSimilarity(kLabs, {kPhong}, subs, options);
    EXPECT_EQ(r.labs[0].pairs_flagged, 12u * 11u / 2u);
    EXPECT_EQ(r.labs[0].common_fingerprints, 0u);
}

TEST(SimilarityClass, WritesPairsJsonIndexAndSideBySidePages) {
    const fs::path root = scratch("report"), out = scratch("report_out");
    placeLab(root / "<b>alice</b>", kPhong, {reference(kPhong)});
    placeLab(root / "bob", kPhong, {reference(kPhong)}, disguise);
    const SimilarityReport r =
        analyseSimilarity(kLabs, {kPhong}, {student(root, "<b>alice</b>"), student(root, "bob")});
    std::string error;
    ASSERT_TRUE(writeSimilarityReport(r, out.string(), &error)) << error;

    const nlohmann::json j = nlohmann::json::parse(readText(out / "pairs.json"));
    ASSERT_EQ(j.at("pairs").size(), 1u);
    const nlohmann::json& p = j.at("pairs")[0];
    EXPECT_EQ(p.at("lab"), kPhong);
    EXPECT_EQ(p.at("a").at("student"), "<b>alice</b>");
    EXPECT_TRUE(p.at("a").at("cohort").is_null());
    EXPECT_TRUE(p.at("flagged").get<bool>());
    EXPECT_GE(p.at("score").get<double>(), 0.75);
    EXPECT_LE(p.at("score").get<double>(), 1.0);
    ASSERT_FALSE(p.at("regions").empty());
    const nlohmann::json& region = p.at("regions")[0];
    EXPECT_EQ(region.at("a").at("file").get<std::string>().rfind("01-phong/", 0), 0u);
    EXPECT_LE(region.at("a").at("first_line").get<int>(), region.at("a").at("last_line").get<int>());
    EXPECT_EQ(j.at("clusters").size(), 1u);
    EXPECT_EQ(j.at("method").at("k"), 12);

    const std::string index = readText(out / "index.html");
    EXPECT_NE(index.find("&lt;b&gt;alice&lt;/b&gt;"), std::string::npos);
    EXPECT_EQ(index.find("<b>alice"), std::string::npos);
    const std::string view = p.at("view").get<std::string>();
    EXPECT_EQ(view, "pairs/01-phong/0.html");
    const std::string page = readText(out / view);
    EXPECT_NE(page.find("class=\"l r0\""), std::string::npos);    // matched lines are marked
    EXPECT_NE(page.find("u_light_position"), std::string::npos);  // both students' source is shown
}

}  // namespace
}  // namespace shaderlab::similarity
