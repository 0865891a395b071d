// k-gram hashes and robust winnowing; see winnowing.h.
#include "shaderlab/similarity/winnowing.h"

#include <xxhash.h>

#include <deque>

namespace shaderlab::similarity {

std::vector<std::uint64_t> kgramHashes(const std::vector<std::uint64_t>& tokens, std::size_t k) {
    std::vector<std::uint64_t> out;
    if (k == 0 || tokens.size() < k) return out;
    out.reserve(tokens.size() - k + 1);
    // A k-gram's hash is XXH3 of its k token hashes: no rolling hash is needed at these sizes
    // (a lab's student files are some thousand tokens), and XXH3 mixes better than Karp-Rabin.
    for (std::size_t i = 0; i + k <= tokens.size(); ++i)
        out.push_back(XXH3_64bits(tokens.data() + i, k * sizeof(std::uint64_t)));
    return out;
}

std::vector<Fingerprint> winnow(const std::vector<std::uint64_t>& hashes, std::size_t w) {
    std::vector<Fingerprint> out;
    if (hashes.empty()) return out;
    if (w == 0) w = 1;
    // The candidates for the minimum of the current window, their hashes increasing from front
    // to back; a newer hash that is not larger removes older ones, so ties go to the rightmost.
    std::deque<std::size_t> candidates;
    std::size_t last = hashes.size();  // the position recorded last (none yet)
    auto record = [&](std::size_t p) {
        if (p != last) out.push_back(Fingerprint{hashes[p], static_cast<std::uint32_t>(p)});
        last = p;
    };
    for (std::size_t i = 0; i < hashes.size(); ++i) {
        while (!candidates.empty() && hashes[candidates.back()] >= hashes[i]) candidates.pop_back();
        candidates.push_back(i);
        if (candidates.front() + w <= i) candidates.pop_front();
        if (i + 1 >= w) record(candidates.front());
    }
    if (hashes.size() < w) record(candidates.front());
    return out;
}

}  // namespace shaderlab::similarity
