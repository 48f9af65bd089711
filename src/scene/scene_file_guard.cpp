// SPDX-License-Identifier: MIT
#include "scene/scene_file_guard.h"

#include <assimp/Importer.hpp>
#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <utility>
#include <vector>

namespace occu {

namespace {

[[noreturn]] void refuse(const std::string &path, const std::string &why)
{
    throw std::runtime_error("cannot read scene '" + path + "': " + why);
}

// --- JSON, as rapidjson's default parse reads it (no comments, no NaN,
// one value and white space), nesting at most 64 deep.

struct Json {
    enum Kind { Null, Bool, Number, String, Array, Object } kind = Null;
    bool unsigned_integer = false;  // a number of digits only, below 2^64
    std::uint64_t u = 0;
    std::string text;
    std::vector<Json> items;
    std::vector<std::pair<std::string, Json>> members;

    // The first member named `key` (rapidjson's FindMember), or null.
    const Json *find(const char *key) const
    {
        for (const auto &m : members)
            if (m.first == key)
                return &m.second;
        return nullptr;
    }
};

class JsonParser {
public:
    JsonParser(const char *begin, const char *end) : p_(begin), end_(end) {}

    bool document(Json &out)
    {
        space();
        if (!value(out, 0))
            return false;
        space();
        return p_ == end_;
    }

private:
    const char *p_, *end_;

