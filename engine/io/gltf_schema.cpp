#include "engine/io/gltf_schema.hpp"

#include <algorithm>
#include <cstdint>

#include "engine/core/error.hpp"
#include <initializer_list>
#include <utility>

namespace lp {

namespace {

using nlohmann::json;

// A value as an error message shows it: numbers and booleans as written, strings quoted (quoteUserText:
// cut at 24 characters, control characters escaped), containers by kind.
std::string describe(const json& v) {
    if (v.is_string()) return "a string (" + quoteUserText(v.get<std::string>(), 24) + ")";
    if (v.is_number() || v.is_boolean()) return v.dump();
    if (v.is_array()) return "an array";
    if (v.is_object()) return "an object";
    return "null";
}

std::string numberText(const json& v) { return v.dump(); }

std::string listed(std::initializer_list<const char*> values) {
    std::string s;
    for (const char* v : values) s += (s.empty() ? "" : ", ") + std::string(v);
    return s;
}

std::string listed(const std::vector<int64_t>& values) {
    std::string s;
    for (int64_t v : values) s += (s.empty() ? "" : ", ") + std::to_string(v);
    return s;
}

// Whether integer v (a JSON integer) lies in [lo, hi].
bool integerWithin(const json& v, int64_t lo, int64_t hi) {
    if (v.is_number_unsigned()) {
        const uint64_t u = v.get<uint64_t>();
        return hi >= 0 && u <= uint64_t(hi) && (lo <= 0 || u >= uint64_t(lo));
    }
    const int64_t s = v.get<int64_t>();
    return s >= lo && s <= hi;
}

class Checker {
public:
    std::vector<GltfSchemaIssue> issues;

    // Inside leniently(): a property lightpass does not read, or reads with a default to fall back on;
    // breaking its rule is a warning (what then happens: `lenientNote`), not a reason to refuse a model
    // other viewers show.
    bool lenient = false;
    std::string lenientNote;

    void error(const std::string& where, const std::string& what) {
        if (lenient) issues.push_back({where, what + "; " + lenientNote, false});
        else issues.push_back({where, what, true});
    }
    template <typename F>
    void leniently(F&& check, const std::string& note = "ignored (lightpass does not read it)") {
        const bool was = lenient;
        const std::string wasNote = lenientNote;
        lenient = true;
        lenientNote = note;
        check();
        lenient = was;
        lenientNote = wasNote;
    }
    void warning(const std::string& where, const std::string& what) { issues.push_back({where, what, false}); }

    static std::string join(const std::string& at, const std::string& key) { return at.empty() ? key : at + "." + key; }
    static std::string item(const std::string& at, size_t i) { return at + "[" + std::to_string(i) + "]"; }

    // obj's member `key`, or nullptr when absent (an error when required).
    const json* member(const json& obj, const char* key, const std::string& at, bool required) {
        const auto it = obj.find(key);
        if (it == obj.end()) {
            if (required) error(join(at, key), "missing (the glTF schema requires it)");
            return nullptr;
        }
        return &*it;
    }

    bool expect(const json& v, const std::string& where, bool ok, const std::string& want) {
        if (!ok) error(where, "expected " + want + ", got " + describe(v));
        return ok;
    }

    const json* object(const json& obj, const char* key, const std::string& at, bool required = false) {
        const json* v = member(obj, key, at, required);
        return v && expect(*v, join(at, key), v->is_object(), "an object") ? v : nullptr;
    }

    void string(const json& obj, const char* key, const std::string& at, bool required = false) {
        if (const json* v = member(obj, key, at, required)) expect(*v, join(at, key), v->is_string(), "a string");
    }

    void boolean(const json& obj, const char* key, const std::string& at) {
        if (const json* v = member(obj, key, at, false)) expect(*v, join(at, key), v->is_boolean(), "true or false");
    }

