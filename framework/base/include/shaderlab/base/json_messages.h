// Small helpers for messages about JSON documents: paths written the way one reaches a field
// ("passes[0].state.cull", "uniforms[\"u tint\"]"), values described for "expected X, got Y",
// and "did you mean" suggestions. Shared by the schema check and the lab.json reader.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace shaderlab {

// A string as it would appear in JSON, ASCII-only and shortened to about 60 characters, so odd
// bytes or very long values cannot garble a message.
std::string quoteJson(const std::string& s);
// "256", "\"sideways\"", "an array of 5 elements", "an object", "null", ...
std::string describeJson(const nlohmann::json& v);
std::string formatNumber(double d);

bool isPlainName(const std::string& s);  // letters, digits, '_' and '-', not empty
std::string joinKey(const std::string& parent, const std::string& key);
std::string joinIndex(const std::string& parent, std::size_t i);

// " (did you mean \"uniforms\"?)" when a candidate is a few edits away, or a prefix of (or
// prefixed by) the word; "" otherwise.
std::string didYouMean(const std::string& word, const std::vector<std::string>& candidates);
std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace shaderlab
