// SPDX-License-Identifier: MIT
#include "spatial/hierarchy.h"

#include <cmath>
#include <cstdio>

#include <algorithm>
#include <array>
#include <stdexcept>

#include "cli/arguments.h"

namespace occu {

namespace {

struct Item {
    TriangleRef ref;
    Aabb box;
    glm::vec3 centroid;
    bool occluder = true;   // its mesh's Mesh::occluder
};

class Builder {
public:
    Builder(std::vector<HierarchyNode> &nodes, std::vector<TriangleRef> &out, const HierarchyOptions &o)
        : nodes_(nodes), out_(out), options_(o)
    {
    }

    void build(std::uint32_t node, std::vector<Item> items, std::uint32_t depth)
    {
        HierarchyNode &n = nodes_[node];
        n.depth = depth;
        for (const Item &it : items)
            n.bounds.expand(it.box);
        if (items.size() <= options_.max_leaf_triangles || depth >= options_.max_depth) {
            make_leaf(node, items);
            return;
        }
        std::vector<std::vector<Item>> groups = split(items);
        if (groups.size() < 2) {   // all centroids coincide: nothing separates them
            make_leaf(node, items);
            return;
        }
        const auto first = std::uint32_t(nodes_.size());
        nodes_.resize(nodes_.size() + groups.size());
        nodes_[node].first_child = first;
        nodes_[node].child_count = std::uint32_t(groups.size());
        for (std::size_t i = 0; i < groups.size(); ++i)
            build(first + std::uint32_t(i), std::move(groups[i]), depth + 1);
    }

private:
    void make_leaf(std::uint32_t node, const std::vector<Item> &items)
    {
        nodes_[node].first_triangle = std::uint32_t(out_.size());
        nodes_[node].triangle_count = std::uint32_t(items.size());
        // Occluders first, see-through triangles after (in their order):
        // whatever draws or rasterizes a leaf's occluders takes a prefix.
        for (int pass = 0; pass < 2; ++pass)
            for (const Item &it : items)
                if (it.occluder == (pass == 0))
                    out_.push_back(it.ref);
        nodes_[node].occluder_triangles = std::uint32_t(
            std::count_if(items.begin(), items.end(), [](const Item &it) { return it.occluder; }));
    }

    // Octants around the centre of the centroids' box; if every centroid
    // falls in one octant, halves at the median of the longest axis.
    static std::vector<std::vector<Item>> split(std::vector<Item> &items)
    {
        Aabb centroids;
        for (const Item &it : items)
            centroids.expand(it.centroid);
        const glm::vec3 c = centroids.center();
        std::array<std::vector<Item>, 8> octants;
        for (Item &it : items) {
            const int o = (it.centroid.x > c.x) | (it.centroid.y > c.y) << 1 | (it.centroid.z > c.z) << 2;
            octants[o].push_back(it);
        }
        std::vector<std::vector<Item>> groups;
        for (auto &o : octants)
            if (!o.empty())
                groups.push_back(std::move(o));
        if (groups.size() > 1)
            return groups;

        const glm::vec3 e = centroids.extent();
        const int axis = e.x >= e.y && e.x >= e.z ? 0 : e.y >= e.z ? 1 : 2;
        if (e[axis] <= 0.0f)
            return {};
        const auto mid = items.begin() + std::ptrdiff_t(items.size() / 2);
        std::nth_element(items.begin(), mid, items.end(),
                         [axis](const Item &a, const Item &b) { return a.centroid[axis] < b.centroid[axis]; });
        return {std::vector<Item>(items.begin(), mid), std::vector<Item>(mid, items.end())};
    }