    bool more() const { return p_ != end_; }
    static bool digit(char c) { return c >= '0' && c <= '9'; }
    void space()
    {
        while (more() && (*p_ == ' ' || *p_ == '\t' || *p_ == '\n' || *p_ == '\r'))
            ++p_;
    }
    bool literal(const char *word)
    {
        const std::size_t n = std::strlen(word);
        if (std::size_t(end_ - p_) < n || std::memcmp(p_, word, n) != 0)
            return false;
        p_ += n;
        return true;
    }
    bool value(Json &out, int depth)
    {
        if (depth > 64 || !more())
            return false;
        switch (*p_) {
        case '{': return object(out, depth);
        case '[': return array(out, depth);
        case '"': out.kind = Json::String; return string(out.text);
        case 't': out.kind = Json::Bool; return literal("true");
        case 'f': out.kind = Json::Bool; return literal("false");
        case 'n': out.kind = Json::Null; return literal("null");
        default: return number(out);
        }
    }
    bool object(Json &out, int depth)
    {
        out.kind = Json::Object;
        ++p_;
        space();
        if (more() && *p_ == '}')
            return ++p_, true;
        for (;;) {
            std::string key;
            if (!more() || *p_ != '"' || !string(key))
                return false;
            space();
            if (!more() || *p_ != ':')
                return false;
            ++p_;
            space();
            out.members.emplace_back(std::move(key), Json());
            if (!value(out.members.back().second, depth + 1))
                return false;
            space();
            if (!more())
                return false;
            if (*p_ == '}')
                return ++p_, true;
            if (*p_ != ',')
                return false;
            ++p_;
            space();
        }
    }
    bool array(Json &out, int depth)
    {
        out.kind = Json::Array;
        ++p_;
        space();
        if (more() && *p_ == ']')
            return ++p_, true;
        for (;;) {
            out.items.emplace_back();
            if (!value(out.items.back(), depth + 1))
                return false;
            space();
            if (!more())
                return false;
            if (*p_ == ']')
                return ++p_, true;
            if (*p_ != ',')
                return false;
            ++p_;
            space();
        }
    }
    bool hex4(unsigned &out)
    {
        out = 0;
        for (int k = 0; k < 4; ++k, ++p_) {
            if (!more())
                return false;
            const char c = *p_;
            const int d = digit(c) ? c - '0' : (c >= 'a' && c <= 'f') ? c - 'a' + 10 : (c >= 'A' && c <= 'F') ? c - 'A' + 10 : -1;
            if (d < 0)
                return false;
            out = out * 16 + unsigned(d);
        }
        return true;
    }
    static void utf8(unsigned cp, std::string &out)
    {
        if (cp < 0x80) {
            out += char(cp);
        } else if (cp < 0x800) {
            out += char(0xC0 | (cp >> 6));
            out += char(0x80 | (cp & 0x3F));
        } else if (cp < 0x10000) {
            out += char(0xE0 | (cp >> 12));
            out += char(0x80 | ((cp >> 6) & 0x3F));
            out += char(0x80 | (cp & 0x3F));
        } else {
            out += char(0xF0 | (cp >> 18));
            out += char(0x80 | ((cp >> 12) & 0x3F));
            out += char(0x80 | ((cp >> 6) & 0x3F));
            out += char(0x80 | (cp & 0x3F));
        }
    }
    bool string(std::string &out)
    {
        ++p_;
        while (more()) {
            const unsigned char c = static_cast<unsigned char>(*p_++);
            if (c == '"')
                return true;
            if (c < 0x20)
                return false;
            if (c != '\\') {
                out += char(c);
                continue;
            }
            if (!more())
                return false;
            const char e = *p_++;
            switch (e) {
            case '"': case '\\': case '/': out += e; break;
            case 'b': out += '\b'; break;
            case 'f': out += '\f'; break;
            case 'n': out += '\n'; break;
            case 'r': out += '\r'; break;
            case 't': out += '\t'; break;
            case 'u': {
                unsigned cp = 0, low = 0;
                if (!hex4(cp))
                    return false;
                if (cp >= 0xD800 && cp < 0xDC00) {
                    if (!literal("\\u") || !hex4(low) || low < 0xDC00 || low > 0xDFFF)
                        return false;
                    cp = 0x10000 + ((cp - 0xD800) << 10) + (low - 0xDC00);
                } else if (cp >= 0xDC00 && cp < 0xE000) {
                    return false;
                }
                utf8(cp, out);
                break;
            }
            default: return false;
            }
        }
        return false;
    }
    bool number(Json &out)
    {
        out.kind = Json::Number;
        const char *start = p_;
        const bool negative = *p_ == '-';
        if (negative)
            ++p_;
        if (!more() || !digit(*p_))
            return false;
        if (*p_ == '0')
            ++p_;
        else
            while (more() && digit(*p_))
                ++p_;
        bool integer = !negative;
        if (more() && *p_ == '.') {
            ++p_;
            integer = false;
            if (!more() || !digit(*p_))
                return false;
            while (more() && digit(*p_))
                ++p_;
        }
        if (more() && (*p_ == 'e' || *p_ == 'E')) {
            ++p_;
            integer = false;
            if (more() && (*p_ == '+' || *p_ == '-'))
                ++p_;
            if (!more() || !digit(*p_))
                return false;
            while (more() && digit(*p_))
                ++p_;
        }
        if (integer) {
            std::uint64_t v = 0;
            bool fits = true;
            for (const char *q = start; q != p_; ++q) {
                const unsigned d = unsigned(*q - '0');
                if (v > (UINT64_MAX - d) / 10)
                    fits = false;
                else
                    v = v * 10 + d;
            }
            out.unsigned_integer = fits;
            out.u = v;
        }
        return true;
    }
};

// --- glTF 2 ---------------------------------------------------------------

class GltfCheck {
public:
    GltfCheck(const std::string &path, const Json &root, bool binary, std::uint64_t body)
        : path_(path), root_(root), binary_(binary), body_(body)
    {
    }

