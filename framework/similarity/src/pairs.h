// Per lab: the inverted index from fingerprint to documents, the pairs it gives, their matched
// regions and the clusters of flagged pairs. Private to the library.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "documents.h"

namespace shaderlab::similarity::detail {

struct LabResult {
    LabStats stats;
    std::vector<PairResult> pairs;
    std::vector<Cluster> clusters;
    std::vector<std::string> notes;
    std::map<std::string, std::vector<SourceFile>> sources;
};

// Fills the stats, pairs and clusters of `out` from the lab's documents.
void comparePairs(const std::string& lab, const std::vector<Document>& docs, const SimilarityOptions& options,
                  LabResult* out);

}  // namespace shaderlab::similarity::detail
