// SPDX-License-Identifier: MIT
#include "strategies/bartz_occlusion_unit/family.h"

#include <algorithm>
#include <optional>

#include "culling/adaptive_culling.h"
#include "culling/occlusion_question.h"
#include "gl/occlusion_unit.h"
#include "render/occlusion_proxy.h"
#include "render/scene_renderer.h"
#include "spatial/hierarchy.h"

namespace occu::strategies {

namespace {

class OcclusionUnitCuller final : public Culler {
public:
    OcclusionUnitCuller(const StrategyContext &context, const Settings &settings)
        : renderer_(context.renderer), shared_passes_(settings.text("passes") == "shared"),
          leaf_triangles_(settings.text("proxy") == "triangles"), tolerance_(settings.number("tolerance")),
          max_test_area_(settings.number("max-test-area")),
          mode_(occlusion_question(settings, tolerance_))
    {
        // The unit holds at most max_tiles tiles (4096 on occu's drivers): a
        // frame's disjoint footprints go into as few passes as it allows.
        tiles_per_pass_ = std::size_t(std::max(unit_.max_tiles(), 1));
    }

    void begin_frame(const Frame &frame) override
    {
        frame_.emplace(frame);
        GLint viewport[4];
        glGetIntegerv(GL_VIEWPORT, viewport);
        origin_x_ = viewport[0];
        origin_y_ = viewport[1];
        stats_ = {};
    }

    void test(std::vector<NodeTest> &tests) override
    {
        const Frame &f = *frame_;
        rects_.assign(tests.size(), PixelRect{});
        proxies_.assign(tests.size(), Aabb{});
        std::vector<std::size_t> pending;
        const double viewport_area = double(f.width) * double(f.height);
        for (std::size_t i = 0; i < tests.size(); ++i) {
            NodeTest &t = tests[i];
            t.result = Visibility::visible;
            if (f.frustum.classify(t.box) == Frustum::Side::outside) {
                t.result = Visibility::view_culled;
                continue;
            }
            const auto footprint = f.footprint(t.box);
            if (!footprint || double(footprint->rect.area()) > max_test_area_ * viewport_area)
                continue;   // visible untested
            if (!(leaf_triangles_ && t.leaf)) {
                // A box whose proxy cannot be drawn whole is visible untested.
                const auto proxy = proxy_box(t.box, f.camera, f.view_projection, f.height);
                if (!proxy)
                    continue;
                proxies_[i] = *proxy;
            }
            rects_[i] = footprint->rect;
            pending.push_back(i);
        }
        // Passes of boxes with pairwise disjoint footprints (or any, shared).
        for (const std::vector<std::size_t> &pass : disjoint_groups(rects_, std::move(pending), tiles_per_pass_, shared_passes_))
            run_pass(tests, pass);
    }

    CullerStats stats() const override { return stats_; }

private:
    // Each tile grows outwards to whole 64 x 64 blocks of the viewport where
    // that takes in no other member's footprint: its counts cannot change
    // (only its own box's fragments fall in it), and llvmpipe sums bins that
    // tiles cover whole without sorting fragments into tiles (its bins are
    // 64 x 64; patch 0004).
    std::vector<PixelRect> tiles_for(const std::vector<std::size_t> &members) const
    {
        constexpr int bin = 64;
        const PixelRect viewport{0, 0, frame_->width, frame_->height};
        std::vector<PixelRect> tiles;
        for (std::size_t i : members) {
            PixelRect r = rects_[i];
            const PixelRect grown = PixelRect{r.x0 / bin * bin, r.y0 / bin * bin, (r.x1 + bin - 1) / bin * bin,
                                              (r.y1 + bin - 1) / bin * bin}
                                        .clamped(viewport);
            const bool alone = std::none_of(members.begin(), members.end(),
                                            [&](std::size_t j) { return j != i && grown.overlaps(rects_[j]); });
            if (alone && !grown.empty())
                r = grown;
            tiles.push_back({r.x0 + origin_x_, r.y0 + origin_y_, r.x1 + origin_x_, r.y1 + origin_y_});
        }
        return tiles;
    }

