#include "engine/io/gltf_container.hpp"

#include <cctype>
#include <cstring>

#include "engine/core/error.hpp"

namespace lp {

namespace {

constexpr uint32_t kChunkJson = 0x4E4F534Au;  // "JSON"
constexpr uint32_t kChunkBin = 0x004E4942u;   // "BIN\0"

uint32_t littleEndian32(const std::string& bytes, size_t at) {
    uint32_t v = 0;
    for (int k = 3; k >= 0; --k) v = v << 8 | static_cast<unsigned char>(bytes[at + size_t(k)]);
    return v;
}

std::string hex32(uint32_t v) {
    static const char* const kHex = "0123456789ABCDEF";
    std::string s = "0x";
    for (int shift = 28; shift >= 0; shift -= 4) s += kHex[(v >> shift) & 15];
    return s;
}

// A chunk type as text and number: 'BIN\x00' (0x004E4942).
std::string chunkType(uint32_t type) {
    std::string text;
    for (int k = 0; k < 4; ++k) text += char((type >> (8 * k)) & 0xFF);
    return "'" + printableBytes(text, true) + "' (" + hex32(type) + ")";
}

void putLittleEndian32(std::string& out, uint32_t v) {
    for (int k = 0; k < 4; ++k) out += char((v >> (8 * k)) & 0xFF);
}

int base64Value(unsigned char c) {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
}

}  // namespace

GltfSource readGltfContainer(const std::string& bytes, const std::string& file, bool glbByName) {
    GltfSource s;
    auto fail = [&](const std::string& what) { throw Error(file + ": " + what); };
    if (bytes.compare(0, 4, "glTF") != 0) {
        if (glbByName) {
            // A .glb holding JSON text (a renamed .gltf) is read as such; anything else is not a GLB.
            size_t first = bytes.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
            while (first < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[first]))) ++first;
            if (first >= bytes.size() || bytes[first] != '{')
                fail("not a GLB file: it starts with " + quoteUserText(bytes.substr(0, 4)) +
                     ", not the magic 'glTF' (nor with JSON text)");
        }
        s.json = bytes;
        return s;
    }
    s.binary = true;
    if (bytes.size() < 12) fail("GLB header: the file has " + std::to_string(bytes.size()) + " bytes, the header needs 12");
    const uint32_t version = littleEndian32(bytes, 4);
    if (version != 2) fail("GLB container version " + std::to_string(version) + ": lightpass reads glTF 2.0 (GLB version 2)");
    const uint32_t length = littleEndian32(bytes, 8);
    if (length > bytes.size())
        fail("GLB header (byte 8): length " + std::to_string(length) + ", but the file has " + std::to_string(bytes.size()) +
             " bytes (truncated)");
    if (length < 20)
        fail("GLB header (byte 8): length " + std::to_string(length) + ", less than the 20 bytes of the header and the JSON chunk's header");
    if (length < bytes.size()) {
        s.warnings.push_back(std::to_string(bytes.size() - length) + " bytes after the GLB's length (" + std::to_string(length) +
                             " bytes, header byte 8) are ignored");
        s.rebuild = true;  // tinygltf would take the file's size for the GLB's
    }
    size_t at = 12;
    for (int index = 0; at < length; ++index) {
        const std::string chunk = "chunk " + std::to_string(index);
        if (length - at < 8)
            fail(chunk + " at byte " + std::to_string(at) + ": its header needs 8 bytes, but " + std::to_string(length - at) +
                 " remain of the GLB's " + std::to_string(length));
        const uint32_t chunkLength = littleEndian32(bytes, at), type = littleEndian32(bytes, at + 4);
        const std::string named = chunk + (type == kChunkJson ? " (JSON)" : type == kChunkBin ? " (BIN)" : "") + " at byte " + std::to_string(at);
        const size_t room = length - at - 8;
        if (chunkLength > room)
            fail(named + ": length " + std::to_string(chunkLength) + ", but " + std::to_string(room) +
                 " bytes follow its header (the GLB is " + std::to_string(length) + " bytes)");
        if (index == 0) {
            if (type != kChunkJson) fail(named + ": type " + chunkType(type) + ", but the first chunk must be JSON " + chunkType(kChunkJson));
            if (chunkLength == 0) fail(named + ": length 0, but the JSON chunk holds the document");
            s.json = bytes.substr(at + 8, chunkLength);
            // Padding is spaces; some writers pad with NUL bytes, which no JSON parser takes: read as
            // the padding they are (tinygltf then gets the chunk without them).
            for (int k = 0; k < 3 && !s.json.empty() && s.json.back() == '\0'; ++k) {
                s.json.pop_back();
                s.rebuild = true;
            }
        } else if (type == kChunkJson) {
            fail(named + ": a second JSON chunk (only chunk 0 is JSON)");
        } else if (type == kChunkBin && index == 1) {
            if (chunkLength % 4 != 0)
                fail(named + ": length " + std::to_string(chunkLength) + " is not a multiple of 4 (a chunk is padded to 4 bytes)");
            s.bin = reinterpret_cast<const unsigned char*>(bytes.data()) + at + 8;
            s.binBytes = chunkLength;
            s.binOffset = at;
            if (chunkLength == 0) s.rebuild = true;  // tinygltf refuses an empty one; it is no BIN chunk
        } else if (type == kChunkBin) {
            s.warnings.push_back(named + ": a BIN chunk after chunk 1 is ignored (only chunk 1 is the binary buffer)");
        } else if (index == 1) {
            s.rebuild = true;  // the spec's rule: chunks of unknown types are ignored; tinygltf refuses them here
        }
        at += 8 + size_t(chunkLength);
    }
    return s;
}