    std::vector<HierarchyNode> &nodes_;
    std::vector<TriangleRef> &out_;
    const HierarchyOptions &options_;
};

// FNV-1a over bytes: a stable hash (the same on every run and machine for
// the same data), which std::hash does not promise.
struct Fnv1a {
    std::uint64_t h = 1469598103934665603ull;
    template <typename T> void add(const T &value)
    {
        const auto *p = reinterpret_cast<const unsigned char *>(&value);
        for (std::size_t i = 0; i < sizeof(T); ++i) {
            h ^= p[i];
            h *= 1099511628211ull;
        }
    }
};

}  // namespace

std::string Hierarchy::fingerprint_of(const Scene &scene, const Hierarchy &h)
{
    Fnv1a f;
    for (const Mesh &mesh : scene.meshes) {
        // A see-through mesh is marked in the hash (and only then, so that
        // scenes without one keep their fingerprints): what was chosen as
        // occluders for a scene depends on which meshes may occlude.
        if (!mesh.occluder)
            f.add(std::uint64_t(0x7365652d7468726full));
        f.add(mesh.positions.size());
        for (const glm::vec3 &p : mesh.positions)
            f.add(p);
        f.add(mesh.indices.size());
        for (std::uint32_t i : mesh.indices)
            f.add(i);
    }
    for (const HierarchyNode &n : h.nodes_) {
        f.add(n.bounds.min);
        f.add(n.bounds.max);
        f.add(n.first_child);
        f.add(n.child_count);
        f.add(n.first_triangle);
        f.add(n.triangle_count);
    }
    char hex[17];
    std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(f.h));
    return hex;
}

std::vector<std::uint8_t> subtrees_holding(const Hierarchy &hierarchy, const std::vector<std::uint32_t> &leaves)
{
    const auto &nodes = hierarchy.nodes();
    std::vector<std::uint8_t> holds(nodes.size(), 0);
    for (std::uint32_t leaf : leaves)
        if (leaf < nodes.size())
            holds[leaf] = 1;
    // Children follow their parents in the node array: mark bottom-up.
    for (std::size_t i = nodes.size(); i-- > 0;)
        for (std::uint32_t c = 0; c < nodes[i].child_count; ++c)
            holds[i] |= holds[nodes[i].first_child + c];
    return holds;
}

std::vector<std::uint32_t> leaves_in_frustum(const Hierarchy &hierarchy, const Frustum &frustum)
{
    std::vector<std::uint32_t> leaves;
    const auto &nodes = hierarchy.nodes();
    for (std::uint32_t n = 0; n < nodes.size(); ++n)
        if (nodes[n].leaf() && frustum.classify(nodes[n].bounds) != Frustum::Side::outside)
            leaves.push_back(n);
    return leaves;
}

Hierarchy Hierarchy::build(const Scene &scene, const HierarchyOptions &options)
{
    // Every scene passes here, loaded, generated or made by a program: with
    // a NaN coordinate the octree's comparisons order nothing (and
    // std::nth_element's order would be invalid), with an infinite one no
    // box or projection means anything.
    require_finite_vertices(scene, "scene given to the hierarchy");
    if (options.max_leaf_triangles == auto_leaf_triangles) {
        HierarchyOptions chosen = options;
        chosen.max_leaf_triangles = choose_leaf_triangles(scene, options.max_depth);
        return build(scene, chosen);
    }
    Hierarchy h;
    h.max_leaf_triangles_ = options.max_leaf_triangles;
    std::vector<Item> items;
    items.reserve(scene.triangle_count());
    for (std::uint32_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh &mesh = scene.meshes[m];
        for (std::uint32_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
            Item it{{m, i}, {}, {}, mesh.occluder};
            for (int k = 0; k < 3; ++k)
                it.box.expand(mesh.positions[mesh.indices[i + k]]);
            it.centroid = it.box.center();
            items.push_back(it);
        }
    }
    h.nodes_.resize(1);
    h.triangles_.reserve(items.size());
    Builder(h.nodes_, h.triangles_, options).build(0, std::move(items), 0);
    // Children always come after their parent: sum from the back.
    for (std::size_t i = h.nodes_.size(); i-- > 0;) {
        HierarchyNode &n = h.nodes_[i];
        n.subtree_triangles = n.triangle_count;
        for (std::uint32_t c = 0; c < n.child_count; ++c)
            n.subtree_triangles += h.nodes_[n.first_child + c].subtree_triangles;
    }
    h.fingerprint_ = fingerprint_of(scene, h);
    return h;
}