    void run_pass(std::vector<NodeTest> &tests, const std::vector<std::size_t> &members)
    {
        const ProxyTestState proxy_state;   // render/occlusion_proxy.h
        gl::OcclusionPass pass(unit_, mode_, tiles_for(members));
        for (std::size_t i : members) {
            if (leaf_triangles_ && tests[i].leaf)
                // All of them: a leaf whose see-through triangles show is visible.
                renderer_.draw_leaf_flat(tests[i].node, LeafPart::all);
            else
                draw_proxy_box(proxies_[i]);
        }
        const std::vector<gl::OcclusionRecord> &records = pass.end();
        ++stats_.passes;
        for (std::size_t k = 0; k < members.size(); ++k) {
            const gl::OcclusionRecord &r = records[k];
            const bool occluded = adaptive_culling_occludes(r.nohc, r.phc, tolerance_);
            tests[members[k]].result = occluded ? Visibility::occluded : Visibility::visible;
        }
    }

    gl::OcclusionUnit unit_;
    const SceneRenderer &renderer_;
    bool shared_passes_, leaf_triangles_;
    double tolerance_, max_test_area_;
    gl::OcclusionMode mode_;   // conservative only where tolerance 0 needs no counts
    std::size_t tiles_per_pass_ = 64;
    std::optional<Frame> frame_;
    GLint origin_x_ = 0, origin_y_ = 0;
    std::vector<PixelRect> rects_;
    std::vector<Aabb> proxies_;   // per test: what a box test draws (proxy_box)
    CullerStats stats_;
};

}  // namespace

StrategyFamily occlusion_unit_family()
{
    using Role = SettingSpec::Role;
    StrategyFamily f;
    f.name = "ou";
    f.paper = "Bartz, Meissner and Huettner 1998, sections 3 and 5";
    f.summary = "hierarchical occlusion tests of node boxes with GL_MESAX_occlusion_unit, one tile per box";
    f.traversal.coherence = true;
    f.traversal.switch_off = true;
    f.settings = {
        choice_setting("passes", {"disjoint", "shared"},
                       "boxes share a pass only where their footprints are disjoint, or always"),
        choice_setting("proxy", {"box", "triangles"}, "what stands for a leaf in the test: its box or its triangles"),
        number_setting("tolerance", 0.0, 0.0, 0.999, Role::approximation,
                       "adaptive culling: occluded when NOHC <= tolerance * PHC"),
        occlusion_answer_setting(),
        number_setting("max-test-area", 0.25, 0.0001, 1.0, Role::cost,
                       "boxes covering more of the viewport are taken as visible untested", "1"),
    };
    f.presets = {
        {"ou-shared", "passes=shared"},
        {"occu-hier", "", true},
        {"occu-hier-shared", "passes=shared", true},
    };
    // Every box tested (none taken as visible for its size), strictly front
    // to back and in batches (section 3), culling more than half of what
    // the unculled frame draws; leaves tested by their own triangles,
    // which lie inside their box (culling at least what boxes do); shared
    // passes with temporal coherence; the switch-off's probes. A tile
    // counts only the fragments in its box's footprint (section 3.1), an
    // HP query (scott_hp_occlusion_test) all of its grown box's: hp sees
    // at least what ou sees, and culls about as much or less.
    f.test_variants = {
        StrategyTestVariant("ou:max-test-area=1").in_batches_of(1),
        StrategyTestVariant("ou:max-test-area=1").drawing_at_most("none", 0.5).drawing_at_most("hp", 100.0 / 99.0),
        StrategyTestVariant("ou:proxy=triangles:max-test-area=1").drawing_at_most("ou:max-test-area=1"),
        StrategyTestVariant("ou-shared").in_batches_of(32).with_coherence(),
        StrategyTestVariant("ou").with_probing_switch_off(),
        StrategyTestVariant("ou:answer=exact"),
    };
    f.make = [](const StrategyContext &context, const Settings &settings) -> std::unique_ptr<Culler> {
        return std::make_unique<OcclusionUnitCuller>(context, settings);
    };
    return f;
}

}  // namespace occu::strategies
