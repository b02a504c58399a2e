// load_check FILE...: reads each file as lightpass does, without a GPU, and prints what lightpass would
// print: its warnings and "ok", or its one error line (exit 1 if any file failed). A model (.gltf,
// .glb, .obj) is loaded as `--model` loads it and its textures decoded as they are for upload (the
// checker standing in for a bad one, with its warning); a scene (.json) with every model and its
// environment map; an image by its extension (.hdr, .exr: an environment map; else a texture).
// tests/bad_input/sanitize.sh builds it with AddressSanitizer and UBSan and runs it over the corpus.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/io/image_io.hpp"
#include "engine/scene/scene_loader.hpp"

namespace fs = std::filesystem;

namespace {

void decodeTextures(const lp::Scene& scene) {
    for (const lp::ModelInstance& model : scene.models)
        for (const lp::Material& m : model.mesh.materials)
            for (const lp::TextureRef* t : {&m.diffuseMap, &m.bumpMap, &m.normalMap, &m.metallicRoughnessMap, &m.occlusionMap, &m.emissiveMap}) {
                if (t->empty()) continue;
                if (!t->problem.empty()) lp::logWarn(t->key + ": " + t->problem + "; using a checker texture");
                else if (t->encoded) lp::decodeTextureOrChecker(*t->encoded, t->key);
                else lp::loadTextureOrChecker(t->path);
            }
}

void check(const fs::path& file) {
    std::string ext = file.extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (lp::isModelPath(file)) {
        decodeTextures(lp::sceneForModel(file));
    } else if (ext == ".json") {
        const lp::Scene scene = lp::loadScene(file);
        decodeTextures(scene);
        if (!scene.environment.map.empty()) lp::loadHdrImage(scene.environment.map);
    } else if (ext == ".hdr" || ext == ".exr") {
        lp::loadHdrImage(file);
    } else {
        lp::loadTextureOrChecker(file);
    }
}

}  // namespace

int main(int argc, char** argv) {
    int failed = 0;
    for (int i = 1; i < argc; ++i) {
        std::string error;
        try {
            check(argv[i]);
        } catch (const std::bad_alloc&) {
            error = "out of memory";
        } catch (const std::exception& e) {
            error = *e.what() ? e.what() : "unexpected error";
        }
        lp::flushRepeatedWarnings();
        if (error.empty()) {
            std::printf("ok %s\n", argv[i]);
        } else {
            std::fprintf(stderr, "lightpass: error: %s\n", lp::oneLineMessage(error).c_str());
            ++failed;
        }
    }
    return failed ? 1 : 0;
}