    void run()
    {
        if (root_.kind != Json::Object)
            no("the JSON document is not an object");
        const Json *asset = root_.find("asset");
        const Json *version = asset ? asset->find("version") : nullptr;
        if (!version || version->kind != Json::String || version->text.empty() || version->text[0] != '2')
            no("asset.version is not 2.x (occu reads glTF 2 only)");
        const std::vector<Json> &buffers = list("buffers");
        std::vector<std::uint64_t> buffer_length;
        for (std::size_t i = 0; i < buffers.size(); ++i)
            buffer_length.push_back(buffer(buffers[i], "buffer " + std::to_string(i), i));
        for (const Json &image : list("images", false))
            if (const Json *uri = image.find("uri"))
                data_uri_length(*uri, "an image");
        const std::vector<Json> &views = list("bufferViews");
        for (std::size_t i = 0; i < views.size(); ++i) {
            const std::string what = "buffer view " + std::to_string(i);
            const std::uint64_t b = index(views[i], "buffer", buffers.size(), what);
            const std::uint64_t end = number(views[i], "byteOffset", what, 0) + number(views[i], "byteLength", what);
            if (end > buffer_length[b])
                no(what + " ends at byte " + std::to_string(end) + " of buffer " + std::to_string(b) + ", which holds " +
                   std::to_string(buffer_length[b]));
            if (views[i].find("byteStride")) {
                const std::uint64_t stride = number(views[i], "byteStride", what);
                if (stride < 4 || stride > 252)
                    no(what + " has byteStride " + std::to_string(stride) + " (glTF allows 4 to 252)");
            }
        }
        const std::vector<Json> &accessors = list("accessors");
        for (std::size_t i = 0; i < accessors.size(); ++i)
            accessor(accessors[i], "accessor " + std::to_string(i), views);
        const std::vector<Json> &meshes = list("meshes");
        for (std::size_t m = 0; m < meshes.size(); ++m) {
            const std::string mesh = "mesh " + std::to_string(m);
            const Json *primitives = meshes[m].find("primitives");
            if (!primitives || primitives->kind != Json::Array)
                no(mesh + " has no primitives array");
            for (std::size_t p = 0; p < primitives->items.size(); ++p)
                primitive(primitives->items[p], mesh + " primitive " + std::to_string(p), accessors);
        }
    }

private:
    const std::string &path_;
    const Json &root_;
    bool binary_;
    std::uint64_t body_;

    [[noreturn]] void no(const std::string &why) const { refuse(path_, "glTF: " + why); }