    // An index into one of the document's arrays: an integer from 0 (tinygltf keeps them as int).
    bool indexValue(const json& v, const std::string& where) {
        if (!expect(v, where, v.is_number_integer() && integerWithin(v, 0, INT64_MAX), "an index (an integer >= 0)")) return false;
        return expect(v, where, integerWithin(v, 0, INT32_MAX), "an index below 2^31");
    }
    void index(const json& obj, const char* key, const std::string& at, bool required = false) {
        if (const json* v = member(obj, key, at, required)) indexValue(*v, join(at, key));
    }
    void indexArray(const json& obj, const char* key, const std::string& at) {
        const json* v = member(obj, key, at, false);
        if (!v || !expect(*v, join(at, key), v->is_array(), "an array of indices")) return;
        for (size_t i = 0; i < v->size(); ++i) indexValue((*v)[i], item(join(at, key), i));
    }

    void integer(const json& obj, const char* key, const std::string& at, int64_t lo, int64_t hi, bool required = false) {
        const json* v = member(obj, key, at, required);
        if (!v) return;
        const std::string range = hi == INT64_MAX ? "an integer >= " + std::to_string(lo)
                                                  : "an integer from " + std::to_string(lo) + " to " + std::to_string(hi);
        expect(*v, join(at, key), v->is_number_integer() && integerWithin(*v, lo, hi), range);
    }

    void enumInteger(const json& obj, const char* key, const std::string& at, const std::vector<int64_t>& values,
                     bool required = false) {
        const json* v = member(obj, key, at, required);
        if (!v) return;
        bool ok = false;
        if (v->is_number_integer())
            for (int64_t e : values) ok = ok || integerWithin(*v, e, e);
        expect(*v, join(at, key), ok, "one of " + listed(values));
    }

    void enumString(const json& obj, const char* key, const std::string& at, std::initializer_list<const char*> values,
                    bool required = false) {
        const json* v = member(obj, key, at, required);
        if (!v) return;
        bool ok = false;
        if (v->is_string())
            for (const char* e : values) ok = ok || v->get<std::string>() == e;
        expect(*v, join(at, key), ok, "one of " + listed(values));
    }

    const json* number(const json& obj, const char* key, const std::string& at, bool required = false) {
        const json* v = member(obj, key, at, required);
        return v && expect(*v, join(at, key), v->is_number(), "a number") ? v : nullptr;
    }

    // An array of numbers of length min..max; nullptr unless it is one.
    const json* numbers(const json& obj, const char* key, const std::string& at, size_t min, size_t max) {
        const json* v = member(obj, key, at, false);
        if (!v) return nullptr;
        const std::string where = join(at, key);
        const std::string want = min == max ? "an array of " + std::to_string(min) + " numbers"
                                            : "an array of " + std::to_string(min) + " to " + std::to_string(max) + " numbers";
        if (!v->is_array() || v->size() < min || v->size() > max) {
            error(where, "expected " + want + ", got " + (v->is_array() ? "an array of " + std::to_string(v->size()) : describe(*v)));
            return nullptr;
        }
        bool ok = true;
        for (size_t i = 0; i < v->size(); ++i) ok = expect((*v)[i], item(where, i), (*v)[i].is_number(), "a number") && ok;
        return ok ? v : nullptr;
    }

    // A material factor the schema bounds to [0, 1] (or [0, inf) with hi < 0): outside, a warning
    // that the loader clamps it.
    void factorValue(const json& v, const std::string& where, double hi = 1.0) {
        const double x = v.get<double>();
        if (x < 0.0 || (hi >= 0.0 && x > hi))
            warning(where, numberText(v) + " is outside " + (hi >= 0.0 ? "[0, 1]" : "[0, inf)") + "; clamped");
    }
    void factor(const json& obj, const char* key, const std::string& at, double hi = 1.0) {
        if (const json* v = number(obj, key, at)) factorValue(*v, join(at, key), hi);
    }
    void factors(const json& obj, const char* key, const std::string& at, size_t n) {
        if (const json* v = numbers(obj, key, at, n, n))
            for (size_t i = 0; i < n; ++i) factorValue((*v)[i], item(join(at, key), i));
    }

