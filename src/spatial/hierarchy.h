// SPDX-License-Identifier: MIT
// The spatial hierarchy occlusion-driven rendering traverses: an octree
// over the scene's triangles whose nodes are bounded by the boxes of the
// triangles they hold, so siblings may overlap. This is the "sloppy n-ary
// space partitioning tree" of Bartz et al. (1998, section 1; their ref.
// [10]): a triangle is never split and belongs to exactly one leaf, and a
// node's box is tight around its contents, which is what is rendered as its
// occlusion proxy (Moeller and Haines, "hierarchical visibility").
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "camera/camera.h"
#include "geometry/aabb.h"
#include "scene/scene.h"

namespace occu {

struct TriangleRef {
    std::uint32_t mesh;
    std::uint32_t first_index;   // into Mesh::indices
};

struct HierarchyNode {
    Aabb bounds;
    std::uint32_t first_child = 0, child_count = 0;          // nodes[first_child ..]
    std::uint32_t first_triangle = 0, triangle_count = 0;    // leaves: triangles[first_triangle ..]
    // Leaves: how many of its triangles, the first ones, belong to meshes
    // that are occluders (Mesh::occluder); the see-through ones follow.
    std::uint32_t occluder_triangles = 0;
    std::uint32_t depth = 0;
    std::uint32_t subtree_triangles = 0;   // in this node's leaves
    bool leaf() const { return child_count == 0; }
};

// HierarchyOptions::max_leaf_triangles meaning "choose it for the scene"
// (auto_leaf_triangles below).
constexpr std::uint32_t auto_leaf_triangles = 0;

struct HierarchyOptions {
    // The most triangles a leaf holds (unless max_depth stops the split
    // first), or auto_leaf_triangles.
    std::uint32_t max_leaf_triangles = 256;
    std::uint32_t max_depth = 20;
};

// The leaf sizes auto_leaf_triangles chooses from (powers of two) and the
// leaf count it aims at; see choose_leaf_triangles.
constexpr std::uint32_t auto_leaf_triangles_min = 64, auto_leaf_triangles_max = 1024;
constexpr std::size_t auto_leaf_count_target = 800;

// A program's --leaf-triangles (or a knob's value): "auto" is
// auto_leaf_triangles, else an integer in 1..2^20. Throws
// std::invalid_argument naming `option` otherwise.
std::uint32_t leaf_triangles_option(const std::string &option, const std::string &text);
// "auto" or the number.
std::string leaf_triangles_text(std::uint32_t max_leaf_triangles);

class Hierarchy {
public:
    // Throws std::runtime_error when a vertex coordinate is not finite
    // (scene/scene.h: require_finite_vertices).
    static Hierarchy build(const Scene &scene, const HierarchyOptions &options = {});

    // The leaf size built with: options.max_leaf_triangles, or the size
    // auto_leaf_triangles chose.
    std::uint32_t max_leaf_triangles() const { return max_leaf_triangles_; }

    const std::vector<HierarchyNode> &nodes() const { return nodes_; }
    const std::vector<TriangleRef> &triangles() const { return triangles_; }
    const HierarchyNode &root() const { return nodes_.front(); }
    std::size_t leaf_count() const;
    // A hash of the scene's triangles and of the nodes built over them:
    // what a precomputed database (e.g.
    // strategies/poon_wang_opacity_maps/occluder_database.h) was made for.
    // 16 hex digits.
    const std::string &fingerprint() const { return fingerprint_; }

private:
    static std::string fingerprint_of(const Scene &scene, const Hierarchy &h);
    std::vector<HierarchyNode> nodes_;
    std::vector<TriangleRef> triangles_;
    std::string fingerprint_;
    std::uint32_t max_leaf_triangles_ = 0;
};

// How many leaves Hierarchy::build(scene, {size, max_depth}) makes for each
// power-of-two size from auto_leaf_triangles_min to auto_leaf_triangles_max,
// in that order, from one build at the smallest size: a node of the octree
// splits the same way whatever the leaf size (its triangles alone decide
// how), so the tree at a larger size is the smallest size's cut where a
// subtree holds few enough triangles.
std::vector<std::pair<std::uint32_t, std::size_t>> leaf_counts_by_size(const Scene &scene,
                                                                     std::uint32_t max_depth = HierarchyOptions{}.max_depth);
// Of (size, leaf count) pairs in increasing size, the size whose count is
// nearest auto_leaf_count_target by ratio (the larger size on a tie);
// auto_leaf_triangles_max when there are none.
std::uint32_t size_nearest_leaf_count_target(const std::vector<std::pair<std::uint32_t, std::size_t>> &counts);
// The size auto_leaf_triangles builds with: that of leaf_counts_by_size.
std::uint32_t choose_leaf_triangles(const Scene &scene, std::uint32_t max_depth = HierarchyOptions{}.max_depth);

// Leaves not outside `frustum`, in node order.
std::vector<std::uint32_t> leaves_in_frustum(const Hierarchy &hierarchy, const Frustum &frustum);

// Per node, 1 when one of `leaves` is in its subtree (itself included), else
// 0: the nodes a traversal must open or draw to reach those leaves. Indices
// that are not nodes are ignored.
std::vector<std::uint8_t> subtrees_holding(const Hierarchy &hierarchy, const std::vector<std::uint32_t> &leaves);

}  // namespace occu
