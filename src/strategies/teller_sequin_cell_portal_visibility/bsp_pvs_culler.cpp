// SPDX-License-Identifier: MIT
#include "strategies/teller_sequin_cell_portal_visibility/family.h"

#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "scene/level.h"
#include "scene/scene.h"
#include "spatial/hierarchy.h"

namespace occu::strategies {

namespace {

// Which clusters each hierarchy leaf's triangles lie in: a triangle's
// face (Level::Face: a mesh's range of indices), the BSP leaves that
// list the face (leaf_faces: a face crossing a splitting plane is listed
// by every leaf it lies in) and their clusters.
struct LeafClusters {
    std::vector<std::vector<std::int32_t>> clusters;   // per hierarchy node (inner nodes: empty)
    std::vector<std::uint8_t> always;                  // per node: holds a triangle drawn whatever the eye's cluster
    std::size_t brush_entity_triangles = 0, unlisted_triangles = 0;
};

LeafClusters leaf_clusters(const Scene &scene, const Hierarchy &hierarchy)
{
    const Level &level = *scene.level;
    // Per face, the clusters of the leaves listing it (sorted, unique).
    std::vector<std::vector<std::int32_t>> face_clusters(level.faces.size());
    for (const Level::Leaf &leaf : level.leaves) {
        if (leaf.cluster < 0)
            continue;
        for (std::uint32_t k = leaf.first_leaf_face; k < leaf.first_leaf_face + leaf.leaf_face_count; ++k) {
            const std::uint32_t face = level.leaf_faces[k];
            std::vector<std::int32_t> &c = face_clusters[face];
            if (std::find(c.begin(), c.end(), leaf.cluster) == c.end())
                c.push_back(leaf.cluster);
        }
    }
    // Per mesh, its faces by the first index of their triangles.
    std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> faces_of_mesh(scene.meshes.size());
    for (std::uint32_t f = 0; f < level.faces.size(); ++f) {
        const Level::Face &face = level.faces[f];
        if (face.mesh >= 0 && std::size_t(face.mesh) < scene.meshes.size() && face.index_count)
            faces_of_mesh[std::size_t(face.mesh)].push_back({face.first_index, f});
    }
    for (auto &faces : faces_of_mesh)
        std::sort(faces.begin(), faces.end());

    LeafClusters out;
    const auto &nodes = hierarchy.nodes();
    out.clusters.resize(nodes.size());
    out.always.assign(nodes.size(), 0);
    for (std::uint32_t n = 0; n < nodes.size(); ++n) {
        if (!nodes[n].leaf())
            continue;
        std::vector<std::int32_t> &clusters = out.clusters[n];
        for (std::uint32_t t = nodes[n].first_triangle; t < nodes[n].first_triangle + nodes[n].triangle_count; ++t) {
            const TriangleRef &ref = hierarchy.triangles()[t];
            const auto &faces = faces_of_mesh[ref.mesh];
            auto it = std::upper_bound(faces.begin(), faces.end(), std::make_pair(ref.first_index, ~0u));
            // A triangle of no face the level records: drawn, to be safe.
            if (it == faces.begin() || ref.first_index >= (it - 1)->first + level.faces[(it - 1)->second].index_count) {
                out.always[n] = 1;
                continue;
            }
            const std::uint32_t f = (it - 1)->second;
            if (level.faces[f].model != 0) {
                // A brush entity's face: Quake III draws entities by their
                // bounds, not by the world's leaves, which do not list them.
                out.always[n] = 1;
                ++out.brush_entity_triangles;
                continue;
            }
            if (face_clusters[f].empty())
                ++out.unlisted_triangles;
            for (std::int32_t c : face_clusters[f])
                clusters.push_back(c);
        }
        std::sort(clusters.begin(), clusters.end());
        clusters.erase(std::unique(clusters.begin(), clusters.end()), clusters.end());
    }
    return out;
}

class BspPvsCuller final : public Culler {
public:
    explicit BspPvsCuller(const StrategyContext &context)
        : level_(*context.scene.level), hierarchy_(context.hierarchy),
          leaves_(leaf_clusters(context.scene, context.hierarchy))
    {
        for (const HierarchyNode &n : hierarchy_.nodes())
            if (n.leaf())
                scene_triangles_ += n.triangle_count;
    }