    // A number the schema requires > 0 (or >= 0 with `zero`): otherwise an error.
    void positive(const json& obj, const char* key, const std::string& at, bool required, bool zero = false) {
        const json* v = number(obj, key, at, required);
        if (!v) return;
        const double x = v->get<double>();
        if (zero ? x < 0.0 : x <= 0.0) error(join(at, key), numberText(*v) + (zero ? " must be >= 0" : " must be > 0"));
    }

    // Each element of array `key` of `obj`, an object, to `check(element, where)`.
    template <typename F>
    void objects(const json& obj, const char* key, const std::string& at, F&& check, bool required = false, size_t minItems = 0) {
        const json* v = member(obj, key, at, required);
        if (!v) return;
        const std::string where = join(at, key);
        if (!expect(*v, where, v->is_array(), "an array of objects")) return;
        if (v->size() < minItems) error(where, "expected at least " + std::to_string(minItems) + " element(s), got none");
        for (size_t i = 0; i < v->size(); ++i)
            if (expect((*v)[i], item(where, i), (*v)[i].is_object(), "an object")) check((*v)[i], item(where, i));
    }

    void textureInfo(const json& obj, const char* key, const std::string& at, const char* extra = nullptr, bool extraIsFactor = false) {
        const json* t = object(obj, key, at);
        if (!t) return;
        const std::string w = join(at, key);
        index(*t, "index", w, true);
        integer(*t, "texCoord", w, 0, INT32_MAX);
        if (const json* ext = object(*t, "extensions", w))
            if (const json* x = object(*ext, "KHR_texture_transform", join(w, "extensions"))) {
                const std::string xw = join(w, "extensions.KHR_texture_transform");
                numbers(*x, "offset", xw, 2, 2);
                number(*x, "rotation", xw);
                numbers(*x, "scale", xw, 2, 2);
                integer(*x, "texCoord", xw, 0, INT32_MAX);
            }
        if (extra) {
            if (extraIsFactor) factor(*t, extra, w);
            else number(*t, extra, w);
        }
    }

