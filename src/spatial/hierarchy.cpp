#include "spatial/hierarchy.h"

#include <cstdio>

#include <algorithm>
#include <array>

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
    Hierarchy h;
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

}  // namespace occu