    void begin_frame(const Frame &frame) override
    {
        frustum_.emplace(frame.frustum);
        ++frames_;
        const std::int32_t leaf = level_.leaf_at(frame.camera.position);
        const std::int32_t cluster =
            leaf >= 0 && std::size_t(leaf) < level_.leaves.size() ? level_.leaves[std::size_t(leaf)].cluster : -1;
        // Quake III's renderer (R_MarkLeaves) marks every leaf when the
        // eye is in no cluster or the level has no visibility data.
        everything_ = cluster < 0 || level_.cluster_count == 0;
        if (everything_) {
            ++(cluster < 0 ? frames_outside_ : frames_unvised_);
            return;
        }
        if (cluster != cluster_) {
            cluster_ = cluster;
            std::vector<std::uint32_t> shown;
            set_triangles_now_ = 0;
            const auto &nodes = hierarchy_.nodes();
            for (std::uint32_t n = 0; n < nodes.size(); ++n) {
                if (!nodes[n].leaf())
                    continue;
                bool sees = leaves_.always[n];
                for (std::int32_t c : leaves_.clusters[n])
                    sees = sees || level_.cluster_sees(cluster, c);
                if (sees) {
                    shown.push_back(n);
                    set_triangles_now_ += nodes[n].triangle_count;
                }
            }
            shows_ = subtrees_holding(hierarchy_, shown);
        }
        ++frames_in_clusters_;
        set_triangles_ += set_triangles_now_;
    }

    void test(std::vector<NodeTest> &tests) override
    {
        for (NodeTest &t : tests) {
            if (frustum_->classify(t.box) == Frustum::Side::outside)
                t.result = Visibility::view_culled;
            else
                t.result = everything_ || shows_[t.node] ? Visibility::visible : Visibility::occluded;
        }
    }

    std::string note() const override
    {
        std::string s = std::to_string(frames_outside_) + " of " + std::to_string(frames_) +
                        " frames with the eye in no cluster (every cluster drawn there)";
        if (frames_unvised_)
            s += "; " + std::to_string(frames_unvised_) + " in a level without visibility data (everything drawn)";
        if (frames_in_clusters_ && scene_triangles_ > 0) {
            char share[128];
            std::snprintf(share, sizeof(share), "; in clusters, the PVS held %.3f%% of the scene's triangles",
                          100.0 * set_triangles_ / double(frames_in_clusters_) / scene_triangles_);
            s += share;
        }
        if (leaves_.brush_entity_triangles)
            s += "; " + std::to_string(leaves_.brush_entity_triangles) + " triangles of brush entities always drawn";
        if (leaves_.unlisted_triangles)
            s += "; " + std::to_string(leaves_.unlisted_triangles) +
                 " triangles of world faces in no cluster's leaf never drawn";
        return s;
    }

private:
    const Level &level_;
    const Hierarchy &hierarchy_;
    LeafClusters leaves_;
    std::optional<Frustum> frustum_;
    std::int32_t cluster_ = -1;      // the cluster shows_ was made for
    bool everything_ = true;
    std::vector<std::uint8_t> shows_;
    std::size_t frames_ = 0, frames_outside_ = 0, frames_unvised_ = 0, frames_in_clusters_ = 0;
    double scene_triangles_ = 0, set_triangles_ = 0, set_triangles_now_ = 0;
};

}  // namespace

StrategyFamily bsp_pvs_family()
{
    StrategyFamily f;
    f.name = "bsp-pvs";
    f.paper = "Quake III's PVS (q3map -vis): Teller and Sequin 1991, cell-portal visibility; Wonka et al. 2000, "
              "section 1.2";
    f.summary = "the level's own PVS: the eye's BSP cluster, drawing what lies in the clusters it sees, cut by the "
                "frustum";
    f.conservative = false;
    f.scene_requirements = {{"a Quake III level's BSP tree, clusters and visibility data (--scene "
                             "PAK.pk3:maps/NAME.bsp or NAME.bsp)",
                             [](const Scene &scene) { return scene.level != nullptr; }}};
    f.make = [](const StrategyContext &context, const Settings &) -> std::unique_ptr<Culler> {
        return std::make_unique<BspPvsCuller>(context);
    };
    return f;
}

}  // namespace occu::strategies