    // The array `name` of the document, each item an object; empty when
    // absent.
    const std::vector<Json> &list(const char *name, bool objects = true) const
    {
        static const std::vector<Json> none;
        const Json *a = root_.find(name);
        if (!a)
            return none;
        if (a->kind != Json::Array)
            no(std::string(name) + " is not an array");
        for (const Json &item : a->items)
            if (objects && item.kind != Json::Object)
                no(std::string("an item of ") + name + " is not an object");
        return a->items;
    }
    std::uint64_t number(const Json &object, const char *key, const std::string &what, std::int64_t otherwise = -1) const
    {
        const Json *v = object.find(key);
        if (!v) {
            if (otherwise < 0)
                no(what + " has no " + key);
            return std::uint64_t(otherwise);
        }
        if (v->kind != Json::Number || !v->unsigned_integer || v->u > UINT32_MAX)
            no(what + ": " + key + " is not an unsigned 32-bit integer");
        return v->u;
    }
    std::uint64_t index(const Json &object, const char *key, std::size_t size, const std::string &what) const
    {
        const std::uint64_t i = number(object, key, what);
        if (i >= size)
            no(what + ": " + key + " " + std::to_string(i) + " is out of range (" + std::to_string(size) + ")");
        return i;
    }
    // The bytes a data URI holds (-1 for a reference to a file); refuses
    // URIs assimp's parser mishandles.
    std::int64_t data_uri_length(const Json &uri, const std::string &what) const
    {
        if (uri.kind != Json::String)
            no(what + "'s uri is not a string");
        const std::string &s = uri.text;
        if (std::any_of(s.begin(), s.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20; }))
            no(what + "'s uri holds a control character");
        if (s.compare(0, 5, "data:") != 0)
            return -1;
        const std::size_t comma = s.find(',');
        if (comma == std::string::npos || comma > 100)
            no(what + "'s data URI has no ',' within its first 100 characters");
        const std::size_t n = s.size() - comma - 1;
        if (s.substr(0, comma).find(";base64") == std::string::npos)
            return std::int64_t(n);
        if (n % 4 != 0)
            no(what + "'s base64 data is " + std::to_string(n) + " characters long, not a multiple of 4");
        if (n < 4)
            return 0;
        return std::int64_t(n / 4 * 3 - (s[s.size() - 1] == '=') - (s[s.size() - 2] == '='));
    }
    // The buffer's length as assimp sees it, checked against its data.
    std::uint64_t buffer(const Json &b, const std::string &what, std::size_t i) const
    {
        const std::uint64_t stated = number(b, "byteLength", what);
        const Json *uri = b.find("uri");
        if (!uri) {
            const std::uint64_t held = binary_ && i == 0 ? body_ : 0;
            if (stated > held)
                no(what + " has byteLength " + std::to_string(stated) + " but the file holds " + std::to_string(held));
            return stated;
        }
        const std::int64_t held = data_uri_length(*uri, what);
        if (held < 0) {
            // A file next to the scene: assimp opens it and compares sizes.
            const std::string dir = path_.find('/') == std::string::npos ? "" : path_.substr(0, path_.rfind('/') + 1);
            struct stat st;
            if (stat((dir + uri->text).c_str(), &st) == 0 && std::uint64_t(st.st_size) < stated)
                no(what + " has byteLength " + std::to_string(stated) + " but '" + uri->text + "' holds " +
                   std::to_string(st.st_size) + " bytes");
            return stated;
        }
        if (stated > std::uint64_t(held))
            no(what + " has byteLength " + std::to_string(stated) + " but its data URI holds " + std::to_string(held));
        return stated ? stated : std::uint64_t(held);
    }
    void accessor(const Json &a, const std::string &what, const std::vector<Json> &views) const
    {
        if (a.find("sparse"))
            no(what + " is sparse (occu does not read sparse accessors)");
        if (!a.find("bufferView"))
            no(what + " has no bufferView (occu needs each accessor's data in the file)");
        const std::uint64_t v = index(a, "bufferView", views.size(), what);
        std::uint64_t bytes = 0;
        switch (number(a, "componentType", what)) {
        case 5120: case 5121: bytes = 1; break;
        case 5122: case 5123: bytes = 2; break;
        case 5125: case 5126: bytes = 4; break;
        default: no(what + " has an unknown componentType");
        }
        const Json *type = a.find("type");
        static const std::pair<const char *, int> types[] = {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4},
                                                             {"MAT2", 4},   {"MAT3", 9}, {"MAT4", 16}};
        int components = 0;
        for (const auto &t : types)
            if (type && type->kind == Json::String && type->text == t.first)
                components = t.second;
        if (!components)
            no(what + " has an unknown type");
        const std::uint64_t element = bytes * std::uint64_t(components);
        const std::uint64_t count = number(a, "count", what);
        const std::uint64_t offset = number(a, "byteOffset", what, 0);
        const Json &view = views[v];
        const std::uint64_t stride = view.find("byteStride") ? number(view, "byteStride", what) : element;
        const std::uint64_t length = number(view, "byteLength", what);
        if (count > 0 && offset + (count - 1) * stride + element > length)
            no(what + " (" + std::to_string(count) + " elements of " + std::to_string(element) + " bytes from byte " +
               std::to_string(offset) + ") runs past the end of buffer view " + std::to_string(v) + " (" +
               std::to_string(length) + " bytes)");
    }
    std::uint64_t count_of(const std::vector<Json> &accessors, std::uint64_t a) const
    {
        return number(accessors[a], "count", "accessor " + std::to_string(a));
    }
    void references(const Json &attributes, const std::vector<Json> &accessors, const std::string &what) const
    {
        if (attributes.kind != Json::Object)
            no(what + " is not an object");
        for (const auto &m : attributes.members)
            index(attributes, m.first.c_str(), accessors.size(), what);
    }
    void primitive(const Json &p, const std::string &what, const std::vector<Json> &accessors) const
    {
        if (p.kind != Json::Object)
            no(what + " is not an object");
        const std::uint64_t mode = number(p, "mode", what, 4);
        if (mode > 6)
            no(what + " has mode " + std::to_string(mode) + " (glTF has 0 to 6)");
        // No positions: nothing for occu, and assimp 5.2.5 dereferenced
        // null closing a line loop whose every face it dropped (SEGV).
        const Json *attributes = p.find("attributes");
        if (!attributes || !attributes->find("POSITION"))
            no(what + " has no POSITION attribute");
        references(*attributes, accessors, what + " attributes");
        std::uint64_t vertices = count_of(accessors, attributes->find("POSITION")->u);
        if (const Json *targets = p.find("targets")) {
            if (targets->kind != Json::Array)
                no(what + " targets is not an array");
            for (const Json &t : targets->items)
                references(t, accessors, what + " target");
        }
        if (p.find("indices")) {
            const std::uint64_t i = index(p, "indices", accessors.size(), what);
            const Json *type = accessors[i].find("type");
            const std::uint64_t component = number(accessors[i], "componentType", "accessor " + std::to_string(i));
            if (!type || type->text != "SCALAR" || (component != 5121 && component != 5123 && component != 5125))
                no(what + ": its indices, accessor " + std::to_string(i) + ", are not unsigned scalars");
            vertices = count_of(accessors, i);
            // assimp closes an indexed line loop with its first face,
            // which it drops when an index is beyond the vertices: null.
            if (mode == 2)
                no(what + " is an indexed line loop (occu reads triangles; assimp 5.2.5 crashes on some)");
        }
        // assimp makes count - 2 triangles of a strip or fan, count - 1
        // lines of a line strip: 2^64 for fewer vertices.
        const std::uint64_t least = mode == 5 || mode == 6 ? 3 : mode == 2 || mode == 3 ? 2 : 0;
        if (vertices < least)
            no(what + " (mode " + std::to_string(mode) + ") has " + std::to_string(vertices) + " vertices; it needs " +
               std::to_string(least));
    }
};

