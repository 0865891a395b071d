// Message helpers for JSON documents; see json_messages.h.
#include "shaderlab/base/json_messages.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <sstream>

namespace shaderlab {

namespace {

constexpr std::size_t kMaxQuotedChars = 60;

std::string lowercase(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 0; i < a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i + 1;
        for (std::size_t j = 0; j < b.size(); ++j) {
            const std::size_t above = row[j + 1];
            row[j + 1] = std::min({above + 1, row[j] + 1, diagonal + (a[i] == b[j] ? 0 : 1)});
            diagonal = above;
        }
    }
    return row[b.size()];
}

}  // namespace

std::string quoteJson(const std::string& s) {
    std::string q = nlohmann::json(s).dump(-1, ' ', true, nlohmann::json::error_handler_t::replace);
    if (q.size() > kMaxQuotedChars) q = q.substr(0, kMaxQuotedChars - 4) + "...\"";
    return q;
}

std::string formatNumber(double d) {
    // Integers in full ("4194304", not "4.1943e+06"), other values to six significant digits.
    if (std::isfinite(d) && std::floor(d) == d && std::fabs(d) < 1e15)
        return std::to_string(static_cast<long long>(d));
    std::ostringstream s;
    s << d;
    return s.str();
}

std::string describeJson(const nlohmann::json& v) {
    using T = nlohmann::json::value_t;
    switch (v.type()) {
        case T::null:
            return "null";
        case T::boolean:
            return v.get<bool>() ? "true" : "false";
        case T::string:
            return quoteJson(v.get<std::string>());
        case T::array:
            if (v.empty()) return "an empty array";
            return "an array of " + std::to_string(v.size()) + (v.size() == 1 ? " element" : " elements");
        case T::object:
            return v.empty() ? "an empty object" : "an object";
        default:
            return v.is_number() ? v.dump() : "an unsupported value";
    }
}

bool isPlainName(const std::string& s) {
    if (s.empty()) return false;
    return std::all_of(s.begin(), s.end(),
                       [](unsigned char c) { return std::isalnum(c) || c == '_' || c == '-'; });
}

std::string joinKey(const std::string& parent, const std::string& key) {
    // Keys that are not plain names are shown quoted so the path stays unambiguous.
    if (!isPlainName(key)) return parent + "[" + quoteJson(key) + "]";
    return parent.empty() ? key : parent + "." + key;
}

std::string joinIndex(const std::string& parent, std::size_t i) {
    return parent + "[" + std::to_string(i) + "]";
}

std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates) {
    const std::string w = lowercase(word);
    const std::size_t allowed = std::max<std::size_t>(1, w.size() / 4 + 1);
    std::string best;
    std::size_t best_distance = std::numeric_limits<std::size_t>::max();
    for (const std::string& candidate : candidates) {
        const std::string c = lowercase(candidate);
        std::size_t d = editDistance(w, c);
        const bool prefix = std::min(w.size(), c.size()) >= 3 && (c.rfind(w, 0) == 0 || w.rfind(c, 0) == 0);
        if (d > allowed && !prefix) continue;
        if (prefix) d = std::min(d, allowed);
        if (d < best_distance) {
            best = candidate;
            best_distance = d;
        }
    }
    return best;
}

std::string didYouMean(const std::string& word, const std::vector<std::string>& candidates) {
    const std::string match = closestMatch(word, candidates);
    return match.empty() ? "" : " (did you mean " + quoteJson(match) + "?)";
}

}  // namespace shaderlab
