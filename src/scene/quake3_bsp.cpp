// SPDX-License-Identifier: MIT
#include "scene/quake3_bsp.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>

#include "scene/palette.h"

namespace occu {

namespace {

// The lump directory's order (Proudfoot, "Lumps").
enum Lump {
    entities_lump, textures_lump, planes_lump, nodes_lump, leaves_lump, leaf_faces_lump, leaf_brushes_lump,
    models_lump, brushes_lump, brush_sides_lump, vertices_lump, meshverts_lump, effects_lump, faces_lump,
    lightmaps_lump, light_volumes_lump, visdata_lump, lump_count
};
const char *const lump_names[lump_count] = {"entities", "textures", "planes", "nodes", "leafs", "leaffaces",
                                            "leafbrushes", "models", "brushes", "brushsides", "vertexes",
                                            "meshverts", "effects", "faces", "lightmaps", "lightvols", "visdata"};
// Bytes a record; 1 for the lumps that are not arrays of records.
const std::size_t record_sizes[lump_count] = {1, 72, 16, 36, 48, 4, 4, 40, 12, 8, 44, 4, 72, 104, 128 * 128 * 3, 8, 1};

constexpr std::size_t header_bytes = 8 + 8 * lump_count;

// Surface and content flags (Quake III's surfaceflags.h).
constexpr std::uint32_t surf_sky = 0x4, surf_nodraw = 0x80, surf_alphashadow = 0x10000;
constexpr std::uint32_t contents_water = 0x20, contents_fog = 0x40, contents_translucent = 0x20000000;

// The flat look's sky: one unlit colour, a clear day's.
const glm::vec3 sky_colour{0.52f, 0.68f, 0.88f};

constexpr int face_polygon = 1, face_patch = 2, face_mesh = 3, face_billboard = 4;

// What a level may make at most: beyond it a file (or a patch level)
// asks for more memory than a scene can use.
// (About 40 times the largest of Debian's 100 levels at 8 patch segments;
// the work of reaching it a second or two at worst.)
constexpr std::uint64_t max_vertices = 1u << 22, max_indices = 3u << 22;

// Quake's spawn lift and view height (its game code: SelectSpawnPoint
// raises the player 9 units above the spot; DEFAULT_VIEWHEIGHT 26).
constexpr float spawn_lift_units = 9.0f, view_height_units = 26.0f;

bool finite(const glm::vec3 &v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

class Reader {
public:
    Reader(const std::string &source, const std::vector<char> &bytes) : source_(source), bytes_(bytes) {}

    [[noreturn]] void refuse(const std::string &why) const
    {
        throw std::runtime_error("cannot read scene '" + source_ + "': Quake III BSP: " + why);
    }
    [[noreturn]] void refuse(int lump, const std::string &why) const
    {
        refuse("lump " + std::to_string(lump) + " (" + lump_names[lump] + "): " + why);
    }
    [[noreturn]] void refuse(int lump, std::size_t record, const std::string &why) const
    {
        refuse(lump, "record " + std::to_string(record) + ": " + why);
    }

    void read_header()
    {
        if (bytes_.size() < 4 || std::memcmp(bytes_.data(), "IBSP", 4) != 0)
            refuse("the file does not begin with 'IBSP'");
        if (bytes_.size() < header_bytes)
            refuse("the file is " + std::to_string(bytes_.size()) + " bytes, shorter than the header's " +
                   std::to_string(header_bytes));
        const std::int32_t version = i32(4);
        if (version != 46)
            refuse("version " + std::to_string(version) + " (0x" + hex(std::uint32_t(version)) +
                   "); occu reads version 46 (Quake III Arena's, 0x2e)");
        for (int l = 0; l < lump_count; ++l) {
            const std::int64_t offset = i32(8 + 8 * std::size_t(l)), length = i32(12 + 8 * std::size_t(l));
            if (offset < 0 || length < 0)
                refuse(l, "a negative offset or length in the directory (" + std::to_string(offset) + ", " +
                              std::to_string(length) + ")");
            if (std::uint64_t(offset) + std::uint64_t(length) > bytes_.size())
                refuse(l, "bytes " + std::to_string(offset) + " to " + std::to_string(offset + length) +
                              " lie beyond the end of the file (" + std::to_string(bytes_.size()) + " bytes)");
            if (length % std::int64_t(record_sizes[l]) != 0)
                refuse(l, std::to_string(length) + " bytes are not whole records of " +
                              std::to_string(record_sizes[l]) + " bytes");
            offsets_[l] = std::size_t(offset);
            lengths_[l] = std::size_t(length);
        }
    }

    std::size_t count(int lump) const { return lengths_[lump] / record_sizes[lump]; }
    // Byte `at` of record `record` of `lump`, `size` bytes there.
    std::size_t at(int lump, std::size_t record, std::size_t field) const
    {
        return offsets_[lump] + record * record_sizes[lump] + field;
    }
    std::size_t offset(int lump) const { return offsets_[lump]; }
    std::size_t length(int lump) const { return lengths_[lump]; }

    // Little-endian values at `at` (callers keep `at` + 4 inside the file:
    // the header's checks and count()).
    std::int32_t i32(std::size_t at) const
    {
        const auto *b = reinterpret_cast<const unsigned char *>(bytes_.data() + at);
        return std::int32_t(std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 |
                            std::uint32_t(b[3]) << 24);
    }
    float f32(std::size_t at) const
    {
        const std::uint32_t u = std::uint32_t(i32(at));
        float f;
        std::memcpy(&f, &u, 4);
        return f;
    }
    glm::vec3 vec3(std::size_t at) const { return {f32(at), f32(at + 4), f32(at + 8)}; }
    glm::vec3 ivec3(std::size_t at) const { return glm::vec3(float(i32(at)), float(i32(at + 4)), float(i32(at + 8))); }
    const char *data() const { return bytes_.data(); }

    // A range [first, first + n) that record `record` of `lump` gives into
    // `target`'s records: both non-negative, inside it.
    void require_range(int lump, std::size_t record, const char *what, std::int64_t first, std::int64_t n,
                       int target) const
    {
        require_range(lump, record, what, first, n, count(target), lump_names[target]);
    }
    void require_range(int lump, std::size_t record, const char *what, std::int64_t first, std::int64_t n,
                       std::size_t available, const std::string &of) const
    {
        if (first < 0 || n < 0 || std::uint64_t(first) + std::uint64_t(n) > available)
            refuse(lump, record, std::string(what) + " " + std::to_string(first) + " to " + std::to_string(first + n) +
                                     " lie outside the " + std::to_string(available) + " " + of);
    }

    static std::string hex(std::uint32_t v)
    {
        char s[16];
        std::snprintf(s, sizeof s, "%x", v);
        return s;
    }

private:
    const std::string &source_;
    const std::vector<char> &bytes_;
    std::size_t offsets_[lump_count] = {}, lengths_[lump_count] = {};
};

// The entities lump: { "key" "value" ... } blocks.
struct Entity {
    std::vector<std::pair<std::string, std::string>> pairs;
    const std::string *value(const char *key) const
    {
        for (const auto &[k, v] : pairs)
            if (k == key)
                return &v;
        return nullptr;
    }
};

std::vector<Entity> parse_entities(const Reader &r)
{
    const char *p = r.data() + r.offset(entities_lump);
    const char *const begin = p, *const end = p + r.length(entities_lump);
    std::vector<Entity> out;
    auto where = [&](const char *q) { return "at byte " + std::to_string(q - begin) + ": "; };
    auto skip_space = [&]() {
        while (p < end && (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r'))
            ++p;
    };
    auto quoted = [&](std::string &s) {
        if (p == end || *p != '"')
            r.refuse(entities_lump, where(p) + "a key or value does not begin with '\"'");
        const char *q = static_cast<const char *>(std::memchr(p + 1, '"', std::size_t(end - p - 1)));
        if (!q)
            r.refuse(entities_lump, where(p) + "a string runs to the end of the lump without its closing '\"'");
        s.assign(p + 1, q);
        if (s.find('\0') != std::string::npos)
            r.refuse(entities_lump, where(p) + "a string holds a NUL byte");
        p = q + 1;
    };
    for (;;) {
        skip_space();
        // The compiler ends the text with a NUL.
        if (p == end || (*p == '\0' && std::all_of(p, end, [](char c) { return c == '\0'; })))
            break;
        if (*p != '{')
            r.refuse(entities_lump, where(p) + "expected '{' opening an entity");
        ++p;
        Entity e;
        for (;;) {
            skip_space();
            if (p == end)
                r.refuse(entities_lump, where(p) + "entity " + std::to_string(out.size()) + " has no closing '}'");
            if (*p == '}') {
                ++p;
                break;
            }
            std::string key, value;
            quoted(key);
            skip_space();
            quoted(value);
            e.pairs.emplace_back(std::move(key), std::move(value));
        }
        out.push_back(std::move(e));
    }
    return out;
}

// `n` finite numbers separated by spaces, and nothing else.
bool numbers(const std::string &text, float *values, int n)
{
    const char *p = text.c_str();
    for (int i = 0; i < n; ++i) {
        char *e = nullptr;
        values[i] = std::strtof(p, &e);
        if (e == p || !std::isfinite(values[i]))
            return false;
        p = e;
    }
    while (*p == ' ' || *p == '\t')
        ++p;
    return *p == '\0';
}

std::vector<LevelSpawn> spawns_of(const Reader &r, const std::vector<Entity> &entities)
{
    static const char *const spawn_classes[] = {"info_player_deathmatch", "info_player_start", "team_CTF_redplayer",
                                                "team_CTF_blueplayer", "team_CTF_redspawn", "team_CTF_bluespawn"};
    std::vector<LevelSpawn> out;
    for (std::size_t i = 0; i < entities.size(); ++i) {
        const std::string *classname = entities[i].value("classname");
        if (!classname || std::none_of(std::begin(spawn_classes), std::end(spawn_classes),
                                       [&](const char *c) { return *classname == c; }))
            continue;
        const std::string what = "entity " + std::to_string(i) + " (" + *classname + ")";
        // Quake's defaults for a key the entity leaves out: origin 0 0 0, angle 0.
        float origin[3] = {0, 0, 0}, yaw = 0;
        if (const std::string *o = entities[i].value("origin"); o && !numbers(*o, origin, 3))
            r.refuse(entities_lump, what + ": origin '" + o->substr(0, 60) + "' is not three finite numbers");
        if (const std::string *a = entities[i].value("angles")) {
            float angles[3];
            if (!numbers(*a, angles, 3))
                r.refuse(entities_lump, what + ": angles '" + a->substr(0, 60) + "' are not three finite numbers");
            yaw = angles[1];
        } else if (const std::string *a1 = entities[i].value("angle"); a1 && !numbers(*a1, &yaw, 1)) {
            r.refuse(entities_lump, what + ": angle '" + a1->substr(0, 60) + "' is not a finite number");
        }
        LevelSpawn s;
        s.classname = *classname;
        const glm::vec3 q(origin[0], origin[1], origin[2]);
        s.origin = quake3_to_occu(q);
        s.eye = quake3_to_occu(q + glm::vec3(0, 0, spawn_lift_units + view_height_units));
        s.yaw_degrees = yaw;
        const float radians = glm::radians(yaw);
        s.direction = glm::normalize(quake3_to_occu(glm::vec3(std::cos(radians), std::sin(radians), 0.0f)));
        out.push_back(s);
    }
    return out;
}

// One vertex of the file, in occu's coordinates, with what the look reads:
// texture and lightmap coordinates, and its colour (RGBA8).
struct FileVertex {
    glm::vec3 position, normal;
    glm::vec2 st{0.0f}, lightmap{0.0f};
    glm::vec4 colour{1.0f};
};

// Quake III's default brightening of baked light (its renderer's
// R_ColorShiftLightingBytes with two overbright bits and no hardware
// gamma: one bit): doubled, and where a channel would pass 255 all three
// scaled back so that the hue stays.
void brighten(const std::uint8_t in[3], std::uint8_t out[3])
{
    int c[3] = {in[0] * 2, in[1] * 2, in[2] * 2};
    const int top = std::max({c[0], c[1], c[2]});
    for (int k = 0; k < 3; ++k)
        out[k] = std::uint8_t(top > 255 ? c[k] * 255 / top : c[k]);
}

// Whether the curves of a patch's control grid along one direction are
// all straight and evenly parameterized: along `n` points spaced `step`
// apart, `lines` of them spaced `stride` apart, every middle point of a
// piece (a, b, c) has a - 2b + c = 0 (to a millionth of the points'
// magnitudes: the rounding of their conversion to metres): the quadratic
// is then linear in its parameter.
bool straight(const FileVertex *control, std::int64_t n, std::int64_t lines, std::int64_t step, std::int64_t stride)
{
    for (std::int64_t l = 0; l < lines; ++l)
        for (std::int64_t k = 0; k + 2 < n; k += 2) {
            const glm::vec3 &a = control[l * stride + k * step].position, &b = control[l * stride + (k + 1) * step].position,
                            &c = control[l * stride + (k + 2) * step].position;
            const float magnitude = glm::length(a) + 2.0f * glm::length(b) + glm::length(c);
            if (!(glm::length(a - 2.0f * b + c) <= 1e-6f * magnitude))
                return false;
        }
    return true;
}

// Quadratic Bernstein weights at t.
glm::vec3 bernstein2(float t) { return {(1 - t) * (1 - t), 2 * t * (1 - t), t * t}; }

// A texture of the file: the flags that decide what is drawn and what hides.
struct Texture {
    std::string name;
    std::uint32_t surface_flags, content_flags;
    bool drawn;       // not SURF_NODRAW
    bool sky;         // SURF_SKY: drawn as the sky, unlit (scene/quake3_bsp.h)
    bool occluder;    // not see-through (scene/quake3_bsp.h)
};

std::vector<Texture> read_textures(const Reader &r)
{
    std::vector<Texture> textures;
    for (std::size_t t = 0; t < r.count(textures_lump); ++t) {
        const char *name = r.data() + r.at(textures_lump, t, 0);
        Texture tex;
        tex.name.assign(name, static_cast<std::size_t>(std::find(name, name + 64, '\0') - name));
        tex.surface_flags = std::uint32_t(r.i32(r.at(textures_lump, t, 64)));
        tex.content_flags = std::uint32_t(r.i32(r.at(textures_lump, t, 68)));
        tex.drawn = !(tex.surface_flags & surf_nodraw);
        tex.sky = tex.surface_flags & surf_sky;
        tex.occluder = !(tex.content_flags & (contents_translucent | contents_water | contents_fog)) &&
                       !(tex.surface_flags & surf_alphashadow);
        textures.push_back(std::move(tex));
    }
    return textures;
}

void read_planes(const Reader &r, Level &level)
{
    for (std::size_t i = 0; i < r.count(planes_lump); ++i) {
        const glm::vec3 n = r.vec3(r.at(planes_lump, i, 0));
        const float d = r.f32(r.at(planes_lump, i, 12));
        if (!finite(n) || !std::isfinite(d))
            r.refuse(planes_lump, i, "a normal or distance that is not finite");
        // Rotated normal; the distance scales with the units.
        level.planes.push_back({glm::vec3(n.x, n.z, -n.y), d * quake3_unit_metres});
    }
}

void read_nodes(const Reader &r, Level &level)
{
    const std::size_t node_count = r.count(nodes_lump), leaf_count = r.count(leaves_lump);
    for (std::size_t i = 0; i < node_count; ++i) {
        Level::Node node;
        node.plane = r.i32(r.at(nodes_lump, i, 0));
        r.require_range(nodes_lump, i, "plane", node.plane, 1, planes_lump);
        for (int c = 0; c < 2; ++c) {
            const std::int32_t child = r.i32(r.at(nodes_lump, i, 4 + 4 * std::size_t(c)));
            node.children[c] = child;
            if (child >= 0 && (std::size_t(child) <= i || std::size_t(child) >= node_count))
                r.refuse(nodes_lump, i, "child node " + std::to_string(child) +
                                            " does not lie after it among the " + std::to_string(node_count) +
                                            " nodes (the tree would not end)");
            if (child < 0 && std::uint64_t(-(std::int64_t(child) + 1)) >= leaf_count)
                r.refuse(nodes_lump, i, "child leaf " + std::to_string(-(std::int64_t(child) + 1)) +
                                            " lies outside the " + std::to_string(leaf_count) + " leafs");
        }
        node.bounds = Aabb::of(quake3_to_occu(r.ivec3(r.at(nodes_lump, i, 12))),
                               quake3_to_occu(r.ivec3(r.at(nodes_lump, i, 24))));
        level.nodes.push_back(node);
    }
}

// The clusters' bit vectors (read before the leaves, whose clusters index them).
void read_visibility(const Reader &r, Level &level)
{
    if (r.length(visdata_lump) == 0)
        return;
    if (r.length(visdata_lump) < 8)
        r.refuse(visdata_lump, std::to_string(r.length(visdata_lump)) +
                                   " bytes, fewer than its two counts (8 bytes)");
    const std::int32_t n = r.i32(r.offset(visdata_lump)), size = r.i32(r.offset(visdata_lump) + 4);
    if (n < 0 || size < 0 || std::uint64_t(n) * std::uint64_t(size) > r.length(visdata_lump) - 8)
        r.refuse(visdata_lump, std::to_string(n) + " clusters of " + std::to_string(size) +
                                   " bytes do not fit its " + std::to_string(r.length(visdata_lump) - 8) +
                                   " bytes of bit vectors");
    if (std::int64_t(size) * 8 < n)
        r.refuse(visdata_lump, "vectors of " + std::to_string(size) + " bytes cannot hold a bit for each of " +
                                   std::to_string(n) + " clusters");
    level.cluster_count = n;
    level.bytes_per_cluster = size;
    const auto *v = reinterpret_cast<const std::uint8_t *>(r.data() + r.offset(visdata_lump) + 8);
    level.visibility.assign(v, v + std::size_t(n) * std::size_t(size));
}

// The leaves and the face numbers they list.
void read_leaves(const Reader &r, Level &level)
{
    for (std::size_t i = 0; i < r.count(leaves_lump); ++i) {
        Level::Leaf leaf;
        leaf.cluster = r.i32(r.at(leaves_lump, i, 0));
        leaf.area = r.i32(r.at(leaves_lump, i, 4));
        if (leaf.cluster < -1 || (level.cluster_count > 0 && leaf.cluster >= level.cluster_count))
            r.refuse(leaves_lump, i, "cluster " + std::to_string(leaf.cluster) + " is neither -1 (solid) nor one of the " +
                                         std::to_string(level.cluster_count) + " clusters of the visdata");
        leaf.bounds = Aabb::of(quake3_to_occu(r.ivec3(r.at(leaves_lump, i, 8))),
                               quake3_to_occu(r.ivec3(r.at(leaves_lump, i, 20))));
        const std::int32_t first = r.i32(r.at(leaves_lump, i, 32)), n = r.i32(r.at(leaves_lump, i, 36));
        r.require_range(leaves_lump, i, "leaf faces", first, n, leaf_faces_lump);
        r.require_range(leaves_lump, i, "leaf brushes", r.i32(r.at(leaves_lump, i, 40)), r.i32(r.at(leaves_lump, i, 44)),
                        leaf_brushes_lump);
        leaf.first_leaf_face = std::uint32_t(first);
        leaf.leaf_face_count = std::uint32_t(n);
        level.leaves.push_back(leaf);
    }
    for (std::size_t i = 0; i < r.count(leaf_faces_lump); ++i) {
        const std::int32_t f = r.i32(r.at(leaf_faces_lump, i, 0));
        r.require_range(leaf_faces_lump, i, "face", f, 1, faces_lump);
        level.leaf_faces.push_back(std::uint32_t(f));
    }
}

// The model of each face (-1: none). Each model (the world, then the brush
// entities) owns a run of faces; the compiler writes them one after
// another. Overlapping runs are refused: a face of two models means
// nothing, and marking runs that overlap would cost models x faces.
std::vector<std::int32_t> face_models(const Reader &r)
{
    std::vector<std::int32_t> face_model(r.count(faces_lump), -1);
    std::vector<std::pair<std::int32_t, std::size_t>> runs;   // (first face, model) of non-empty runs
    for (std::size_t m = 0; m < r.count(models_lump); ++m) {
        const std::int32_t first = r.i32(r.at(models_lump, m, 24)), n = r.i32(r.at(models_lump, m, 28));
        r.require_range(models_lump, m, "faces", first, n, faces_lump);
        r.require_range(models_lump, m, "brushes", r.i32(r.at(models_lump, m, 32)), r.i32(r.at(models_lump, m, 36)),
                        brushes_lump);
        if (n > 0)
            runs.emplace_back(first, m);
    }
    std::sort(runs.begin(), runs.end());
    for (std::size_t k = 0; k < runs.size(); ++k) {
        const std::size_t m = runs[k].second;
        const std::int32_t first = runs[k].first, n = r.i32(r.at(models_lump, m, 28));
        if (k + 1 < runs.size() && std::int64_t(first) + n > runs[k + 1].first)
            r.refuse(models_lump, m, "faces " + std::to_string(first) + " to " + std::to_string(std::int64_t(first) + n) +
                                         " overlap those of model " + std::to_string(runs[k + 1].second));
        std::fill(face_model.begin() + first, face_model.begin() + first + n, std::int32_t(m));
    }
    return face_model;
}

// World brushes (model 0) that are opaque solids, in Quake's coordinates
// (the file's planes; level.planes are occu's), and their bounds in occu's.
void read_opaque_solids(const Reader &r, const std::vector<Texture> &textures, Level &level)
{
    constexpr std::uint32_t contents_solid = 0x1;
    if (r.count(models_lump) == 0)
        return;
    const std::int32_t first = r.i32(r.at(models_lump, 0, 32)), n = r.i32(r.at(models_lump, 0, 36));
    for (std::int32_t b = first; b < first + n; ++b) {
        const std::size_t br = std::size_t(b);
        const std::int32_t first_side = r.i32(r.at(brushes_lump, br, 0)), sides = r.i32(r.at(brushes_lump, br, 4));
        const std::int32_t texture = r.i32(r.at(brushes_lump, br, 8));
        r.require_range(brushes_lump, br, "brush sides", first_side, sides, brush_sides_lump);
        r.require_range(brushes_lump, br, "texture", texture, 1, textures_lump);
        const std::uint32_t contents = textures[std::size_t(texture)].content_flags;
        if (!(contents & contents_solid) || (contents & (contents_translucent | contents_water | contents_fog)))
            continue;
        bool sky = false;
        Level::Brush solid;
        solid.number = b;
        solid.lo = glm::vec3(-std::numeric_limits<float>::infinity());
        solid.hi = glm::vec3(std::numeric_limits<float>::infinity());
        for (std::int32_t k = first_side; k < first_side + sides; ++k) {
            const std::size_t side = std::size_t(k);
            const std::int32_t plane = r.i32(r.at(brush_sides_lump, side, 0));
            const std::int32_t side_texture = r.i32(r.at(brush_sides_lump, side, 4));
            r.require_range(brush_sides_lump, side, "plane", plane, 1, planes_lump);
            r.require_range(brush_sides_lump, side, "texture", side_texture, 1, textures_lump);
            sky = sky || (textures[std::size_t(side_texture)].surface_flags & surf_sky);
            const glm::vec3 normal = r.vec3(r.at(planes_lump, std::size_t(plane), 0));
            const float distance = r.f32(r.at(planes_lump, std::size_t(plane), 12));
            // Sides are clipped as polygons (occluders/brush_occluders.h): within
            // the compiler's world (q3map2: 65536 units either way).
            if (!(std::abs(glm::length(normal) - 1.0f) < 1e-3f) || !(std::abs(distance) <= 1048576.0f))
                r.refuse(planes_lump, std::size_t(plane),
                         "a brush side's plane (normal length " + std::to_string(glm::length(normal)) +
                             ", distance " + std::to_string(distance) + ") is not a unit normal within 2^20 units");
            solid.planes.emplace_back(normal, distance);
            for (int a = 0; a < 3; ++a) {
                const glm::vec3 e(a == 0, a == 1, a == 2);
                if (normal == e) solid.hi[a] = std::min(solid.hi[a], distance);
                if (normal == -e) solid.lo[a] = std::max(solid.lo[a], -distance);
            }
        }
        // Every brush the compiler writes carries its six axial (bevel) planes.
        if (sky || !(solid.lo.x < solid.hi.x && solid.lo.y < solid.hi.y && solid.lo.z < solid.hi.z) ||
            !finite(solid.lo) || !finite(solid.hi))
            continue;
        level.solid_brush_bounds.push_back(Aabb::of(quake3_to_occu(solid.lo), quake3_to_occu(solid.hi)));
        level.opaque_solids.push_back(std::move(solid));
    }
}

std::vector<FileVertex> read_vertices(const Reader &r, bool look, std::size_t &bad_coordinates)
{
    const std::size_t vertex_count = r.count(vertices_lump);
    std::vector<FileVertex> vertices(vertex_count);
    for (std::size_t i = 0; i < vertex_count; ++i) {
        const glm::vec3 p = r.vec3(r.at(vertices_lump, i, 0));
        if (!finite(p))
            r.refuse(vertices_lump, i, "position (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " +
                                           std::to_string(p.z) + ") is not finite");
        const glm::vec3 n = r.vec3(r.at(vertices_lump, i, 28));
        vertices[i] = {quake3_to_occu(p), glm::vec3(n.x, n.z, -n.y)};
        if (look) {
            FileVertex &v = vertices[i];
            v.st = {r.f32(r.at(vertices_lump, i, 12)), r.f32(r.at(vertices_lump, i, 16))};
            v.lightmap = {r.f32(r.at(vertices_lump, i, 20)), r.f32(r.at(vertices_lump, i, 24))};
            // A level Debian ships has such vertices (pak1's ctf_gate1): the
            // picture's corner instead, counted in a warning.
            if (!std::isfinite(v.st.x) || !std::isfinite(v.st.y) || !std::isfinite(v.lightmap.x) ||
                !std::isfinite(v.lightmap.y)) {
                v.st = v.lightmap = glm::vec2(0.0f);
                ++bad_coordinates;
            }
            const auto *c = reinterpret_cast<const std::uint8_t *>(r.data() + r.at(vertices_lump, i, 40));
            std::uint8_t lit[3];
            brighten(c, lit);
            v.colour = glm::vec4(lit[0], lit[1], lit[2], c[3]) / 255.0f;
        }
    }
    return vertices;
}

// One face record of the file, its numbers as read.
struct FaceRecord {
    std::size_t number;
    std::int32_t first_vertex, n_vertices, first_meshvert, n_meshverts;
};

// What the faces make so far: the bound on vertices and indices.
struct MadeSoFar {
    std::uint64_t vertices = 0, indices = 0;
};

// A polygon's or mesh's triangles: the file vertex numbers its meshverts list.
void polygon_triangles(const Reader &r, const FaceRecord &f, MadeSoFar &made, std::vector<std::uint32_t> &triangles)
{
    const std::size_t i = f.number;
    if (f.n_meshverts % 3 != 0)
        r.refuse(faces_lump, i, std::to_string(f.n_meshverts) + " meshverts are not whole triangles");
    // Faces may share meshverts: what they make together is bounded, not the lump.
    made.indices += std::uint64_t(f.n_meshverts);
    if (made.indices > max_indices)
        r.refuse(faces_lump, i, "the faces so far make more than " + std::to_string(max_indices / 3) + " triangles");
    for (std::int32_t k = 0; k < f.n_meshverts; ++k) {
        const std::int32_t offset = r.i32(r.at(meshverts_lump, std::size_t(f.first_meshvert + k), 0));
        if (offset < 0 || offset >= f.n_vertices)
            r.refuse(faces_lump, i, "meshvert " + std::to_string(f.first_meshvert + k) + " is " +
                                        std::to_string(offset) + ", outside the face's " +
                                        std::to_string(f.n_vertices) + " vertices");
        triangles.push_back(std::uint32_t(f.first_vertex + offset));
    }
}

// A patch of w x h control points tessellated at `segments` a piece: the
// vertices it makes (`made`) and its triangles, indices into them.
void patch_triangles(const Reader &r, const FaceRecord &f, const FileVertex *control, std::int32_t w, std::int32_t h,
                     int segments, MadeSoFar &made_so_far, std::vector<FileVertex> &made,
                     std::vector<std::uint32_t> &triangles)
{
    // A direction in which every piece is straight and evenly
    // parameterized (each middle control point halfway between its
    // neighbours) is exactly one segment a piece: more would add
    // triangles, not shape.
    const std::int64_t su = straight(control, w, h, 1, w) ? 1 : segments,
                       sv = straight(control, h, w, w, 1) ? 1 : segments;
    const std::int64_t columns = std::int64_t(w - 1) / 2 * su + 1, rows = std::int64_t(h - 1) / 2 * sv + 1;
    made_so_far.vertices += std::uint64_t(columns * rows);
    made_so_far.indices += 6 * std::uint64_t((columns - 1) * (rows - 1));
    if (made_so_far.vertices > max_vertices || made_so_far.indices > max_indices)
        r.refuse(faces_lump, f.number, "its patches at " + std::to_string(segments) +
                                           " segments a piece make more than " + std::to_string(max_vertices) +
                                           " vertices or " + std::to_string(max_indices / 3) +
                                           " triangles (fewer segments make fewer)");
    for (std::int64_t row = 0; row < rows; ++row) {
        const std::int64_t pj = std::min<std::int64_t>(row / sv, (h - 1) / 2 - 1);
        const glm::vec3 bv = bernstein2(float(row - pj * sv) / float(sv));
        for (std::int64_t col = 0; col < columns; ++col) {
            const std::int64_t pi = std::min<std::int64_t>(col / su, (w - 1) / 2 - 1);
            const glm::vec3 bu = bernstein2(float(col - pi * su) / float(su));
            FileVertex v{glm::vec3(0.0f), glm::vec3(0.0f), glm::vec2(0.0f), glm::vec2(0.0f), glm::vec4(0.0f)};
            for (int b = 0; b < 3; ++b)
                for (int a = 0; a < 3; ++a) {
                    const FileVertex &c = control[(2 * pj + b) * w + 2 * pi + a];
                    const float weight = bu[a] * bv[b];
                    v.position += weight * c.position;
                    v.normal += weight * c.normal;
                    v.st += weight * c.st;
                    v.lightmap += weight * c.lightmap;
                    v.colour += weight * c.colour;
                }
            made.push_back(v);
        }
    }
    for (std::int64_t row = 0; row + 1 < rows; ++row)
        for (std::int64_t col = 0; col + 1 < columns; ++col) {
            const auto v00 = std::uint32_t(row * columns + col), v01 = v00 + 1, v10 = std::uint32_t(v00 + columns),
                       v11 = v10 + 1;
            triangles.insert(triangles.end(), {v00, v01, v11, v00, v11, v10});
        }
}

// Front faces counter-clockwise: the winding of the triangles of `mesh`
// from `first_index` on that agrees with their own vertex normals (the
// compiler's, or a patch's control points' interpolated).
void wind_counter_clockwise(Mesh &mesh, std::size_t first_index)
{
    float agreement = 0.0f;
    for (std::size_t t = first_index; t < mesh.indices.size(); t += 3) {
        const glm::vec3 &a = mesh.positions[mesh.indices[t]], &b = mesh.positions[mesh.indices[t + 1]],
                        &c = mesh.positions[mesh.indices[t + 2]];
        const glm::vec3 n =
            mesh.normals[mesh.indices[t]] + mesh.normals[mesh.indices[t + 1]] + mesh.normals[mesh.indices[t + 2]];
        const float d = glm::dot(glm::cross(b - a, c - a), n);
        if (std::isfinite(d))
            agreement += d;
    }
    if (agreement < 0.0f)
        for (std::size_t t = first_index; t < mesh.indices.size(); t += 3)
            std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
}

// Normals of the face's vertices (from `base`) that the file leaves zero
// or not finite: the face's own (the sum of its triangles' at the vertex,
// its triangles from `first_index`). The others are made unit. Returns how
// many it replaced.
std::size_t replace_bad_normals(Mesh &mesh, std::size_t base, std::size_t first_index)
{
    std::size_t bad = 0;
    std::vector<glm::vec3> own;
    for (std::size_t v = base; v < mesh.normals.size(); ++v) {
        glm::vec3 &n = mesh.normals[v];
        const float length = glm::length(n);
        if (length > 0.0f && std::isfinite(length)) {
            n /= length;
            continue;
        }
        ++bad;
        if (own.empty()) {
            own.assign(mesh.normals.size() - base, glm::vec3(0.0f));
            for (std::size_t t = first_index; t < mesh.indices.size(); t += 3) {
                const glm::vec3 &a = mesh.positions[mesh.indices[t]];
                const glm::vec3 n3 =
                    glm::cross(mesh.positions[mesh.indices[t + 1]] - a, mesh.positions[mesh.indices[t + 2]] - a);
                for (int k = 0; k < 3; ++k)
                    own[mesh.indices[t + std::size_t(k)] - base] += n3;
            }
        }
        const float s = glm::length(own[v - base]);
        n = s > 0.0f && std::isfinite(s) ? own[v - base] / s : glm::vec3(0.0f, 1.0f, 0.0f);
    }
    return bad;
}

// The faces into meshes of `scene`, one a texture, each face recorded in
// `level` (its mesh and range of indices, or mesh -1 where not drawn);
// `face_model` the model of each (face_models), `vertices` the file's.
// Returns how many vertex normals it replaced (replace_bad_normals).
std::size_t read_faces(const Reader &r, const Quake3Options &options, const std::vector<Texture> &textures,
                       const std::vector<std::int32_t> &face_model, const std::vector<FileVertex> &vertices, Level &level,
                       Scene &scene)
{
    // Per texture, its mesh without and with a lightmap.
    std::vector<std::int32_t> texture_mesh(2 * textures.size(), -1);
    MadeSoFar made_so_far;
    std::size_t bad_normals = 0;
    // The lightmap pages side by side in the atlas (read_lightmaps).
    const std::int64_t pages = std::int64_t(r.count(lightmaps_lump));
    const std::int64_t columns = std::max<std::int64_t>(1, std::int64_t(std::ceil(std::sqrt(double(pages)))));
    const std::int64_t rows = std::max<std::int64_t>(1, (pages + columns - 1) / columns);
    for (std::size_t i = 0; i < r.count(faces_lump); ++i) {
        Level::Face face;
        face.texture = r.i32(r.at(faces_lump, i, 0));
        face.type = r.i32(r.at(faces_lump, i, 8));
        face.model = face_model[i];
        const FaceRecord record{i, r.i32(r.at(faces_lump, i, 12)), r.i32(r.at(faces_lump, i, 16)),
                                r.i32(r.at(faces_lump, i, 20)), r.i32(r.at(faces_lump, i, 24))};
        r.require_range(faces_lump, i, "texture", face.texture, 1, textures_lump);
        if (face.type < face_polygon || face.type > face_billboard)
            r.refuse(faces_lump, i, "type " + std::to_string(face.type) + " is none of 1 (polygon), 2 (patch), 3 (mesh), 4 (billboard)");
        r.require_range(faces_lump, i, "vertices", record.first_vertex, record.n_vertices, vertices_lump);
        if (face.type != face_billboard)
            r.require_range(faces_lump, i, "meshverts", record.first_meshvert, record.n_meshverts, meshverts_lump);
        const Texture &texture = textures[std::size_t(face.texture)];
        // Its lightmap page: < 0 none (vertex light), else one of the lump's.
        const std::int32_t page = r.i32(r.at(faces_lump, i, 28));
        if (options.look && page >= pages)
            r.refuse(faces_lump, i, "lightmap " + std::to_string(page) + " is not one of the " +
                                        std::to_string(pages) + " lightmaps");
        const bool lightmapped = options.look && page >= 0 && !texture.sky;

        // The face's triangles (indices into the file's vertices) and, for
        // a patch, the vertices it makes.
        std::vector<FileVertex> made;
        std::vector<std::uint32_t> triangles;   // into `made` when a patch, else file vertex numbers
        if (face.type == face_polygon || face.type == face_mesh) {
            polygon_triangles(r, record, made_so_far, triangles);
        } else if (face.type == face_patch) {
            ++level.patch_count;
            const std::int32_t w = r.i32(r.at(faces_lump, i, 96)), h = r.i32(r.at(faces_lump, i, 100));
            if (w < 3 || h < 3 || w % 2 == 0 || h % 2 == 0 || std::int64_t(w) * h != record.n_vertices)
                r.refuse(faces_lump, i, "a patch of " + std::to_string(w) + " x " + std::to_string(h) +
                                            " control points (odd sizes of at least 3, holding its " +
                                            std::to_string(record.n_vertices) + " vertices, expected)");
            if (!texture.drawn) {
                // The compiler keeps patches it has made triangles of itself
                // (q3map2 -patchmeta) as nodraw faces, for collision.
                ++level.hidden_face_count;
                level.faces.push_back(face);
                continue;
            }
            patch_triangles(r, record, vertices.data() + record.first_vertex, w, h, options.patch_segments,
                            made_so_far, made, triangles);
        } else {
            ++level.billboard_count;
        }

        // A triangle with collinear corners has no surface (scene/scene.h):
        // a polygon's fan from an end of an edge with a vertex on it (the
        // compiler's fix of a T-junction) makes one.
        const auto position = [&](std::uint32_t v) {
            return face.type == face_patch ? made[v].position : vertices[v].position;
        };
        std::size_t kept = 0;
        for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
            if (collinear_corners(position(triangles[t]), position(triangles[t + 1]), position(triangles[t + 2])))
                continue;
            std::copy_n(triangles.begin() + std::ptrdiff_t(t), 3, triangles.begin() + std::ptrdiff_t(kept));
            kept += 3;
        }
        triangles.resize(kept);
        if (!texture.drawn && face.type != face_billboard)
            ++level.hidden_face_count;
        if (face.type == face_billboard || !texture.drawn || triangles.empty()) {
            level.faces.push_back(face);
            continue;
        }
        if (!texture.occluder)
            ++level.see_through_face_count;

        std::int32_t &mesh_number = texture_mesh[2 * std::size_t(face.texture) + (lightmapped ? 1 : 0)];
        if (mesh_number < 0) {
            mesh_number = std::int32_t(scene.meshes.size());
            Mesh m;
            m.name = texture.name;
            m.color = texture.sky ? sky_colour : building_colours(std::uint32_t(face.texture), 0.5f, 0.0f).wall;
            m.shaded = !texture.sky;
            m.occluder = texture.occluder;
            m.lightmapped = lightmapped;
            scene.meshes.push_back(std::move(m));
        }
        Mesh &mesh = scene.meshes[std::size_t(mesh_number)];
        face.mesh = mesh_number;
        face.first_index = std::uint32_t(mesh.indices.size());
        face.index_count = std::uint32_t(triangles.size());

        // The face's vertices into the mesh (a polygon's or mesh's own
        // range of the file's, a patch's made ones).
        const auto base = std::uint32_t(mesh.positions.size());
        auto look_of = [&](const FileVertex &v) {
            if (!options.look)
                return;
            mesh.texcoords.push_back(v.st);
            if (lightmapped)
                mesh.lightmap_coords.push_back(
                    {(float(page % columns) + v.lightmap.x) / float(columns), (float(page / columns) + v.lightmap.y) / float(rows)});
            const glm::vec4 c = glm::clamp(v.colour, 0.0f, 1.0f) * 255.0f + 0.5f;
            mesh.vertex_light.push_back(std::uint32_t(c.r) | std::uint32_t(c.g) << 8 | std::uint32_t(c.b) << 16 |
                                        std::uint32_t(c.a) << 24);
        };
        if (face.type == face_patch) {
            for (const FileVertex &v : made) {
                mesh.positions.push_back(v.position);
                mesh.normals.push_back(v.normal);
                look_of(v);
            }
            for (std::uint32_t t : triangles)
                mesh.indices.push_back(base + t);
        } else {
            made_so_far.vertices += std::uint64_t(record.n_vertices);
            if (made_so_far.vertices > max_vertices)
                r.refuse(faces_lump, i, "the faces so far make more than " + std::to_string(max_vertices) + " vertices");
            for (std::int32_t k = 0; k < record.n_vertices; ++k) {
                mesh.positions.push_back(vertices[std::size_t(record.first_vertex + k)].position);
                mesh.normals.push_back(vertices[std::size_t(record.first_vertex + k)].normal);
                look_of(vertices[std::size_t(record.first_vertex + k)]);
            }
            for (std::uint32_t t : triangles)
                mesh.indices.push_back(base + t - std::uint32_t(record.first_vertex));
        }
        wind_counter_clockwise(mesh, face.first_index);
        bad_normals += replace_bad_normals(mesh, base, face.first_index);
        level.faces.push_back(face);
    }
    return bad_normals;
}

// The lightmap pages (lump 14: 128 x 128 RGB each, rows from the top)
// into one atlas of ceil(sqrt(n)) columns, brightened as the game does
// (brighten), as read_faces maps the faces' lightmap coordinates into it.
Image read_lightmaps(const Reader &r)
{
    const std::size_t pages = r.count(lightmaps_lump);
    const std::size_t columns = std::max<std::size_t>(1, std::size_t(std::ceil(std::sqrt(double(pages)))));
    const std::size_t rows = std::max<std::size_t>(1, (pages + columns - 1) / columns);
    Image atlas;
    atlas.name = "lightmaps";
    atlas.width = int(columns * 128);
    atlas.height = int(rows * 128);
    atlas.rgba.assign(std::size_t(atlas.width) * std::size_t(atlas.height) * 4, 255);
    for (std::size_t p = 0; p < pages; ++p) {
        const auto *page = reinterpret_cast<const std::uint8_t *>(r.data() + r.at(lightmaps_lump, p, 0));
        for (std::size_t y = 0; y < 128; ++y)
            for (std::size_t x = 0; x < 128; ++x) {
                std::uint8_t *out = &atlas.rgba[(((p / columns) * 128 + y) * std::size_t(atlas.width) +
                                                 (p % columns) * 128 + x) * 4];
                brighten(page + (y * 128 + x) * 3, out);
            }
    }
    return atlas;
}

}  // namespace

bool looks_like_ibsp(const std::vector<char> &bytes)
{
    return bytes.size() >= 4 && std::memcmp(bytes.data(), "IBSP", 4) == 0;
}

Scene read_quake3_bsp(const std::string &source, const std::vector<char> &bytes, const Quake3Options &options,
                      std::vector<std::string> &warnings)
{
    Reader r(source, bytes);
    if (options.patch_segments < 1 || options.patch_segments > 64)
        r.refuse("patch segments " + std::to_string(options.patch_segments) + " outside 1..64");
    r.read_header();
    auto level = std::make_shared<Level>();
    const std::vector<Texture> textures = read_textures(r);
    read_planes(r, *level);
    read_nodes(r, *level);
    read_visibility(r, *level);
    read_leaves(r, *level);
    const std::vector<std::int32_t> face_model = face_models(r);
    read_opaque_solids(r, textures, *level);
    std::size_t bad_coordinates = 0;
    const std::vector<FileVertex> vertices = read_vertices(r, options.look, bad_coordinates);
    if (bad_coordinates)
        warnings.push_back("scene '" + source + "': " + std::to_string(bad_coordinates) +
                           " vertices have texture or lightmap coordinates that are not finite; 0 instead");

    Scene scene;
    const std::size_t bad_normals = read_faces(r, options, textures, face_model, vertices, *level, scene);
    if (bad_normals)
        warnings.push_back("scene '" + source + "': " + std::to_string(bad_normals) +
                           " vertex normals of the level are zero or not finite; the faces' own instead");
    if (scene.meshes.empty())
        r.refuse(faces_lump, "none of its " + std::to_string(r.count(faces_lump)) + " faces is drawn");

    if (options.look && r.count(lightmaps_lump) > 0) {
        scene.lightmap_atlas = std::int32_t(scene.images.size());
        scene.images.push_back(read_lightmaps(r));
    }
    level->spawns = spawns_of(r, parse_entities(r));
    scene.update_bounds();
    scene.level = std::move(level);
    return scene;
}

}  // namespace occu
