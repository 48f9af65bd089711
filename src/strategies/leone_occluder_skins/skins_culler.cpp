// SPDX-License-Identifier: MIT
#include "strategies/leone_occluder_skins/family.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>

#include "occluders/depth_occluders.h"
#include "occluders/sources.h"
#include "raster/depth_rasterizer.h"
#include "spatial/hierarchy.h"
#include "strategies/leone_occluder_skins/triangle_clusters.h"

namespace occu::strategies {

namespace {

class OccluderSkinCuller final : public Culler {
public:
    OccluderSkinCuller(const StrategyContext &context, const Settings &settings)
        : scene_(context.scene), hierarchy_(context.hierarchy), settings_(settings),
          drawn_(settings.text("occluders") != "skins"),
          limit_(std::size_t(settings.integer("max-occluders"))), box_test_(settings.text("occludee") != "rect"),
          triangle_test_(settings.text("occludee") == "triangles")
    {
        options_.per_pixel_depth = settings.text("depth") == "pixel";
        options_.merge_partial_coverage = merges_partial_coverage(settings, int(settings.integer("map-divisor")));
        if (settings.text("occluders") != "drawn")
            occluders_.emplace(context.scene, settings, &context.hierarchy);
        if (triangle_test_) {
            clusters_.emplace(context.scene, context.hierarchy);
            last_shown_.assign(context.hierarchy.nodes().size(), ShownTriangle{});
        }
    }

    void begin_frame(const Frame &frame) override
    {
        frame_.emplace(frame);
        options_.divisor = map_divisor(settings_, frame.width, frame.height);
        raster_.begin(frame.view_projection, frame.width, frame.height, options_);
        if (occluders_)
            occluders_->render(frame, raster_, limit_);
        stats_.passes = 1;
    }

    void test(std::vector<NodeTest> &tests) override
    {
        const Frame &f = *frame_;
        for (NodeTest &t : tests) {
            const auto footprint = f.occlusion_candidate(t);
            if (!footprint)
                continue;
            // Behind every occluder pixel, with a margin for the box's float z.
            const float z = footprint->window_z_near - 1e-6f;
            if (triangle_test_ && t.leaf ? leaf_triangles_occluded(t, footprint->rect, z)
                : box_test_ && t.leaf    ? raster_.occluded(t.box, footprint->rect, z)
                                         : raster_.occluded(footprint->rect, z))
                t.result = Visibility::occluded;
        }
    }

    // occludee=triangles: every triangle of the leaf, see-through ones
    // included (GL draws them), hidden pixel by pixel: what the leaf
    // draws, tighter than its box. A leaf is hidden when its box is, or
    // else every cluster of its triangles (a few neighbours and their box)
    // is, by its box or else triangle by triangle: a hidden leaf's box
    // fails where its triangles leave gaps, which its clusters' boxes
    // mostly do not, so one box test stands for a cluster's triangles.
    // The test stops at the first triangle that shows, so the one that
    // showed when the leaf was last tested goes first (frames are
    // coherent), before the box's faces; each cluster's largest first.
    bool leaf_triangles_occluded(const NodeTest &t, const PixelRect &rect, float z)
    {
        if (raster_.occluded(rect, z))
            return true;
        ShownTriangle &shown = last_shown_[t.node];
        if (shown.slot != none) {
            const DepthRasterizer::TriangleCorners corners = {&shown.corners[0], &shown.corners[1], &shown.corners[2]};
            if (raster_.first_shown(&corners, 1) == 0)
                return false;
        }
        if (raster_.faces_occluded(t.box, z))
            return true;
        const Frame &f = *frame_;
        const std::uint32_t leaf_first = hierarchy_.nodes()[t.node].first_triangle;
        for (const TriangleClusters::Cluster *cluster = clusters_->begin(t.node); cluster != clusters_->end(t.node);
             ++cluster) {
            if (!cluster->box.empty()) {
                const auto footprint = f.footprint(cluster->box);
                if (footprint && raster_.occluded(cluster->box, footprint->rect, footprint->window_z_near - 1e-6f))
                    continue;
            }
            // The cluster's triangles at once (the rasterizer sets them up
            // in lanes), up to the first that shows: one block of corners.
            std::uint32_t which[TriangleClusters::cluster_triangles];
            DepthRasterizer::TriangleCorners corners[TriangleClusters::cluster_triangles];
            std::size_t count = 0;
            const std::uint32_t begin = leaf_first + cluster->first, end = begin + cluster->count;
            for (std::uint32_t slot = begin; slot < end; ++slot)
                if (slot != shown.slot) {
                    which[count] = slot;
                    corners[count++] = slot_corners(slot);
                }
            const std::size_t first = raster_.first_shown(corners, count);
            if (first < count) {
                shown.slot = which[first];
                std::copy_n(clusters_->corners(shown.slot), 3, shown.corners);
                return false;
            }
        }
        shown.slot = none;
        return true;
    }

    DepthRasterizer::TriangleCorners slot_corners(std::uint32_t slot) const
    {
        const glm::vec3 *c = clusters_->corners(slot);
        return {c, c + 1, c + 2};
    }

