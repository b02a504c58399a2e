#include "engine/core/error.hpp"

namespace lp {

namespace {

// The length of the UTF-8 sequence starting at text[i] (1 to 4), or 0 when the bytes there are not
// valid UTF-8 (a stray continuation byte, an overlong form, a surrogate, past U+10FFFF, cut short).
size_t utf8Sequence(const std::string& text, size_t i) {
    const auto at = [&](size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned char c = at(i);
    if (c < 0x80) return 1;
    size_t n = 0;
    unsigned char lo = 0x80, hi = 0xBF;  // the second byte's range
    if (c >= 0xC2 && c <= 0xDF) n = 2;
    else if (c == 0xE0) n = 3, lo = 0xA0;
    else if (c >= 0xE1 && c <= 0xEC) n = 3;
    else if (c == 0xED) n = 3, hi = 0x9F;
    else if (c >= 0xEE && c <= 0xEF) n = 3;
    else if (c == 0xF0) n = 4, lo = 0x90;
    else if (c >= 0xF1 && c <= 0xF3) n = 4;
    else if (c == 0xF4) n = 4, hi = 0x8F;
    else return 0;
    if (i + n > text.size()) return 0;
    if (at(i + 1) < lo || at(i + 1) > hi) return 0;
    for (size_t k = 2; k < n; ++k)
        if (at(i + k) < 0x80 || at(i + k) > 0xBF) return 0;
    return n;
}

void appendEscaped(std::string& out, unsigned char c) {
    static const char* const kHex = "0123456789ABCDEF";
    out += "\\x";
    out += kHex[c >> 4];
    out += kHex[c & 15];
}

// `text` made printable (see quoteUserText), at most maxChars characters; `characters` is set to the
// number of characters of the whole text. With lineBreaksAsSpaces, CR and LF become spaces.
std::string printable(const std::string& text, size_t maxChars, size_t& characters, bool lineBreaksAsSpaces) {
    std::string out;
    characters = 0;
    for (size_t i = 0; i < text.size(); ++characters) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        const size_t n = utf8Sequence(text, i);
        const bool keep = characters < maxChars;
        if (n == 0 || c < 0x20 || c == 0x7F || (c == 0xC2 && static_cast<unsigned char>(text[i + 1]) < 0xA0)) {
            // Not UTF-8, or a control character: C0, DEL, or C1 (U+0080..U+009F, a CSI among them).
            const size_t bytes = n == 0 ? 1 : n;
            if (keep) {
                if (lineBreaksAsSpaces && (c == '\n' || c == '\r')) out += ' ';
                else
                    for (size_t k = 0; k < bytes; ++k) appendEscaped(out, static_cast<unsigned char>(text[i + k]));
            }
            i += bytes;
        } else {
            if (keep) out.append(text, i, n);
            i += n;
        }
    }
    return out;
}

}  // namespace

std::string quoteUserText(const std::string& text, size_t maxChars) {
    size_t characters = 0;
    const std::string shown = printable(text, maxChars, characters, false);
    if (characters <= maxChars) return "'" + shown + "'";
    return "'" + shown + "...' (" + std::to_string(characters) + " characters)";
}

std::string shownPath(const std::filesystem::path& path) {
    const std::string& text = path.native();
    size_t characters = 0;
    const std::string shown = printable(text, 240, characters, false);
    return shown == text ? text : quoteUserText(text, 120);
}

std::string oneLineMessage(const std::string& message, size_t maxChars) {
    size_t characters = 0;
    std::string shown = printable(message, maxChars, characters, true);
    if (characters > maxChars) shown += "... (cut: " + std::to_string(characters) + " characters)";
    return shown;
}

}  // namespace lp