std::size_t Hierarchy::leaf_count() const
{
    return std::size_t(std::count_if(nodes_.begin(), nodes_.end(), [](const HierarchyNode &n) { return n.leaf(); }));
}

std::vector<std::pair<std::uint32_t, std::size_t>> leaf_counts_by_size(const Scene &scene, std::uint32_t max_depth)
{
    HierarchyOptions smallest;
    smallest.max_leaf_triangles = auto_leaf_triangles_min;
    smallest.max_depth = max_depth;
    const Hierarchy h = Hierarchy::build(scene, smallest);
    const auto &nodes = h.nodes();
    std::vector<std::pair<std::uint32_t, std::size_t>> counts;
    for (std::uint32_t size = auto_leaf_triangles_min; size <= auto_leaf_triangles_max; size *= 2) {
        // A node is a leaf at `size` when it is one at the smallest size or
        // holds at most `size` triangles, and its parent (if any) splits,
        // holding more than `size`.
        auto leaf_at = [&](const HierarchyNode &n) { return n.leaf() || n.subtree_triangles <= size; };
        std::size_t leaves = leaf_at(nodes.front()) ? 1 : 0;
        for (const HierarchyNode &parent : nodes)
            if (!parent.leaf() && parent.subtree_triangles > size)
                for (std::uint32_t c = 0; c < parent.child_count; ++c)
                    leaves += leaf_at(nodes[parent.first_child + c]) ? 1 : 0;
        counts.emplace_back(size, leaves);
    }
    return counts;
}

std::uint32_t size_nearest_leaf_count_target(const std::vector<std::pair<std::uint32_t, std::size_t>> &counts)
{
    // Why a leaf count and not a size: a leaf is one draw call, one proxy
    // and one test for the query strategies (Bartz et al. 1998, section 3:
    // the unit's cost is per tested box), while smaller leaves are tighter
    // boxes that cull more. A first sweep of the leaf size gave the fastest
    // sizes roughly 500 to 1,100 leaves on scenes of very different
    // triangle counts (docs/real-scenes.md, "The hierarchy's leaf size"):
    // the city at 1024 (824), the levels at 256 (458 to 851), the engine
    // at 512 (905), the house at 128 to 512. The sizes are powers of two,
    // so the counts they give a scene are about a factor of two apart:
    // 800, the middle of that band by ratio, puts one size in it for
    // nearly every scene. Measured against 256 it suits the query
    // strategies, not the CPU maps, which gain from tighter boxes at a
    // small cost per box (same section): hence not the default.
    std::uint32_t best = auto_leaf_triangles_max;
    double best_distance = INFINITY;
    for (const auto &[size, leaves] : counts) {
        const double distance = std::abs(std::log(double(std::max<std::size_t>(leaves, 1)) /
                                                  double(auto_leaf_count_target)));
        if (distance <= best_distance) {
            best = size;
            best_distance = distance;
        }
    }
    return best;
}

std::uint32_t choose_leaf_triangles(const Scene &scene, std::uint32_t max_depth)
{
    return size_nearest_leaf_count_target(leaf_counts_by_size(scene, max_depth));
}

std::uint32_t leaf_triangles_option(const std::string &option, const std::string &text)
{
    if (text == "auto")
        return auto_leaf_triangles;
    try {
        return std::uint32_t(integer_option(option, text, 1, 1 << 20));
    } catch (const std::invalid_argument &) {
        throw std::invalid_argument(option + " wants auto or an integer in 1.." + std::to_string(1 << 20) +
                                    ", got '" + text + "'");
    }
}

std::string leaf_triangles_text(std::uint32_t max_leaf_triangles)
{
    return max_leaf_triangles == auto_leaf_triangles ? "auto" : std::to_string(max_leaf_triangles);
}

}  // namespace occu
