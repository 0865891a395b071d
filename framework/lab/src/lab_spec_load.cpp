// Step 1 of the lab.json parser: the text into a JSON DOM, refusing what the DOM would hide or
// what later steps could not take: more than 1 MiB, duplicate keys (the DOM keeps only the last),
// nesting deeper than 32 levels and strings longer than 4096 bytes (the schema validator and its
// regexes recurse on both). Syntax errors name a line and a column counted in characters. It knows
// nothing of what lab.json means; the schema and the later steps do (lab_spec.cpp).
#include <cstddef>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "lab_spec_steps.h"

namespace shaderlab::lab_spec_detail {

namespace {

constexpr std::size_t kMaxDepth = 32;
constexpr std::size_t kMaxStringBytes = 4096;

std::string lineColumn(const std::string& text, std::size_t byte) {
    const std::size_t at = std::min(byte == 0 ? 0 : byte - 1, text.size());
    std::size_t line = 1, line_start = 0;
    for (std::size_t i = 0; i < at; ++i) {
        if (text[i] == '\n') {
            ++line;
            line_start = i + 1;
        }
    }
    std::size_t column = 1;
    for (std::size_t i = line_start; i < at; ++i)
        if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) ++column;  // count code points
    return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

std::string syntaxProblem(const std::string& what) {
    const std::size_t at = what.find("parse error");
    if (at != std::string::npos) {
        const std::size_t colon = what.find(": ", at);
        if (colon != std::string::npos) return what.substr(colon + 2);
    }
    const std::size_t bracket = what.find("] ");
    return bracket == std::string::npos ? what : what.substr(bracket + 2);
}

// A SAX pass over the text before the DOM is built: keys repeated within one object (the DOM
// would keep only the last), nesting deeper than kMaxDepth and strings longer than
// kMaxStringBytes (the schema validator and regexes recurse on both).
class PreScan : public nlohmann::json_sax<json> {
  public:
    std::vector<std::pair<std::string, std::string>> problems;  // path, problem

    bool null() override { return scalar(); }
    bool boolean(bool) override { return scalar(); }
    bool number_integer(number_integer_t) override { return scalar(); }
    bool number_unsigned(number_unsigned_t) override { return scalar(); }
    bool number_float(number_float_t, const string_t&) override { return scalar(); }
    bool string(string_t& s) override {
        if (s.size() > kMaxStringBytes)
            problems.emplace_back(pathHere(), "a string of " + std::to_string(s.size()) +
                                                  " bytes is longer than the limit of " +
                                                  std::to_string(kMaxStringBytes));
        return scalar();
    }
    bool binary(binary_t&) override { return scalar(); }
    bool start_object(std::size_t) override { return open(true); }
    bool key(string_t& k) override {
        Frame& f = frames_.back();
        if (k.size() > kMaxStringBytes) {
            problems.emplace_back(pathOfTop(), "a key of " + std::to_string(k.size()) + " bytes is too long");
            return false;
        }
        if (!f.keys.insert(k).second)
            problems.emplace_back(joinKey(pathOfTop(), k),
                                  "duplicate key: it appears more than once in this object, and only the "
                                  "last one would count");
        f.key = k;
        return true;
    }
    bool end_object() override { return close(); }
    bool start_array(std::size_t) override { return open(false); }
    bool end_array() override { return close(); }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
        return false;
    }

  private:
    struct Frame {
        bool is_object;
        std::set<std::string> keys;
        std::string key;
        std::size_t index = 0;
    };
    bool open(bool is_object) {
        if (frames_.size() >= kMaxDepth) {
            problems.emplace_back(pathOfTop(), "nested deeper than " + std::to_string(kMaxDepth) + " levels");
            return false;  // stop: the DOM must not be built either
        }
        frames_.push_back(Frame{is_object, {}, {}, 0});
        return true;
    }
    std::string pathOfTop() const {
        std::string path;
        for (std::size_t i = 0; i + 1 < frames_.size(); ++i)
            path = frames_[i].is_object ? joinKey(path, frames_[i].key) : joinIndex(path, frames_[i].index);
        return path;
    }
    std::string pathHere() const {
        if (frames_.empty()) return "";
        const Frame& f = frames_.back();
        return f.is_object ? joinKey(pathOfTop(), f.key) : joinIndex(pathOfTop(), f.index);
    }
    bool scalar() {
        if (!frames_.empty() && !frames_.back().is_object) ++frames_.back().index;
        return true;
    }
    bool close() {
        frames_.pop_back();
        return scalar();
    }
    std::vector<Frame> frames_;
};

}  // namespace

bool loadJson(const std::string& text, Diagnostics& diag, json& out) {
    if (text.size() > kMaxLabJsonBytes) {
        diag.error("", "is " + std::to_string(text.size()) + " bytes, more than the limit of " +
                           std::to_string(kMaxLabJsonBytes) + " (1 MiB)");
        return false;
    }
    PreScan scan;
    bool syntax_ok = true;
    try {
        syntax_ok = json::sax_parse(text, &scan);
    } catch (const json::exception&) {
        syntax_ok = false;  // reported by the DOM parse below
    }
    for (const auto& [path, problem] : scan.problems) diag.error(path, problem);
    if (!syntax_ok && !scan.problems.empty()) return false;  // stopped for depth: do not build the DOM
    try {
        out = json::parse(text);
    } catch (const json::parse_error& e) {
        diag.error(lineColumn(text, e.byte), syntaxProblem(e.what()));
        return false;
    } catch (const json::exception& e) {
        // e.g. "number overflow parsing '1e999'": find the literal to point at it.
        const std::string what = e.what();
        std::string where;
        const std::size_t open = what.find('\'');
        const std::size_t close = open == std::string::npos ? open : what.find('\'', open + 1);
        if (close != std::string::npos) {
            const std::size_t at = text.find(what.substr(open + 1, close - open - 1));
            if (at != std::string::npos) where = lineColumn(text, at + 1);
        }
        diag.error(where, syntaxProblem(what));
        return false;
    }
    return !diag.any();
}

}  // namespace shaderlab::lab_spec_detail