std::string makeGlb(const std::string& json, const unsigned char* bin, size_t binBytes) {
    const size_t jsonPadded = (json.size() + 3) / 4 * 4, binPadded = (binBytes + 3) / 4 * 4;
    const size_t total = 12 + 8 + jsonPadded + (binBytes ? 8 + binPadded : 0);
    if (total > 0xFFFFFFFFull) throw Error("GLB over 4 GiB");
    std::string out = "glTF";
    out.reserve(total);
    putLittleEndian32(out, 2);
    putLittleEndian32(out, uint32_t(total));
    putLittleEndian32(out, uint32_t(jsonPadded));
    putLittleEndian32(out, kChunkJson);
    out += json;
    out.append(jsonPadded - json.size(), ' ');
    if (binBytes) {
        putLittleEndian32(out, uint32_t(binPadded));
        putLittleEndian32(out, kChunkBin);
        out.append(reinterpret_cast<const char*>(bin), binBytes);
        out.append(binPadded - binBytes, '\0');
    }
    return out;
}

bool isDataUri(const std::string& uri) { return uri.compare(0, 5, "data:") == 0; }

DataUri decodeDataUri(const std::string& uri) {
    DataUri d;
    const size_t comma = uri.find(',');
    if (!isDataUri(uri) || comma == std::string::npos) {
        d.problem = "data URI: no ',' before its data";
        return d;
    }
    const std::string header = uri.substr(5, comma - 5);
    const bool base64 = header.size() >= 7 && header.compare(header.size() - 7, 7, ";base64") == 0;
    d.mediaType = header.substr(0, base64 ? header.size() - 7 : header.find(';'));
    if (!base64) {
        d.problem = "data URI: not base64-encoded (no ';base64'; glTF's data URIs are base64)";
        return d;
    }
    const size_t start = comma + 1;
    size_t end = uri.size();
    size_t padding = 0;
    while (end > start && uri[end - 1] == '=' && padding < 2) --end, ++padding;
    if ((end - start) % 4 == 1 || (padding && (end - start + padding) % 4 != 0)) {
        d.problem = "data URI: " + std::to_string(uri.size() - start) + " characters of base64 data, which no whole number of bytes encodes (cut short?)";
        return d;
    }
    d.bytes.reserve((end - start) / 4 * 3 + 2);
    uint32_t bits = 0;
    int held = 0;
    for (size_t i = start; i < end; ++i) {
        const int v = base64Value(static_cast<unsigned char>(uri[i]));
        if (v < 0) {
            d.problem = "data URI: character " + std::to_string(i - start + 1) + " of its base64 data, " +
                        quoteUserText(uri.substr(i, 1)) + ", is not base64";
            d.bytes.clear();
            return d;
        }
        bits = bits << 6 | uint32_t(v);
        held += 6;
        if (held >= 8) {
            held -= 8;
            d.bytes += char((bits >> held) & 0xFF);
        }
    }
    return d;
}

std::string percentDecoded(const std::string& uri) {
    std::string out;
    out.reserve(uri.size());
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
            out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

}  // namespace lp