void guard_gltf(const std::string &path, const std::vector<char> &bytes, bool binary)
{
    std::uint64_t body = 0;
    const char *json = bytes.data(), *json_end = bytes.data() + bytes.size();
    if (binary) {
        auto u32 = [&](std::size_t at) {
            return std::uint32_t(std::uint8_t(bytes[at])) | std::uint32_t(std::uint8_t(bytes[at + 1])) << 8 |
                   std::uint32_t(std::uint8_t(bytes[at + 2])) << 16 | std::uint32_t(std::uint8_t(bytes[at + 3])) << 24;
        };
        if (bytes.size() < 20 || std::memcmp(bytes.data(), "glTF", 4) != 0)
            refuse(path, "GLB: no 'glTF' header");
        if (u32(4) != 2)
            refuse(path, "GLB: version " + std::to_string(u32(4)) + ", not 2 (occu reads glTF 2 only)");
        const std::uint64_t length = u32(12);
        if (u32(16) != 0x4E4F534A || 20 + length > bytes.size())
            refuse(path, "GLB: its first chunk is not JSON of at most the file's length");
        json = bytes.data() + 20;
        json_end = json + length;
        const std::uint64_t bin = 20 + (length + 3) / 4 * 4;
        if (u32(8) >= bin + 8 && bin + 8 <= bytes.size()) {
            body = u32(std::size_t(bin));
            if (bin + 8 + body > bytes.size())
                refuse(path, "GLB: its binary chunk of " + std::to_string(body) + " bytes runs past the end of the file");
        }
    }
    // rapidjson reads the text up to its first NUL.
    json_end = std::find(json, json_end, '\0');
    Json root;
    if (!JsonParser(json, json_end).document(root))
        refuse(path, "glTF: not JSON (or nested more than 64 deep)");
    GltfCheck(path, root, binary, body).run();
}

std::string lower_extension(const std::string &path)
{
    const std::size_t dot = path.rfind('.');
    if (dot == std::string::npos || path.find('/', dot) != std::string::npos)
        return "";
    std::string e = path.substr(dot + 1);
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return e;
}

// assimp's PLY importer claims a file whose first 200 bytes hold "ply".
bool mentions_ply(const std::vector<char> &bytes)
{
    std::string head(bytes.begin(), bytes.begin() + std::ptrdiff_t(std::min<std::size_t>(200, bytes.size())));
    std::transform(head.begin(), head.end(), head.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return head.find("ply") != std::string::npos;
}

}  // namespace

void guard_scene_file(const std::string &path, const std::vector<char> &bytes)
{
    const std::string ext = lower_extension(path);
    // assimp picks the importer by the extension, by the content when no
    // importer claims the extension.
    const bool unclaimed = ext.empty() || !Assimp::Importer().IsExtensionSupported("." + ext);
    const auto first = std::find_if(bytes.begin(), bytes.end(), [](char c) { return !std::isspace(static_cast<unsigned char>(c)); });
    if (ext == "glb")
        guard_gltf(path, bytes, true);
    else if (ext == "gltf" || (unclaimed && first != bytes.end() && *first == '{'))
        guard_gltf(path, bytes, false);
}

bool assimp_would_read_as_ply(const std::string &path, const std::vector<char> &bytes)
{
    const std::string ext = lower_extension(path);
    return ext == "ply" || ((ext.empty() || !Assimp::Importer().IsExtensionSupported("." + ext)) && mentions_ply(bytes));
}

}  // namespace occu
