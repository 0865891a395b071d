// Shared by the report writers (report_json.cpp, report_html.cpp). Private to the library.
#pragma once

#include <string>
#include <vector>

#include "shaderlab/similarity/similarity.h"

namespace shaderlab::similarity::detail {

// pairs.json, with each pair's side-by-side page (relative to the report folder; "" for none).
std::string pairsJson(const SimilarityReport& report, const std::vector<std::string>& views);

// index.html.
std::string indexHtml(const SimilarityReport& report, const std::vector<std::string>& views);

// The side-by-side page of pair `index`.
std::string pairHtml(const SimilarityReport& report, std::size_t index);

std::string htmlEscape(const std::string& s);

}  // namespace shaderlab::similarity::detail
