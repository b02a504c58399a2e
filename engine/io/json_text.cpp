#include "engine/io/json_text.hpp"

#include <algorithm>

#include "engine/core/error.hpp"

namespace lp {

namespace {

using nlohmann::json;

// The parser builds the document as json::parse does, and keeps where and why it stopped instead of
// throwing the library's "[json.exception.parse_error.101] ..." (the number overflow of 1e309 arrives
// as an out_of_range without any position).
struct DocumentParser : nlohmann::detail::json_sax_dom_parser<json> {
    DocumentParser(json& root) : nlohmann::detail::json_sax_dom_parser<json>(root, false) {}
    bool failed = false;
    size_t position = 0;  // characters read when it stopped
    std::string token, what;
    int id = 0;
    bool parse_error(std::size_t at, const std::string& lastToken, const nlohmann::detail::exception& e) {
        failed = true;
        position = at;
        token = lastToken;
        what = e.what();
        id = e.id;
        return false;
    }
};

// Byte offset of the bracket that first goes deeper than maxDepth, or npos. Strings are skipped (a
// bracket inside one is text); a malformed document is left to the parser to name.
size_t tooDeepAt(const std::string& text, size_t maxDepth) {
    size_t depth = 0;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '"') {
            for (++i; i < text.size() && text[i] != '"'; ++i)
                if (text[i] == '\\') ++i;
        } else if (c == '[' || c == '{') {
            if (++depth > maxDepth) return i;
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return std::string::npos;
}

}  // namespace

std::string textPosition(const std::string& text, size_t offset) {
    offset = std::min(offset, text.size());
    size_t line = 1, column = 1;
    for (size_t i = 0; i < offset; ++i) {
        if (text[i] == '\n') {
            ++line;
            column = 1;
        } else if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) {  // not a UTF-8 continuation byte
            ++column;
        }
    }
    return std::to_string(line) + ":" + std::to_string(column);
}

json parseJsonText(const std::string& text, const std::string& file, size_t maxDepth) {
    if (const size_t at = tooDeepAt(text, maxDepth); at != std::string::npos)
        throw Error(file + ":" + textPosition(text, at) + ": arrays and objects nested more than " + std::to_string(maxDepth) +
                    " levels deep (the limit for a JSON document)");
    json root;
    DocumentParser parser(root);
    json::sax_parse(text, &parser);
    if (!parser.failed) return root;
    std::string what;
    size_t offset = parser.position > 0 ? parser.position - 1 : 0;  // the last character read
    if (parser.id == 406) {
        // Number overflow: the number ended where the parser stopped.
        offset = parser.position >= parser.token.size() ? parser.position - parser.token.size() : 0;
        what = "number " + quoteUserText(parser.token) + " is beyond the range of a double (about 1.8e308)";
    } else {
        // "[json.exception.parse_error.101] parse error at line 1, column 9: syntax error while parsing
        // value - invalid literal; last read: '...'": the reason, with the token quoted as ours are.
        what = parser.what;
        const size_t column = what.find(", column ");
        const size_t colon = column == std::string::npos ? std::string::npos : what.find(": ", column);
        if (colon != std::string::npos) what = what.substr(colon + 2);
        const std::string lastRead = "last read: '" + parser.token + "'";
        if (const size_t at = what.find(lastRead); at != std::string::npos)
            what.replace(at, lastRead.size(), "last read: " + quoteUserText(parser.token));
        // Past a line's end or the text's, the place is where the last token ended.
        while (offset > 0 && offset < text.size() && (text[offset] == '\n' || text[offset] == '\r')) --offset;
        what = "invalid JSON: " + what;
    }
    throw Error(file + ":" + textPosition(text, offset) + ": " + oneLineMessage(what, 300));
}

}  // namespace lp
