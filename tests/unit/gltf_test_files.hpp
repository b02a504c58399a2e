// What the glTF loader tests share: a temporary folder per test, named after the test, and the one
// error line loading a file gives.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

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

}  // namespace lp::test