    void rendered(std::uint32_t node) override
    {
        if (!drawn_)
            return;
        const HierarchyNode &n = hierarchy_.nodes()[node];
        const auto &triangles = hierarchy_.triangles();
        // Its occluders only: the hierarchy puts the see-through triangles last.
        for (std::uint32_t i = n.first_triangle; i < n.first_triangle + n.occluder_triangles; ++i) {
            const Mesh &mesh = scene_.meshes[triangles[i].mesh];
            raster_.render_triangles(mesh.positions.data(), mesh.indices.data() + triangles[i].first_index, 1);
        }
    }

    CullerStats stats() const override { return stats_; }

private:
    const Scene &scene_;
    const Hierarchy &hierarchy_;
    Settings settings_;
    bool drawn_;
    std::size_t limit_;
    bool box_test_;
    bool triangle_test_;
    DepthRasterizer::Options options_;
    DepthRasterizer raster_;
    std::optional<DepthOccluders> occluders_;
    // occludee=triangles: each leaf's triangles by cluster, and the one
    // that last showed in each leaf: its slot (or none) and a copy of its
    // corners, tested first at the leaf's next test, where a visible leaf's
    // test mostly ends, without a read of the slots (megabytes on a city,
    // a cache miss a leaf).
    static constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
    struct ShownTriangle {
        glm::vec3 corners[3];
        std::uint32_t slot = none;
    };
    std::optional<TriangleClusters> clusters_;
    std::vector<ShownTriangle> last_shown_;
    std::optional<Frame> frame_;
    CullerStats stats_;
};

}  // namespace

StrategyFamily occluder_skins_family()
{
    using Role = SettingSpec::Role;
    StrategyFamily f;
    f.name = "skins";
    f.paper = "Leone et al., sections 4-7";
    f.summary = "occluder skins (or the frame's drawn triangles) in a CPU depth buffer, rectangles tested at one z";
    f.traversal.switch_off = true;
    f.settings = {
        choice_setting("occluders", {"skins", "drawn", "both"},
                       "the meshes' occluder skins, the triangles of the leaves drawn so far this frame, or both"),
        choice_setting("depth", {"pixel", "polygon"}, "depth per pixel, or one farthest depth per polygon"),
        choice_setting("occludee", {"box", "rect", "triangles"},
                       "a leaf is its screen rectangle at its nearest depth and, where that fails, its box's faces "
                       "pixel by pixel; or the rectangle alone (section 6); or, where the box fails too, its own "
                       "triangles pixel by pixel (what it draws, tighter than its box)"),
        map_size_setting(256, "depth pixels"),
        map_divisor_setting("depth pixel"),
        integer_setting("max-occluders", 256, 0, 1 << 24, Role::cost,
                        "skins rasterized per frame, largest on screen first", "0"),
    };
    f.occluder_sources = {
        {&skin_occluder_source(), [](const Settings &s) { return s.text("occluders") != "drawn"; }},
        {&triangle_occluder_source()},
    };
    f.presets = {
        {"skins-drawn", "occluders=drawn"},
        {"skins-both", "occluders=both"},
        // For scenes whose meshes have no volume for skins (levels, thin
        // walls): the scene's own largest triangles, fused as Masked
        // Occlusion Culling fuses them, and leaves tested by what they draw;
        // the triangle budget as many as the last frame's added to the
        // buffer (on the city's streets a few hundred cull what 1024 do).
        {"skins-triangles", "occluder-triangles=1024:coverage=merged:occludee=triangles:adapt-triangles=on"},
    };
    // The scene's own triangles beside the skins, in whole depth pixels and
    // merged (each culls at least what the one before it does); occludees
    // tested by their triangles where their box fails; their budget
    // adapted, and fixed; the rectangle alone
    // (section 6); one farthest depth per polygon (section 5); the drawn
    // leaves' triangles with the switch-off's probes.
    f.test_variants = {
        StrategyTestVariant("skins:occluder-triangles=512"),
        StrategyTestVariant("skins:occluder-triangles=512:coverage=merged").drawing_at_most("skins:occluder-triangles=512"),
        StrategyTestVariant("skins:occluder-triangles=512:coverage=merged:occludee=triangles")
            .drawing_at_most("skins:occluder-triangles=512:coverage=merged"),
        StrategyTestVariant("skins:occluder-triangles=1024"),
        StrategyTestVariant("skins:occluder-triangles=1024:coverage=merged"),
        // The budget adapted frame by frame, and skins-triangles' fixed.
        StrategyTestVariant("skins:occluder-triangles=512:coverage=merged:occludee=triangles:adapt-triangles=on"),
        StrategyTestVariant("skins-triangles:adapt-triangles=off"),
        StrategyTestVariant("skins:occludee=triangles"),
        StrategyTestVariant("skins:occludee=rect"),
        StrategyTestVariant("skins:depth=polygon"),
        // A buffer of its own resolution, the divisor from the frame's size
        // (3 at the tests' frames of 128 pixels), and the exact end.
        StrategyTestVariant("skins:map-size=50"),
        StrategyTestVariant("skins:map-divisor=1"),
        StrategyTestVariant("skins-drawn:occludee=triangles"),
        StrategyTestVariant("skins-drawn").with_probing_switch_off(),
    };
    f.make = [](const StrategyContext &context, const Settings &settings) -> std::unique_ptr<Culler> {
        return std::make_unique<OccluderSkinCuller>(context, settings);
    };
    return f;
}

}  // namespace occu::strategies
