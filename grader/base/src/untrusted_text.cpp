// Escaping and capping text from student code and drivers; see untrusted_text.h.
#include "grader/base/untrusted_text.h"

#include <cstdint>
#include <cstdio>

namespace grader {

namespace {

// Length of the valid UTF-8 sequence at s[i] and its code point; 0 when it is not one (overlong
// forms and surrogates included).
std::size_t decodeUtf8(std::string_view s, std::size_t i, std::uint32_t* cp) {
    const auto b = [&](std::size_t k) { return static_cast<unsigned char>(s[i + k]); };
    const unsigned char c = b(0);
    std::size_t n = 0;
    std::uint32_t v = 0, min = 0;
    if (c < 0x80) {
        *cp = c;
        return 1;
    } else if ((c & 0xE0) == 0xC0) {
        n = 2, v = c & 0x1F, min = 0x80;
    } else if ((c & 0xF0) == 0xE0) {
        n = 3, v = c & 0x0F, min = 0x800;
    } else if ((c & 0xF8) == 0xF0) {
        n = 4, v = c & 0x07, min = 0x10000;
    } else {
        return 0;
    }
    if (i + n > s.size()) return 0;
    for (std::size_t k = 1; k < n; ++k) {
        if ((b(k) & 0xC0) != 0x80) return 0;
        v = (v << 6) | (b(k) & 0x3F);
    }
    if (v < min || v > 0x10FFFF || (v >= 0xD800 && v <= 0xDFFF)) return 0;
    *cp = v;
    return n;
}

// Characters that change how the text around them is shown (Trojan Source, CVE-2021-42574).
bool isBidiControl(std::uint32_t cp) {
    return cp == 0x061C || cp == 0x200E || cp == 0x200F || (cp >= 0x202A && cp <= 0x202E) ||
           (cp >= 0x2066 && cp <= 0x2069);
}

}  // namespace

std::string printableText(std::string_view text, std::size_t max_bytes, bool keep_newlines) {
    std::string out;
    out.reserve(text.size() < max_bytes ? text.size() : max_bytes);
    std::size_t i = 0;
    char buf[16];
    while (i < text.size()) {
        if (out.size() >= max_bytes) break;
        std::uint32_t cp = 0;
        const std::size_t n = decodeUtf8(text, i, &cp);
        if (n == 0) {
            std::snprintf(buf, sizeof buf, "\\x%02X", static_cast<unsigned char>(text[i]));
            out += buf;
            i += 1;
            continue;
        }
        const bool allowed_control = cp == '\t' || (keep_newlines && cp == '\n');
        if ((cp < 0x20 && !allowed_control) || cp == 0x7F) {
            std::snprintf(buf, sizeof buf, "\\x%02X", static_cast<unsigned>(cp));
            out += buf;
        } else if ((cp >= 0x80 && cp <= 0x9F) || isBidiControl(cp)) {
            std::snprintf(buf, sizeof buf, "\\u%04X", static_cast<unsigned>(cp));
            out += buf;
        } else {
            out.append(text.data() + i, n);
        }
        i += n;
    }
    if (i < text.size()) out += " [... " + std::to_string(text.size() - i) + " more bytes left out]";
    return out;
}

}  // namespace grader