    void material(const json& m, const std::string& w) {
        string(m, "name", w);
        if (const json* pbr = object(m, "pbrMetallicRoughness", w)) {
            const std::string pw = join(w, "pbrMetallicRoughness");
            factors(*pbr, "baseColorFactor", pw, 4);
            textureInfo(*pbr, "baseColorTexture", pw);
            factor(*pbr, "metallicFactor", pw);
            factor(*pbr, "roughnessFactor", pw);
            textureInfo(*pbr, "metallicRoughnessTexture", pw);
        }
        textureInfo(m, "normalTexture", w, "scale");
        textureInfo(m, "occlusionTexture", w, "strength", true);
        textureInfo(m, "emissiveTexture", w);
        factors(m, "emissiveFactor", w, 3);
        enumString(m, "alphaMode", w, {"OPAQUE", "MASK", "BLEND"});
        factor(m, "alphaCutoff", w, -1.0);
        boolean(m, "doubleSided", w);
        if (const json* ext = object(m, "extensions", w)) {
            const std::string ew = join(w, "extensions");
            if (const json* s = object(*ext, "KHR_materials_emissive_strength", ew))
                number(*s, "emissiveStrength", join(ew, "KHR_materials_emissive_strength"));
            if (const json* s = object(*ext, "KHR_materials_ior", ew))
                if (const json* n = number(*s, "ior", join(ew, "KHR_materials_ior")))
                    if (n->get<double>() != 0.0 && n->get<double>() < 1.0)
                        error(join(ew, "KHR_materials_ior.ior"), numberText(*n) + " must be >= 1 (or 0)");
            if (const json* s = object(*ext, "KHR_materials_specular", ew)) {
                const std::string sw = join(ew, "KHR_materials_specular");
                if (const json* f = number(*s, "specularFactor", sw))
                    if (f->get<double>() < 0.0 || f->get<double>() > 1.0)
                        error(join(sw, "specularFactor"), numberText(*f) + " must be in [0, 1]");
                if (const json* c = numbers(*s, "specularColorFactor", sw, 3, 3))
                    for (size_t i = 0; i < 3; ++i)
                        if ((*c)[i].get<double>() < 0.0)
                            error(item(join(sw, "specularColorFactor"), i), numberText((*c)[i]) + " must be >= 0");
                textureInfo(*s, "specularTexture", sw);
                textureInfo(*s, "specularColorTexture", sw);
            }
            if (const json* c = object(*ext, "KHR_materials_clearcoat", ew)) {
                const std::string cw = join(ew, "KHR_materials_clearcoat");
                for (const char* key : {"clearcoatFactor", "clearcoatRoughnessFactor"})
                    if (const json* f = number(*c, key, cw))
                        if (!(f->get<double>() >= 0.0 && f->get<double>() <= 1.0))
                            error(join(cw, key), numberText(*f) + " must be in [0, 1]");
                textureInfo(*c, "clearcoatTexture", cw);
                textureInfo(*c, "clearcoatRoughnessTexture", cw);
                textureInfo(*c, "clearcoatNormalTexture", cw, "scale");
            }
            if (const json* t = object(*ext, "KHR_materials_transmission", ew)) {
                const std::string tw = join(ew, "KHR_materials_transmission");
                if (const json* f = number(*t, "transmissionFactor", tw))
                    if (!(f->get<double>() >= 0.0 && f->get<double>() <= 1.0))
                        error(join(tw, "transmissionFactor"), numberText(*f) + " must be in [0, 1]");
                textureInfo(*t, "transmissionTexture", tw);
            }
            if (const json* v = object(*ext, "KHR_materials_volume", ew)) {
                const std::string vw = join(ew, "KHR_materials_volume");
                if (const json* f = number(*v, "thicknessFactor", vw))
                    if (f->get<double>() < 0.0) error(join(vw, "thicknessFactor"), numberText(*f) + " must be >= 0");
                textureInfo(*v, "thicknessTexture", vw);
                if (const json* d = number(*v, "attenuationDistance", vw))
                    if (!(d->get<double>() > 0.0))
                        error(join(vw, "attenuationDistance"), numberText(*d) + " must be > 0 (leave it out for no absorption)");
                if (const json* c = numbers(*v, "attenuationColor", vw, 3, 3))
                    for (size_t i = 0; i < 3; ++i)
                        if (!((*c)[i].get<double>() >= 0.0 && (*c)[i].get<double>() <= 1.0))
                            error(item(join(vw, "attenuationColor"), i), numberText((*c)[i]) + " must be in [0, 1]");
            }
            object(*ext, "KHR_materials_unlit", ew);
        }
    }

    void node(const json& n, const std::string& w) {
        string(n, "name", w);
        index(n, "camera", w);
        index(n, "mesh", w);
        index(n, "skin", w);
        indexArray(n, "children", w);
        numbers(n, "matrix", w, 16, 16);
        numbers(n, "rotation", w, 4, 4);
        numbers(n, "scale", w, 3, 3);
        numbers(n, "translation", w, 3, 3);
        numbers(n, "weights", w, 1, SIZE_MAX);
        if (const json* ext = object(n, "extensions", w))
            if (const json* l = object(*ext, "KHR_lights_punctual", join(w, "extensions")))
                index(*l, "light", join(w, "extensions.KHR_lights_punctual"), true);
    }

    void attributes(const json& obj, const char* key, const std::string& at, bool required) {
        const json* a = object(obj, key, at, required);
        if (!a) return;
        for (auto it = a->begin(); it != a->end(); ++it) indexValue(it.value(), join(join(at, key), it.key()));
    }

    void primitive(const json& p, const std::string& w) {
        attributes(p, "attributes", w, true);
        index(p, "indices", w);
        index(p, "material", w);
        enumInteger(p, "mode", w, {0, 1, 2, 3, 4, 5, 6});
        objects(p, "targets", w, [&](const json& t, const std::string& tw) {
            for (auto it = t.begin(); it != t.end(); ++it) indexValue(it.value(), join(tw, it.key()));
        });
        if (const json* ext = object(p, "extensions", w))
            if (const json* v = object(*ext, "KHR_materials_variants", join(w, "extensions"))) {
                const std::string vw = join(w, "extensions.KHR_materials_variants");
                objects(*v, "mappings", vw, [&](const json& m, const std::string& mw) {
                    index(m, "material", mw, true);
                    indexArray(m, "variants", mw);
                    if (!m.count("variants")) error(join(mw, "variants"), "missing (the extension requires it)");
                    string(m, "name", mw);
                }, true);
            }
    }

