// Document fingerprints by winnowing: Schleimer, Wilkerson and Aiken, "Winnowing: local
// algorithms for document fingerprinting", SIGMOD 2003 (the algorithm behind MOSS).
//
// A document is a sequence of token hashes. Every run of k consecutive tokens (a k-gram) gets a
// hash; of every window of w consecutive k-gram hashes the smallest is kept (the rightmost of
// equal ones), each kept position once. The paper's two guarantees follow: a match shorter than
// the noise threshold k can never give a fingerprint, and any match of at least t = w + k - 1
// tokens shares at least one fingerprint, since its k-grams then fill a whole window, and both
// documents keep that window's minimum. About 2 / (w + 1) of the k-grams are kept.
//
// Does not: know about files, lines or what the tokens were; that is the caller's (documents.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace shaderlab::similarity {

struct Fingerprint {
    std::uint64_t hash = 0;
    std::uint32_t position = 0;  // index of the k-gram's first token

    bool operator==(const Fingerprint& o) const { return hash == o.hash && position == o.position; }
};

// The hash of every k-gram of `tokens` (tokens.size() - k + 1 of them; none when shorter than k).
std::vector<std::uint64_t> kgramHashes(const std::vector<std::uint64_t>& tokens, std::size_t k);

// Winnowing of `hashes` with window `w` (>= 1): in each window the minimum, the rightmost of equal
// ones, recorded once however many windows select it. A sequence shorter than one window is one
// window. Positions index `hashes`, in increasing order.
std::vector<Fingerprint> winnow(const std::vector<std::uint64_t>& hashes, std::size_t w);

}  // namespace shaderlab::similarity
