// SPDX-License-Identifier: MIT
#include "strategies/leone_occluder_skins/family.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "occluders/depth_occluders.h"
#include "occluders/sources.h"
#include "raster/depth_rasterizer.h"
#include "spatial/hierarchy.h"

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
        if (triangle_test_)
            order_largest_first();
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
            if (box_test_ && t.leaf ? raster_.occluded(t.box, footprint->rect, z) : raster_.occluded(footprint->rect, z))
                t.result = Visibility::occluded;
            else if (triangle_test_ && t.leaf && triangles_occluded(t.node))
                t.result = Visibility::occluded;
        }
    }

    // Every triangle of the leaf, see-through ones included (GL draws
    // them), hidden pixel by pixel: what the leaf draws, tighter than its
    // box. The test stops at the first that shows, so the likeliest to
    // show go first: the one that showed when the leaf was last tested
    // (frames are coherent), then the largest.
    bool triangles_occluded(std::uint32_t node)
    {
        const HierarchyNode &n = hierarchy_.nodes()[node];
        const auto &triangles = hierarchy_.triangles();
        const auto first = largest_first_.begin() + n.first_triangle;
        for (auto j = first; j != first + n.triangle_count; ++j) {
            const TriangleRef &t = triangles[*j];
            const Mesh &mesh = scene_.meshes[t.mesh];
            if (!raster_.triangles_occluded(mesh.positions.data(), mesh.indices.data() + t.first_index, 1)) {
                std::rotate(first, j, j + 1);
                return false;
            }
        }
        return true;
    }

    // Each leaf's triangles by world area, the largest first.
    void order_largest_first()
    {
        const auto &triangles = hierarchy_.triangles();
        largest_first_.resize(triangles.size());
        std::vector<float> area(triangles.size());
        for (std::uint32_t i = 0; i < triangles.size(); ++i) {
            const Mesh &mesh = scene_.meshes[triangles[i].mesh];
            const std::uint32_t *idx = mesh.indices.data() + triangles[i].first_index;
            const glm::vec3 &a = mesh.positions[idx[0]], &b = mesh.positions[idx[1]], &c = mesh.positions[idx[2]];
            const float twice = glm::length(glm::cross(b - a, c - a));
            area[i] = std::isfinite(twice) ? twice : 0.0f;
            largest_first_[i] = i;
        }
        for (const HierarchyNode &n : hierarchy_.nodes())
            if (n.leaf())
                std::stable_sort(largest_first_.begin() + n.first_triangle,
                                 largest_first_.begin() + n.first_triangle + n.triangle_count,
                                 [&](std::uint32_t x, std::uint32_t y) { return area[x] > area[y]; });
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
    std::vector<std::uint32_t> largest_first_;   // occludee=triangles: hierarchy triangles, each leaf's by area,
                                                 // the last one seen to show moved first
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
        // Occlusion Culling fuses them, and leaves tested by what they draw.
        {"skins-triangles", "occluder-triangles=1024:coverage=merged:occludee=triangles"},
    };
    // The scene's own triangles beside the skins, in whole depth pixels and
    // merged (each culls at least what the one before it does); occludees
    // tested by their triangles where their box fails; the rectangle alone
    // (section 6); one farthest depth per polygon (section 5); the drawn
    // leaves' triangles with the switch-off's probes.
    f.test_variants = {
        StrategyTestVariant("skins:occluder-triangles=512"),
        StrategyTestVariant("skins:occluder-triangles=512:coverage=merged").drawing_at_most("skins:occluder-triangles=512"),
        StrategyTestVariant("skins:occluder-triangles=512:coverage=merged:occludee=triangles")
            .drawing_at_most("skins:occluder-triangles=512:coverage=merged"),
        StrategyTestVariant("skins:occluder-triangles=1024"),
        StrategyTestVariant("skins:occluder-triangles=1024:coverage=merged"),
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