    void accessor(const json& a, const std::string& w) {
        string(a, "name", w);
        index(a, "bufferView", w);
        integer(a, "byteOffset", w, 0, INT64_MAX);
        enumInteger(a, "componentType", w, {5120, 5121, 5122, 5123, 5125, 5126}, true);
        boolean(a, "normalized", w);
        integer(a, "count", w, 1, INT64_MAX, true);
        enumString(a, "type", w, {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"}, true);
        // max and min hold one number per component of `type`.
        static const std::pair<const char*, size_t> kComponents[] = {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4},
                                                                     {"MAT2", 4},   {"MAT3", 9}, {"MAT4", 16}};
        size_t components = 0;
        const auto type = a.find("type");
        for (const auto& [name, n] : kComponents)
            if (type != a.end() && type->is_string() && type->get<std::string>() == name) components = n;
        leniently([&] {
            for (const char* bound : {"max", "min"}) {
                if (components) numbers(a, bound, w, components, components);
                else numbers(a, bound, w, 1, 16);
            }
        });
        // Sparse storage: `count` indices and values replacing elements of the dense data.
        if (const json* sp = object(a, "sparse", w)) {
            const std::string sw = join(w, "sparse");
            integer(*sp, "count", sw, 1, INT64_MAX, true);
            const auto count = sp->find("count"), total = a.find("count");
            if (count != sp->end() && total != a.end() && count->is_number_integer() && total->is_number_integer() &&
                integerWithin(*count, 1, INT64_MAX) && integerWithin(*total, 1, INT64_MAX) && count->get<int64_t>() > total->get<int64_t>())
                error(join(sw, "count"), numberText(*count) + " is more than the accessor's count " + numberText(*total));
            if (const json* idx = object(*sp, "indices", sw, true)) {
                const std::string iw = join(sw, "indices");
                index(*idx, "bufferView", iw, true);
                integer(*idx, "byteOffset", iw, 0, INT32_MAX);
                enumInteger(*idx, "componentType", iw, {5121, 5123, 5125}, true);
            }
            if (const json* val = object(*sp, "values", sw, true)) {
                const std::string vw = join(sw, "values");
                index(*val, "bufferView", vw, true);
                integer(*val, "byteOffset", vw, 0, INT32_MAX);
            }
        }
    }

    void camera(const json& c, const std::string& w) {
        string(c, "name", w);
        enumString(c, "type", w, {"perspective", "orthographic"}, true);
        const auto type = c.find("type");
        const bool perspective = type != c.end() && type->is_string() && type->get<std::string>() == "perspective";
        if (const json* p = object(c, "perspective", w, perspective)) {
            const std::string pw = join(w, "perspective");
            positive(*p, "yfov", pw, true);
            positive(*p, "znear", pw, true);
            positive(*p, "zfar", pw, false);
            positive(*p, "aspectRatio", pw, false);
        }
        if (const json* o = object(c, "orthographic", w, !perspective && type != c.end())) {
            const std::string ow = join(w, "orthographic");
            number(*o, "xmag", ow, true);
            number(*o, "ymag", ow, true);
            positive(*o, "zfar", ow, true);
            positive(*o, "znear", ow, true, true);
        }
    }

    void light(const json& l, const std::string& w) {
        string(l, "name", w);
        enumString(l, "type", w, {"directional", "point", "spot"}, true);
        // Colours above 1 are kept (a colour times an intensity is what the file means); negative
        // light is refused.
        if (const json* c = numbers(l, "color", w, 3, 3))
            for (size_t i = 0; i < 3; ++i)
                if ((*c)[i].get<double>() < 0.0) error(item(join(w, "color"), i), numberText((*c)[i]) + " must be >= 0");
        positive(l, "intensity", w, false, true);
        positive(l, "range", w, false);
        const auto type = l.find("type");
        const bool spot = type != l.end() && type->is_string() && type->get<std::string>() == "spot";
        if (const json* s = object(l, "spot", w, spot)) {
            number(*s, "innerConeAngle", join(w, "spot"));  // their ranges: the loader's checks
            number(*s, "outerConeAngle", join(w, "spot"));
        }
    }

    void document(const json& root) {
        if (!root.is_object()) {
            error("(document)", "expected an object, got " + describe(root));
            return;
        }
        if (const json* asset = object(root, "asset", "", true)) {
            // glTF 1.0 files differ throughout (named scenes, techniques): say so before anything else.
            const auto version = asset->find("version");
            if (version != asset->end() && !(version->is_string() && version->get<std::string>().rfind("2.", 0) == 0)) {
                error("asset.version", (version->is_string() ? quoteUserText(version->get<std::string>(), 24) : describe(*version)) +
                                           " is not a glTF 2 version: lightpass reads glTF 2.0");
                return;
            }
            string(*asset, "version", "asset", true);
            string(*asset, "minVersion", "asset");
            string(*asset, "generator", "asset");
            string(*asset, "copyright", "asset");
        }
        index(root, "scene", "");
        for (const char* key : {"extensionsUsed", "extensionsRequired"}) {
            const json* v = member(root, key, "", false);
            if (!v || !expect(*v, key, v->is_array(), "an array of strings")) continue;
            for (size_t i = 0; i < v->size(); ++i) expect((*v)[i], item(key, i), (*v)[i].is_string(), "a string");
        }
        objects(root, "scenes", "", [&](const json& s, const std::string& w) {
            string(s, "name", w);
            indexArray(s, "nodes", w);
        });
        objects(root, "nodes", "", [&](const json& n, const std::string& w) { node(n, w); });
        objects(root, "meshes", "", [&](const json& m, const std::string& w) {
            string(m, "name", w);
            objects(m, "primitives", w, [&](const json& p, const std::string& pw) { primitive(p, pw); }, true, 1);
            numbers(m, "weights", w, 1, SIZE_MAX);
        });
        objects(root, "accessors", "", [&](const json& a, const std::string& w) { accessor(a, w); });
        objects(root, "bufferViews", "", [&](const json& v, const std::string& w) {
            string(v, "name", w);
            index(v, "buffer", w, true);
            integer(v, "byteOffset", w, 0, INT64_MAX);
            integer(v, "byteLength", w, 1, INT64_MAX, true);
            // 0 (glTF 1.0's "tightly packed", still written by some exporters) reads as packed.
            const auto stride = v.find("byteStride");
            if (stride != v.end() && stride->is_number_integer() && integerWithin(*stride, 0, 0))
                warning(join(w, "byteStride"), "0 is outside 4..252; read as tightly packed");
            else
                integer(v, "byteStride", w, 4, 252);
            enumInteger(v, "target", w, {34962, 34963});
        });
        objects(root, "buffers", "", [&](const json& b, const std::string& w) {
            string(b, "name", w);
            string(b, "uri", w);
            integer(b, "byteLength", w, 1, INT64_MAX, true);
        });
        objects(root, "materials", "", [&](const json& m, const std::string& w) { material(m, w); });
        objects(root, "textures", "", [&](const json& t, const std::string& w) {
            string(t, "name", w);
            index(t, "sampler", w);
            index(t, "source", w);
        });
        objects(root, "images", "", [&](const json& i, const std::string& w) {
            string(i, "name", w);
            string(i, "uri", w);
            string(i, "mimeType", w);
            index(i, "bufferView", w);
            const bool uri = i.contains("uri"), view = i.contains("bufferView");
            if (uri == view) error(w, uri ? "has both a uri and a bufferView (the schema allows one)" : "has neither a uri nor a bufferView");
        });
        objects(root, "samplers", "", [&](const json& s, const std::string& w) {
            // The loader keeps only valid filters and wraps (Loader::sampler); the rest sample as
            // textures without a sampler do.
            leniently([&] {
                string(s, "name", w);
                enumInteger(s, "magFilter", w, kGltfMagFilters);
                enumInteger(s, "minFilter", w, kGltfMinFilters);
                enumInteger(s, "wrapS", w, kGltfSamplerWraps);
                enumInteger(s, "wrapT", w, kGltfSamplerWraps);
            }, "ignored (the default is used: repeat, trilinear)");
        });
        objects(root, "cameras", "", [&](const json& c, const std::string& w) { camera(c, w); });
        // Not read by lightpass (a skinned mesh is drawn in its bind pose), but what tinygltf refuses
        // is named here as the schema words it.
        objects(root, "skins", "", [&](const json& k, const std::string& w) {
            index(k, "inverseBindMatrices", w);
            index(k, "skeleton", w);
            indexArray(k, "joints", w);
            member(k, "joints", w, true);
        });
        objects(root, "animations", "", [&](const json& an, const std::string& w) {
            objects(an, "channels", w, [&](const json& c, const std::string& cw) {
                index(c, "sampler", cw, true);
                if (const json* t = object(c, "target", cw, true)) {
                    index(*t, "node", join(cw, "target"));  // optional: a pointer extension may say what moves
                    string(*t, "path", join(cw, "target"), true);
                }
            }, true, 1);
            objects(an, "samplers", w, [&](const json& sm, const std::string& sw) {
                index(sm, "input", sw, true);
                index(sm, "output", sw, true);
                enumString(sm, "interpolation", sw, {"LINEAR", "STEP", "CUBICSPLINE"});
            }, true, 1);
        });
        if (const json* ext = object(root, "extensions", "")) {
            if (const json* lights = object(*ext, "KHR_lights_punctual", "extensions"))
                objects(*lights, "lights", "extensions.KHR_lights_punctual", [&](const json& l, const std::string& w) { light(l, w); }, true);
            if (const json* variants = object(*ext, "KHR_materials_variants", "extensions"))
                objects(*variants, "variants", "extensions.KHR_materials_variants",
                        [&](const json& v, const std::string& w) { string(v, "name", w, true); }, true);
        }
        // Only on a document whose types are right (the walk below trusts them).
        if (std::none_of(issues.begin(), issues.end(), [](const GltfSchemaIssue& i) { return i.error; })) primitiveIndices(root);
    }

    // A primitive's `indices`: an accessor that exists and has a bufferView (tinygltf, through which
    // lightpass reads glTF, refuses a sparse index accessor without one, in words that name neither),
    // unless a KHR_draco_mesh_compression stream holds its data (decoded after tinygltf).
    void primitiveIndices(const json& root) {
        const auto meshes = root.find("meshes"), accessors = root.find("accessors");
        if (meshes == root.end()) return;
        const size_t accessorCount = accessors == root.end() ? 0 : accessors->size();
        for (size_t m = 0; m < meshes->size(); ++m) {
            const json& primitives = (*meshes)[m]["primitives"];
            for (size_t p = 0; p < primitives.size(); ++p) {
                const auto indices = primitives[p].find("indices");
                if (indices == primitives[p].end()) continue;
                const auto extensions = primitives[p].find("extensions");
                const bool draco = extensions != primitives[p].end() && extensions->is_object() &&
                                   extensions->contains("KHR_draco_mesh_compression");
                const std::string where = "meshes[" + std::to_string(m) + "].primitives[" + std::to_string(p) + "].indices";
                const size_t a = indices->get<size_t>();
                if (a >= accessorCount)
                    error(where, "accessor " + std::to_string(a) + " does not exist (" + std::to_string(accessorCount) + " accessors)");
                else if (!draco && !(*accessors)[a].contains("bufferView"))
                    error(where + " (accessors[" + std::to_string(a) + "])", "has no bufferView; an index accessor without one is not supported");
            }
        }
    }
};

}  // namespace

std::vector<GltfSchemaIssue> checkGltfSchema(const nlohmann::json& root) {
    Checker c;
    c.document(root);
    return c.issues;
}

}  // namespace lp
