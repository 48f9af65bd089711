// SPDX-License-Identifier: MIT
#include "scene/ply_file.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "scene/palette.h"

namespace occu {

namespace {

[[noreturn]] void refuse(const std::string &path, const std::string &why)
{
    throw std::runtime_error("cannot read scene '" + path + "': PLY: " + why);
}

enum class Type { none, int8, uint8, int16, uint16, int32, uint32, float32, float64 };

Type type_named(const std::string &t)
{
    static const std::pair<const char *, Type> names[] = {
        {"char", Type::int8},     {"int8", Type::int8},       {"uchar", Type::uint8},  {"uint8", Type::uint8},
        {"short", Type::int16},   {"int16", Type::int16},     {"ushort", Type::uint16}, {"uint16", Type::uint16},
        {"int", Type::int32},     {"int32", Type::int32},     {"uint", Type::uint32},  {"uint32", Type::uint32},
        {"float", Type::float32}, {"float32", Type::float32}, {"double", Type::float64}, {"float64", Type::float64}};
    for (const auto &[name, type] : names)
        if (t == name)
            return type;
    return Type::none;
}

std::size_t size_of(Type t)
{
    switch (t) {
    case Type::int8: case Type::uint8: return 1;
    case Type::int16: case Type::uint16: return 2;
    case Type::int32: case Type::uint32: case Type::float32: return 4;
    case Type::float64: return 8;
    case Type::none: break;
    }
    return 0;
}

bool integer_type(Type t) { return t != Type::none && t != Type::float32 && t != Type::float64; }

struct Property {
    std::string name;
    Type type = Type::none;        // of the value, or of a list's items
    Type length_type = Type::none; // a list's length; none: not a list
};

struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> properties;
    // The fewest bytes (binary) or values (ASCII) an instance takes.
    std::size_t least_bytes() const
    {
        std::size_t s = 0;
        for (const Property &p : properties)
            s += size_of(p.length_type != Type::none ? p.length_type : p.type);
        return s;
    }
};

std::vector<std::string> words_of(const char *begin, const char *end)
{
    std::vector<std::string> words;
    for (const char *p = begin; p < end;) {
        while (p < end && (*p == ' ' || *p == '\t'))
            ++p;
        const char *q = p;
        while (q < end && *q != ' ' && *q != '\t')
            ++q;
        if (q > p)
            words.emplace_back(p, q);
        p = q;
    }
    return words;
}

// A letter or '_' first, then letters, digits, '_' or '-'.
bool identifier(const std::string &w)
{
    if (w.empty() || !(std::isalpha(static_cast<unsigned char>(w[0])) || w[0] == '_'))
        return false;
    return std::all_of(w.begin(), w.end(),
                       [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'; });
}

// A whole number of at most 10 digits, at most 2^32 - 1.
bool whole_number(const std::string &w, std::uint64_t &value)
{
    if (w.empty() || w.size() > 10 || w.find_first_not_of("0123456789") != std::string::npos)
        return false;
    value = std::stoull(w);
    return value <= 0xffffffffull;
}

// The lines of bytes[at, n), each without its '\n' and a '\r' before it.
struct Lines {
    const std::vector<char> &bytes;
    std::size_t at;
    bool next(const char *&begin, const char *&end)
    {
        if (at >= bytes.size())
            return false;
        const char *data = bytes.data();
        const void *nl = std::memchr(data + at, '\n', bytes.size() - at);
        begin = data + at;
        end = nl ? static_cast<const char *>(nl) : data + bytes.size();
        at = std::size_t(end - data) + (nl ? 1 : 0);
        if (end > begin && end[-1] == '\r')
            --end;
        return true;
    }
};

struct Header {
    bool binary = false, big_endian = false;
    std::vector<Element> elements;
    std::size_t data_start = 0;
};

Header read_header(const std::string &path, const std::vector<char> &bytes, std::vector<std::string> &warnings)
{
    Header h;
    Lines lines{bytes, 0};
    const char *b, *e;
    if (!lines.next(b, e) || words_of(b, e) != std::vector<std::string>{"ply"})
        refuse(path, "the first line is not 'ply'");
    if (!lines.next(b, e))
        refuse(path, "the header has no end_header line");
    const std::vector<std::string> format = words_of(b, e);
    if (format.size() != 3 || format[0] != "format" || format[2] != "1.0" ||
        (format[1] != "ascii" && format[1] != "binary_little_endian" && format[1] != "binary_big_endian"))
        refuse(path, "the second line is not a format line ('format ascii|binary_little_endian|binary_big_endian "
                     "1.0'): '" + std::string(b, std::min<std::size_t>(std::size_t(e - b), 60)) + "'");
    h.binary = format[1] != "ascii";
    h.big_endian = format[1] == "binary_big_endian";
    for (;;) {
        if (!lines.next(b, e))
            refuse(path, "the header has no end_header line");
        const std::vector<std::string> w = words_of(b, e);
        auto bad = [&]() {
            refuse(path, "a header line that is not PLY's: '" + std::string(b, std::min<std::size_t>(std::size_t(e - b), 60)) + "'");
        };
        if (w.empty() || w[0] == "comment" || w[0] == "obj_info")
            continue;
        if (w[0] == "end_header") {
            if (w.size() != 1)
                bad();
            break;
        }
        if (w[0] != "element" && w[0] != "property" && w[0] != "ply" && w[0] != "format") {
            // Old exporters wrote comments without 'comment' (Blender 2.4's
            // "Created by Blender3D ..."): read as one, and said.
            warnings.push_back("scene '" + path + "': PLY: the header line '" +
                               std::string(b, std::min<std::size_t>(std::size_t(e - b), 60)) +
                               "' is not PLY's; read as a comment");
            continue;
        }
        if (w[0] == "element") {
            std::uint64_t count = 0;
            if (w.size() != 3 || !identifier(w[1]) || !whole_number(w[2], count))
                bad();
            h.elements.push_back({w[1], count, {}});
        } else if (w[0] == "property" && !h.elements.empty()) {
            Property p;
            if (w.size() == 3 && type_named(w[1]) != Type::none && identifier(w[2]))
                p = {w[2], type_named(w[1]), Type::none};
            else if (w.size() == 5 && w[1] == "list" && integer_type(type_named(w[2])) &&
                     type_named(w[3]) != Type::none && identifier(w[4]))
                p = {w[4], type_named(w[3]), type_named(w[2])};
            else
                bad();
            h.elements.back().properties.push_back(p);
        } else {
            bad();
        }
    }
    if (h.elements.empty())
        refuse(path, "the header declares no element");
    h.data_start = lines.at;
    return h;
}

// One binary value of type t at p (size_of(t) bytes there).
double binary_value(Type t, const char *p, bool big_endian)
{
    unsigned char b[8];
    const std::size_t n = size_of(t);
    std::memcpy(b, p, n);
    const std::uint16_t probe = 1;
    const bool host_big = *reinterpret_cast<const unsigned char *>(&probe) == 0;
    if (big_endian != host_big)
        std::reverse(b, b + n);
    switch (t) {
    case Type::int8: { std::int8_t v; std::memcpy(&v, b, 1); return v; }
    case Type::uint8: { std::uint8_t v; std::memcpy(&v, b, 1); return v; }
    case Type::int16: { std::int16_t v; std::memcpy(&v, b, 2); return v; }
    case Type::uint16: { std::uint16_t v; std::memcpy(&v, b, 2); return v; }
    case Type::int32: { std::int32_t v; std::memcpy(&v, b, 4); return v; }
    case Type::uint32: { std::uint32_t v; std::memcpy(&v, b, 4); return v; }
    case Type::float32: { float v; std::memcpy(&v, b, 4); return double(v); }
    case Type::float64: { double v; std::memcpy(&v, b, 8); return v; }
    case Type::none: break;
    }
    return 0.0;
}

// Where the values of one instance come from: the binary data, or one line
// of the ASCII data.
class ValueSource {
public:
    ValueSource(const std::string &path, const Header &h, const std::vector<char> &bytes)
        : path_(path), h_(h), bytes_(bytes), at_(h.data_start), lines_{bytes, h.data_start}
    {
    }

    void begin_instance(std::uint64_t instance, std::size_t element)
    {
        instance_ = instance;
        element_ = element;
        if (h_.binary)
            return;
        const char *b, *e;
        if (!lines_.next(b, e))
            refuse(path_, "the data ends before instance " + std::to_string(instance) + " of element " +
                              std::to_string(element));
        ++line_;
        tokens_ = words_of(b, e);
        next_token_ = 0;
    }

    double value(Type t)
    {
        if (h_.binary) {
            const std::size_t n = size_of(t);
            if (bytes_.size() - at_ < n)
                refuse(path_, "the binary data ends inside instance " + std::to_string(instance_) + " of element " +
                                  std::to_string(element_) + " (" + std::to_string(h_.elements[element_].count) +
                                  " declared)");
            const double v = binary_value(t, bytes_.data() + at_, h_.big_endian);
            at_ += n;
            return v;
        }
        if (next_token_ == tokens_.size())
            short_line();
        const std::string &token = tokens_[next_token_++];
        char *end = nullptr;
        const double v = std::strtod(token.c_str(), &end);
        if (*end)
            refuse(path_, "data line " + std::to_string(line_) + ": a value that is not a number: '" +
                              token.substr(0, 20) + "'");
        return v;
    }

    // A list's length, checked against what is left for its items.
    std::uint64_t list_length(Type length_type, Type item_type)
    {
        std::uint64_t items = 0;
        if (h_.binary) {
            const double v = value(length_type);
            items = v < 0 ? std::uint64_t(-1) : std::uint64_t(v);
            if (items > (bytes_.size() - at_) / size_of(item_type))
                refuse(path_, "a list of " + std::to_string(items) + " items in instance " + std::to_string(instance_) +
                                  " of element " + std::to_string(element_) + " runs past the end of the file");
            return items;
        }
        if (next_token_ == tokens_.size())
            short_line();
        const std::string &token = tokens_[next_token_++];
        if (!whole_number(token, items))
            refuse(path_, "data line " + std::to_string(line_) + ": a list length that is not a whole number: '" +
                              token.substr(0, 20) + "'");
        if (items > tokens_.size() - next_token_)
            short_line();
        return items;
    }

    // What is left after the header, for bounding element counts.
    std::size_t bytes_left() const { return bytes_.size() - at_; }

private:
    [[noreturn]] void short_line() const
    {
        refuse(path_, "data line " + std::to_string(line_) + " (instance " + std::to_string(instance_) +
                          " of element " + std::to_string(element_) + ") holds fewer values than its properties");
    }

    const std::string &path_;
    const Header &h_;
    const std::vector<char> &bytes_;
    std::size_t at_;
    Lines lines_;
    std::size_t line_ = 0;
    std::vector<std::string> tokens_;
    std::size_t next_token_ = 0;
    std::uint64_t instance_ = 0;
    std::size_t element_ = 0;
};

int index_of(const Element &e, std::initializer_list<const char *> names)
{
    for (const char *name : names)
        for (std::size_t i = 0; i < e.properties.size(); ++i)
            if (e.properties[i].name == name && e.properties[i].length_type == Type::none)
                return int(i);
    return -1;
}

}  // namespace

Mesh read_ply(const std::string &path, const std::vector<char> &bytes, std::vector<std::string> &warnings)
{
    const Header h = read_header(path, bytes, warnings);
    ValueSource source(path, h, bytes);

    // Counts the data cannot hold are refused before anything is sized by
    // them: an instance takes at least one byte a value (ASCII: a digit and
    // a separator, and a line) or its values' sizes (binary).
    {
        std::uint64_t least = 0;
        for (const Element &e : h.elements) {
            const std::uint64_t each = h.binary ? e.least_bytes() : std::max<std::size_t>(2 * e.properties.size(), 1);
            least += e.properties.empty() ? 0 : e.count * each;
        }
        if (least > source.bytes_left())
            refuse(path, "the header's element counts need at least " + std::to_string(least) + " bytes but " +
                             std::to_string(source.bytes_left()) + " follow it");
    }

    Mesh mesh;
    mesh.color = building_colours(0, 0.5f, 0.0f).wall;
    std::vector<glm::vec3> colours;
    std::vector<std::uint64_t> polygon;               // one face's indices
    std::vector<std::uint32_t> polygon_sizes;
    std::vector<std::uint64_t> polygon_indices;       // every face's, one after another
    std::uint64_t faces = 0, empty_faces = 0;
    bool have_vertices = false;
    std::vector<double> values;
    for (std::size_t ei = 0; ei < h.elements.size(); ++ei) {
        const Element &e = h.elements[ei];
        const bool vertices = e.name == "vertex" && !have_vertices;
        const bool face_element = e.name == "face";
        const int x = index_of(e, {"x"}), y = index_of(e, {"y"}), z = index_of(e, {"z"});
        const int r = index_of(e, {"red", "diffuse_red"}), g = index_of(e, {"green", "diffuse_green"}),
                  b = index_of(e, {"blue", "diffuse_blue"});
        int face_list = -1;
        for (std::size_t i = 0; i < e.properties.size(); ++i)
            if (e.properties[i].length_type != Type::none &&
                (e.properties[i].name == "vertex_indices" || e.properties[i].name == "vertex_index"))
                face_list = int(i);
        if (vertices) {
            if (x < 0 || y < 0 || z < 0)
                refuse(path, "the vertex element has no x, y and z properties");
            have_vertices = true;
            mesh.positions.reserve(std::size_t(e.count));
        }
        const bool with_colour = vertices && r >= 0 && g >= 0 && b >= 0;
        if (e.properties.empty())
            continue;
        values.assign(e.properties.size(), 0.0);
        for (std::uint64_t i = 0; i < e.count; ++i) {
            source.begin_instance(i, ei);
            for (std::size_t p = 0; p < e.properties.size(); ++p) {
                const Property &prop = e.properties[p];
                if (prop.length_type == Type::none) {
                    values[p] = source.value(prop.type);
                    continue;
                }
                const std::uint64_t items = source.list_length(prop.length_type, prop.type);
                const bool keep = face_element && int(p) == face_list;
                polygon.clear();
                for (std::uint64_t k = 0; k < items; ++k) {
                    const double v = source.value(prop.type);
                    if (keep)
                        polygon.push_back(v >= 0 && v <= 4294967295.0 && std::floor(v) == v ? std::uint64_t(v)
                                                                                           : ~std::uint64_t(0));
                }
                if (keep) {
                    ++faces;
                    empty_faces += polygon.empty();
                    polygon_sizes.push_back(std::uint32_t(polygon.size()));
                    polygon_indices.insert(polygon_indices.end(), polygon.begin(), polygon.end());
                }
            }
            if (vertices) {
                mesh.positions.emplace_back(float(values[std::size_t(x)]), float(values[std::size_t(y)]),
                                            float(values[std::size_t(z)]));
                if (with_colour) {
                    const float scale = integer_type(e.properties[std::size_t(r)].type) ? 1.0f / 255.0f : 1.0f;
                    const glm::vec3 c = scale * glm::vec3{float(values[std::size_t(r)]), float(values[std::size_t(g)]),
                                                          float(values[std::size_t(b)])};
                    colours.push_back(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z)
                                          ? glm::clamp(c, 0.0f, 1.0f)
                                          : mesh.color);
                }
            }
        }
    }
    if (!have_vertices)
        refuse(path, "the file has no vertex element");
    require_finite_vertices(mesh, 0, "scene '" + path + "'");
    if (empty_faces)
        refuse(path, std::to_string(empty_faces) + " of its " + std::to_string(faces) + " faces have no indices");

    // Faces into triangles, fans from each face's first vertex.
    const std::uint64_t vertex_count = mesh.positions.size();
    std::uint64_t outside = 0, short_faces = 0;
    std::size_t at = 0;
    for (std::uint32_t n : polygon_sizes) {
        const std::uint64_t *f = polygon_indices.data() + at;
        at += n;
        if (std::any_of(f, f + n, [&](std::uint64_t v) { return v >= vertex_count; })) {
            ++outside;
            continue;
        }
        if (n < 3) {
            ++short_faces;
            continue;
        }
        for (std::uint32_t k = 1; k + 1 < n; ++k) {
            mesh.indices.push_back(std::uint32_t(f[0]));
            mesh.indices.push_back(std::uint32_t(f[k]));
            mesh.indices.push_back(std::uint32_t(f[k + 1]));
        }
    }
    if (outside)
        refuse(path, std::to_string(outside) + " of its " + std::to_string(faces) + " faces index beyond its " +
                         std::to_string(vertex_count) + " vertices");
    if (short_faces)
        warnings.push_back("scene '" + path + "': " + std::to_string(short_faces) + " of its " + std::to_string(faces) +
                           " faces have one or two vertices (points or lines); dropped");
    if (!colours.empty())
        mesh.colors = std::move(colours);

    // Smooth normals: each vertex the area-weighted sum of its triangles'.
    mesh.normals.assign(mesh.positions.size(), glm::vec3(0.0f));
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
        const glm::vec3 n = glm::cross(mesh.positions[i1] - mesh.positions[i0], mesh.positions[i2] - mesh.positions[i0]);
        mesh.normals[i0] += n;
        mesh.normals[i1] += n;
        mesh.normals[i2] += n;
    }
    for (glm::vec3 &n : mesh.normals) {
        const float length = glm::length(n);
        n = length > 0.0f && std::isfinite(length) ? n / length : glm::vec3(0.0f, 1.0f, 0.0f);
    }
    mesh.update_bounds();
    return mesh;
}

}  // namespace occu
