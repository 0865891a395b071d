// Text that comes from a student's files or from a GL driver's log, made fit to print on a
// terminal and to store in a report. Such text can hold anything: terminal escape sequences
// (`#error \e[2J` would clear the grader's screen), other control characters, bytes that are not
// UTF-8, characters that reorder what is shown (Unicode bidirectional overrides), and lines of
// megabytes. Every string from student code or a driver goes through printableText() before it
// reaches a report or a terminal.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace grader {

// `text` with every control character (C0 but tab and, when `keep_newlines`, newline; DEL; C1),
// every byte that is not part of valid UTF-8 and every bidirectional-formatting character written
// out visibly as \xHH or \uHHHH; cut to at most about `max_bytes` at a character boundary, with
// " [... N more bytes left out]" saying how much was cut.
std::string printableText(std::string_view text, std::size_t max_bytes = 4096, bool keep_newlines = false);

}  // namespace grader
