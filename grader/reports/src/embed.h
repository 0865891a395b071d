// Internal: images as data: URIs for the writers that embed them (report.html, Gradescope's
// html output), within a byte budget.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "grader/reports/report.h"

namespace grader::detail {

// RFC 4648 base64 with padding.
std::string base64(const std::string& bytes);

// The file's bytes; empty with *ok false when it cannot be read.
std::string readFileBytes(const std::string& path, bool* ok);

// Size of the data: URI of `n` PNG bytes.
inline std::size_t dataUriSize(std::size_t n) { return 22 + (n + 2) / 3 * 4; }

// All of a report's pictures embedded, or none: data: URIs when every one of `paths` can be read
// from the root and they fit the budget together; otherwise each src is its relative path. A page
// whose pictures are half embedded and half linked would break in a way nobody expects.
class AllOrNothing {
  public:
    AllOrNothing(const std::vector<std::string>& paths, const ImageEmbedding& embedding);
    const std::string& src(const std::string& path) const;  // not escaped
    bool embedded() const { return embedded_; }
    std::size_t embedded_bytes() const { return bytes_; }

  private:
    std::map<std::string, std::string> uris_;
    bool embedded_ = false;
    std::size_t bytes_ = 0;
};

// Pictures embedded one at a time while the budget lasts (Gradescope: there is no folder to link
// to, so a picture is embedded or left out). take() returns the data: URI, or empty once the
// budget is spent or the file cannot be read.
class Budget {
  public:
    explicit Budget(const ImageEmbedding& embedding) : embedding_(embedding) {}
    std::string take(const std::string& path);
    std::size_t left_out() const { return left_out_; }

  private:
    ImageEmbedding embedding_;
    std::size_t spent_ = 0;
    std::size_t left_out_ = 0;
};

}  // namespace grader::detail
