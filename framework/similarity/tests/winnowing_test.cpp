// Winnowing: the paper's guarantees on synthetic sequences (Schleimer, Wilkerson and Aiken 2003).
#include "shaderlab/similarity/winnowing.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

namespace shaderlab::similarity {
namespace {

std::set<std::uint64_t> hashesOf(const std::vector<std::uint64_t>& tokens, std::size_t k, std::size_t w) {
    std::set<std::uint64_t> out;
    for (const Fingerprint& f : winnow(kgramHashes(tokens, k), w)) out.insert(f.hash);
    return out;
}

std::vector<std::uint64_t> randomTokens(std::mt19937_64& rng, std::size_t n) {
    std::vector<std::uint64_t> out(n);
    for (std::uint64_t& t : out) t = rng() % 40;  // a small alphabet, as normalised GLSL has
    return out;
}

bool share(const std::set<std::uint64_t>& a, const std::set<std::uint64_t>& b) {
    return std::any_of(a.begin(), a.end(), [&](std::uint64_t h) { return b.count(h) != 0; });
}

// Any common run of w + k - 1 tokens, anywhere in two otherwise unrelated sequences, shares a
// fingerprint; runs shorter than k never do.
TEST(Winnowing, EveryRunOfWPlusKMinusOneTokensIsFound) {
    std::mt19937_64 rng(2003);
    for (const auto& [k, w] :
         std::vector<std::pair<std::size_t, std::size_t>>{{12, 6}, {5, 4}, {15, 1}, {3, 20}}) {
        int found_shorter = 0;
        for (int trial = 0; trial < 400; ++trial) {
            const std::size_t t = w + k - 1;
            const std::vector<std::uint64_t> run = randomTokens(rng, t);
            std::vector<std::uint64_t> a = randomTokens(rng, 50 + rng() % 200);
            std::vector<std::uint64_t> b = randomTokens(rng, 50 + rng() % 200);
            for (std::uint64_t& x : b) x += 1000;  // nothing shared but the run
            a.insert(a.begin() + rng() % a.size(), run.begin(), run.end());
            b.insert(b.begin() + rng() % b.size(), run.begin(), run.end());
            ASSERT_TRUE(share(hashesOf(a, k, w), hashesOf(b, k, w)))
                << "k " << k << " w " << w << " trial " << trial;

            std::vector<std::uint64_t> c = randomTokens(rng, 100), d = randomTokens(rng, 100);
            for (std::uint64_t& x : d) x += 1000;
            c.insert(c.begin() + 50, run.begin(), run.begin() + (k - 1));
            d.insert(d.begin() + 50, run.begin(), run.begin() + (k - 1));
            EXPECT_FALSE(share(hashesOf(c, k, w), hashesOf(d, k, w))) << "a run of k - 1 tokens matched";
            // A run a little shorter than t is not always found: the guarantee is tight.
            std::vector<std::uint64_t> e = randomTokens(rng, 100), f = randomTokens(rng, 100);
            for (std::uint64_t& x : f) x += 1000;
            e.insert(e.begin() + 50, run.begin(), run.begin() + k);
            f.insert(f.begin() + 50, run.begin(), run.begin() + k);
            found_shorter += share(hashesOf(e, k, w), hashesOf(f, k, w));
        }
        if (w > 1) {
            EXPECT_LT(found_shorter, 400) << "k " << k << " w " << w;
        }
    }
}

TEST(Winnowing, EachFingerprintIsItsWindowsMinimumAndDensityIsAboutTwoOverWPlusOne) {
    std::mt19937_64 rng(11);
    std::vector<std::uint64_t> hashes(200000);
    for (std::uint64_t& h : hashes) h = rng();
    const std::size_t w = 6;
    const std::vector<Fingerprint> fps = winnow(hashes, w);
    for (std::size_t i = 1; i < fps.size(); ++i) ASSERT_LT(fps[i - 1].position, fps[i].position);
    // Every window holds a fingerprint, and it is that window's (rightmost) minimum.
    std::size_t f = 0;
    for (std::size_t start = 0; start + w <= hashes.size(); ++start) {
        std::size_t min_at = start;
        for (std::size_t j = start; j < start + w; ++j)
            if (hashes[j] <= hashes[min_at]) min_at = j;
        while (f < fps.size() && fps[f].position < min_at) ++f;
        ASSERT_LT(f, fps.size());
        ASSERT_EQ(fps[f].position, min_at) << "window at " << start;
        ASSERT_EQ(fps[f].hash, hashes[min_at]);
    }
    const double density = double(fps.size()) / double(hashes.size());
    std::printf("winnowing density at w = %zu: %.4f (2 / (w + 1) = %.4f)\n", w, density, 2.0 / (w + 1));
    EXPECT_NEAR(density, 2.0 / (w + 1), 0.01);
}

TEST(Winnowing, ShortSequences) {
    EXPECT_TRUE(winnow({}, 4).empty());
    const std::vector<Fingerprint> one = winnow({9, 3, 7}, 4);  // shorter than a window: one window
    ASSERT_EQ(one.size(), 1u);
    EXPECT_EQ(one[0], (Fingerprint{3, 1}));
    EXPECT_TRUE(kgramHashes({1, 2, 3}, 4).empty());
    EXPECT_EQ(kgramHashes({1, 2, 3, 4}, 4).size(), 1u);
    // Equal hashes: the rightmost of a window, each position once.
    const std::vector<Fingerprint> ties = winnow({5, 5, 5, 5}, 2);
    ASSERT_EQ(ties.size(), 3u);
    EXPECT_EQ(ties.back().position, 3u);
}

}  // namespace
}  // namespace shaderlab::similarity
