#pragma once
// JSON text parsed with the checks a file from anywhere needs before any recursion touches it: its
// nesting depth is bounded by a scan of its brackets (a 33 KB file of 15000 nested arrays overflowed
// the stack of the parsers and converters that walk a document recursively), and every error is one
// line "<file>:<line>:<column>: what", the offending text quoted by quoteUserText: syntax errors,
// numbers beyond a double (1e309), bytes that are not UTF-8.
#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

namespace lp {

// Deeper than any glTF's own structure (under 10 levels) and any sane `extras`, far below what a
// recursive walk of the document needs of a 1 MiB stack.
constexpr size_t kMaxJsonDepth = 128;

// The document of `text`, or an lp::Error "<file>:<line>:<column>: <what>" naming the first problem:
// nesting deeper than maxDepth (the bracket that goes too deep), or what the parser found.
nlohmann::json parseJsonText(const std::string& text, const std::string& file, size_t maxDepth = kMaxJsonDepth);

// "<line>:<column>" of byte `offset` of `text`, both from 1, the column in characters (UTF-8).
std::string textPosition(const std::string& text, size_t offset);

}  // namespace lp
