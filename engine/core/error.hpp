#pragma once
// One exception type for every user-facing failure: its message is the one line the CLI prints
// ("scenes/x.json: models[0].obj: file not found"), so it must name the file and what is wrong.
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

}  // namespace lp
