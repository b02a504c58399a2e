// What the glTF loader tests share: a temporary folder per test, named after the test, the one
// error line loading a file gives, and a document builder (Doc) whose buffer travels as a data URI.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/core/error.hpp"
#include "engine/io/gltf_loader.hpp"

namespace lp::test {

struct TempDir {
    std::filesystem::path dir;
    explicit TempDir(const std::string& prefix = "lp_gltf_") {
        dir = std::filesystem::temp_directory_path() / (prefix + std::to_string(::getpid()) + "_" +
                                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::remove_all(dir);
        std::filesystem::create_directories(dir);
    }
    ~TempDir() { std::filesystem::remove_all(dir); }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    std::filesystem::path write(const std::string& name, const std::string& bytes) const {
        std::ofstream(dir / name, std::ios::binary) << bytes;
        return dir / name;
    }
};

// The error loading `p` raises, or "" when it loads.
inline std::string loadError(const std::filesystem::path& p) {
    try {
        loadGltf(p);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

inline std::string base64(const std::string& bytes) {
    static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 1])) << 8;
        if (i + 2 < bytes.size()) v |= uint8_t(bytes[i + 2]);
        out += k[v >> 18 & 63];
        out += k[v >> 12 & 63];
        out += i + 1 < bytes.size() ? k[v >> 6 & 63] : '=';
        out += i + 2 < bytes.size() ? k[v & 63] : '=';
    }
    return out;
}

template <typename T>
inline std::string bytesOf(std::initializer_list<T> values) {
    std::string out;
    for (T v : values) out.append(reinterpret_cast<const char*>(&v), sizeof v);
    return out;
}

// A glTF of one buffer made of `views` (each a buffer view, 4-byte aligned), with the given accessors,
// primitive attributes and extra top-level fields: a document to mutate.
struct Doc {
    nlohmann::json j = {{"asset", {{"version", "2.0"}}}, {"bufferViews", nlohmann::json::array()}, {"accessors", nlohmann::json::array()},
              {"nodes", nlohmann::json::array()}, {"scenes", {{{"nodes", nlohmann::json::array()}}}}, {"scene", 0}};
    std::string bin;
    int view(const std::string& data) {
        bin.append((4 - bin.size() % 4) % 4, '\0');
        j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", data.size()}});
        bin += data;
        return int(j["bufferViews"].size()) - 1;
    }
    int accessor(nlohmann::json a) {
        j["accessors"].push_back(std::move(a));
        return int(j["accessors"].size()) - 1;
    }
    int floats(std::initializer_list<float> v, const char* type, size_t count) {
        return accessor({{"bufferView", view(bytesOf(v))}, {"componentType", 5126}, {"type", type}, {"count", count}});
    }
    int floatArray(const std::vector<float>& v, const char* type, size_t count) {
        std::string bytes(v.size() * sizeof(float), '\0');
        if (!v.empty()) std::memcpy(bytes.data(), v.data(), bytes.size());
        return accessor({{"bufferView", view(bytes)}, {"componentType", 5126}, {"type", type}, {"count", count}});
    }
    // The unit quad facing +Z, corners (-1,-1) (1,-1) (1,1) (-1,1); `attributes` added to POSITION.
    int quad(nlohmann::json attributes = nlohmann::json::object()) {
        attributes["POSITION"] = floats({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, "VEC3", 4);
        const int idx = accessor({{"bufferView", view(bytesOf<uint16_t>({0, 1, 2, 0, 2, 3}))}, {"componentType", 5123}, {"type", "SCALAR"},
                                  {"count", 6}});
        j["meshes"].push_back({{"primitives", {{{"attributes", attributes}, {"indices", idx}}}}});
        return int(j["meshes"].size()) - 1;
    }
    int node(nlohmann::json n, bool root = true) {
        j["nodes"].push_back(std::move(n));
        const int i = int(j["nodes"].size()) - 1;
        if (root) j["scenes"][0]["nodes"].push_back(i);
        return i;
    }
    std::string text() const {
        nlohmann::json out = j;
        out["buffers"] = {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}};
        return out.dump();
    }
};

}  // namespace lp::test
