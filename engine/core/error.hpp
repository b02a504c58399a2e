#pragma once
// One exception type for every user-facing failure: its message is the one line the CLI prints
// ("scenes/x.json: models[0].obj: file not found"), so it must name the file and what is wrong.
#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace lp {

struct Error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// `bytes` as text that keeps an Error's message one clean line: control bytes (a lone CR, an ESC)
// written as \xNN, and with `escapeHighBytes` also the bytes past ASCII (a binary field, such as a
// PNG chunk type, rather than a UTF-8 token).
inline std::string printableBytes(const std::string& bytes, bool escapeHighBytes = false) {
    static const char* const kHex = "0123456789ABCDEF";
    std::string out;
    for (const char ch : bytes) {
        const unsigned char c = static_cast<unsigned char>(ch);
        if (c < 0x20 || c == 0x7F || (escapeHighBytes && c > 0x7F)) out += std::string("\\x") + kHex[c >> 4] + kHex[c & 15];
        else out += ch;
    }
    return out;
}

// User text as a message quotes it (a name, a token, a URI, an extension, a path written inside a
// file): in single quotes, every control character (C0, DEL, C1) and every byte that is not part of
// valid UTF-8 written as \xNN, and cut after maxChars characters with its length said, so that a
// 70000-character data URI or a name holding terminal escapes stays a short clean line:
// 'data:image/png;base64,iVBORw0KGgo...' (70012 characters). Every message quoting user text uses it.
std::string quoteUserText(const std::string& text, size_t maxChars = 64);

// A path as a message names it: as it is when it is short and printable (the usual case, and what
// scripts match), else quoted by quoteUserText (a path written inside a file may be 5000 characters of
// terminal escapes; the message must still show what is wrong with it).
std::string shownPath(const std::filesystem::path& path);

// A whole message as it is printed: one line (CR and LF become spaces), control characters and bytes
// that are not UTF-8 written as \xNN, cut after maxChars characters (saying so). The last guard of
// the CLI's error line and of every warning, whatever a library put in its text.
std::string oneLineMessage(const std::string& message, size_t maxChars = 600);

}  // namespace lp
