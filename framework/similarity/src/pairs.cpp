// The inverted index, pair scores, matched regions and clusters; see pairs.h and similarity.h.
#include "pairs.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>
#include <unordered_set>

namespace shaderlab::similarity::detail {

namespace {

using HashSet = std::unordered_set<std::uint64_t>;

// The first position of `hash` in `doc`, or -1.
long firstPosition(const Document& doc, std::uint64_t hash) {
    auto it =
        std::lower_bound(doc.by_hash.begin(), doc.by_hash.end(), std::make_pair(hash, std::uint32_t(0)));
    return it != doc.by_hash.end() && it->first == hash ? static_cast<long>(it->second) : -1;
}

LineRange lines(const Document& doc, std::size_t begin, std::size_t end) {
    const DocToken& first = doc.tokens[begin];
    return LineRange{doc.files[first.file].name, first.line, doc.tokens[end - 1].line};
}

// The passages `a` and `b` share, in a's order: each shared fingerprint of `a` (common ones left
// out) paired with the first occurrence in `b`, and neighbours merged while both sides go on in
// the same file, in order, with no more than a window of tokens and two lines between them.
std::vector<MatchRegion> matchRegions(const Document& a, const Document& b, const HashSet& common,
                                      std::size_t k, std::size_t w) {
    struct Open {
        std::size_t a_begin, a_end, b_begin, b_end, count;
    };
    std::vector<MatchRegion> out;
    bool open = false;
    Open cur{};
    auto close = [&]() {
        if (open)
            out.push_back(
                MatchRegion{lines(a, cur.a_begin, cur.a_end), lines(b, cur.b_begin, cur.b_end), cur.count});
        open = false;
    };
    for (const Fingerprint& f : a.fingerprints) {
        if (common.count(f.hash) != 0) continue;
        const long pb = firstPosition(b, f.hash);
        if (pb < 0) continue;
        const std::size_t pa = f.position, qb = static_cast<std::size_t>(pb);
        const bool continues = open && a.tokens[pa].file == a.tokens[cur.a_begin].file &&
                               b.tokens[qb].file == b.tokens[cur.b_begin].file && pa <= cur.a_end + w &&
                               qb >= cur.b_begin && qb <= cur.b_end + w &&
                               a.tokens[pa].line <= a.tokens[cur.a_end - 1].line + 2 &&
                               b.tokens[qb].line <= b.tokens[cur.b_end - 1].line + 2;
        if (continues) {
            cur.a_end = std::max(cur.a_end, pa + k);
            cur.b_end = std::max(cur.b_end, qb + k);
            ++cur.count;
        } else {
            close();
            cur = Open{pa, pa + k, qb, qb + k, 1};
            open = true;
        }
    }
    close();
    return out;
}

struct UnionFind {
    explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
    std::size_t find(std::size_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    }
    void unite(std::size_t x, std::size_t y) { parent[find(x)] = find(y); }
    std::vector<std::size_t> parent;
};

PairResult makePair(const std::string& lab, const std::vector<Document>& docs, std::size_t i, std::size_t j,
                    std::size_t shared, const std::vector<std::size_t>& own,
                    const SimilarityOptions& options) {
    // A current student first; otherwise by name.
    if (docs[j].current && (!docs[i].current || docs[j].who < docs[i].who)) std::swap(i, j);
    PairResult p;
    p.lab = lab;
    p.a = docs[i].who;
    p.b = docs[j].who;
    p.shared = shared;
    p.a_fingerprints = own[i];
    p.b_fingerprints = own[j];
    p.a_in_b = double(shared) / double(own[i]);
    p.b_in_a = double(shared) / double(own[j]);
    p.score = double(shared) / double(std::min(own[i], own[j]));
    p.bar = flagBar(options, std::min(own[i], own[j]));
    p.flagged = p.score >= p.bar && shared >= options.min_shared;
    p.strong = p.flagged && p.score >= (p.bar + 1.0) / 2.0;
    return p;
}

}  // namespace

void comparePairs(const std::string& lab, const std::vector<Document>& docs, const SimilarityOptions& options,
                  LabResult* out) {
    const std::size_t n = docs.size();
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> postings;
    for (std::uint32_t d = 0; d < n; ++d)
        for (const auto& entry : docs[d].by_hash) postings[entry.first].push_back(d);

    const std::size_t limit = std::max(options.common_min_documents,
                                       static_cast<std::size_t>(std::ceil(options.common_share * double(n))));
    HashSet common;
    for (const auto& [hash, list] : postings)
        if (list.size() > limit) common.insert(hash);
    std::vector<std::size_t> own(n);
    for (std::size_t d = 0; d < n; ++d) {
        own[d] = docs[d].by_hash.size();
        for (const auto& entry : docs[d].by_hash) own[d] -= common.count(entry.first);
    }

    // The shared fingerprints of every pair with any, from the postings alone: the work is the
    // sum over fingerprints of (documents holding it)^2, bounded by the common limit.
    std::unordered_map<std::uint64_t, std::uint32_t> shared;
    for (const auto& [hash, list] : postings) {
        if (list.size() < 2 || list.size() > limit) continue;
        for (std::size_t x = 0; x < list.size(); ++x)
            for (std::size_t y = x + 1; y < list.size(); ++y) {
                if (!docs[list[x]].current && !docs[list[y]].current) continue;
                ++shared[(std::uint64_t(list[x]) << 32) | list[y]];
            }
    }

    out->stats.lab = lab;
    out->stats.documents = n;
    out->stats.empty_documents =
        std::count_if(docs.begin(), docs.end(), [](const Document& d) { return d.fingerprints.empty(); });
    out->stats.short_documents = std::count_if(docs.begin(), docs.end(), [&](const Document& d) {
        return !d.fingerprints.empty() && d.fingerprints.size() < options.min_shared;
    });
    out->stats.fingerprints = postings.size();
    out->stats.common_fingerprints = common.size();
    out->stats.common_limit = limit;

    // Clusters join strong pairs only; the side-by-side view needs the files of every flagged one.
    UnionFind groups(n);
    std::vector<bool> in_strong(n, false), in_flagged(n, false);
    struct Strong {
        std::size_t i, j;
        double score;
    };
    std::vector<Strong> strong;
    std::vector<double> closest(n, 0.0);  // each document's best score
    for (const auto& [key, count] : shared) {
        const std::size_t i = key >> 32, j = key & 0xffffffffu;
        const double score = double(count) / double(std::max<std::size_t>(1, std::min(own[i], own[j])));
        closest[i] = std::max(closest[i], score);
        closest[j] = std::max(closest[j], score);
        if (count < options.min_shared) continue;
        PairResult p = makePair(lab, docs, i, j, count, own, options);
        if (!p.flagged && p.score < options.list_from) continue;
        const bool a_is_i = p.a == docs[i].who;
        p.regions = a_is_i ? matchRegions(docs[i], docs[j], common, options.k, options.w)
                           : matchRegions(docs[j], docs[i], common, options.k, options.w);
        if (p.flagged) in_flagged[i] = in_flagged[j] = true;
        if (p.strong) {
            groups.unite(i, j);
            in_strong[i] = in_strong[j] = true;
            strong.push_back(Strong{i, j, p.score});
        }
        out->pairs.push_back(std::move(p));
    }
    if (n > 0) {
        std::nth_element(closest.begin(), closest.begin() + n / 2, closest.end());
        out->stats.median_closest = closest[n / 2];
    }
    std::sort(out->pairs.begin(), out->pairs.end(), [](const PairResult& x, const PairResult& y) {
        if (x.flagged != y.flagged) return x.flagged;
        if (x.score != y.score) return x.score > y.score;
        return x.a == y.a ? x.b < y.b : x.a < y.a;
    });
    out->stats.pairs_listed = out->pairs.size();
    out->stats.pairs_flagged =
        std::count_if(out->pairs.begin(), out->pairs.end(), [](const PairResult& p) { return p.flagged; });

    std::map<std::size_t, Cluster> by_root;
    for (std::size_t d = 0; d < n; ++d) {
        if (in_flagged[d]) out->sources[sourceKey(lab, docs[d].who)] = docs[d].files;
        if (!in_strong[d]) continue;
        Cluster& c = by_root[groups.find(d)];
        c.lab = lab;
        c.students.push_back(docs[d].who);
    }
    for (const Strong& f : strong) {
        Cluster& c = by_root[groups.find(f.i)];
        c.max_score = std::max(c.max_score, f.score);
    }
    for (auto& [root, c] : by_root) {
        std::sort(c.students.begin(), c.students.end());
        out->clusters.push_back(std::move(c));
    }
    std::sort(out->clusters.begin(), out->clusters.end(), [](const Cluster& x, const Cluster& y) {
        return x.students.size() != y.students.size() ? x.students.size() > y.students.size()
                                                      : x.students < y.students;
    });
    out->stats.clusters = out->clusters.size();
}

}  // namespace shaderlab::similarity::detail
