// SPDX-License-Identifier: MIT
// The hierarchical Z-buffer (Greene, Kass and Miller; Moeller and Haines,
// "Hierarchical Z-Buffering and the Hierarchical Visibility Algorithm"):
// see family.h.
#include "strategies/greene_hierarchical_z_buffer/family.h"

#include <algorithm>
#include <optional>
#include <vector>

#include "gl/framebuffer.h"
#include "gl/state.h"
#include "occluders/depth_occluders.h"
#include "occluders/sources.h"
#include "raster/depth_rasterizer.h"
#include "render/scene_renderer.h"
#include "spatial/hierarchy.h"
#include "strategies/greene_hierarchical_z_buffer/z_pyramid.h"

namespace occu::strategies {

namespace {

class HierarchicalZBufferCuller final : public Culler {
public:
    HierarchicalZBufferCuller(const StrategyContext &context, const Settings &settings)
        : renderer_(context.renderer), settings_(settings), last_frame_(settings.text("source") == "last-frame"),
          limit_(std::size_t(settings.integer("max-occluders")))
    {
        options_.per_pixel_depth = settings.text("depth") == "pixel";
        options_.merge_partial_coverage = merges_partial_coverage(settings, int(settings.integer("map-divisor")));
        if (!last_frame_)
            occluders_.emplace(context.scene, settings, &context.hierarchy);
    }

    void begin_frame(const Frame &frame) override
    {
        frame_.emplace(frame);
        options_.divisor = map_divisor(settings_, frame.width, frame.height);
        if (last_frame_) {
            last_frame_depth(frame);
        } else {
            raster_.begin(frame.view_projection, frame.width, frame.height, options_);
            occluders_->render(frame, raster_, limit_);
            raster_.read(depth_);
            pyramid_.build(raster_.width(), raster_.height(), depth_.data());
        }
        drawn_.clear();
        stats_.passes = 1;
    }

    void test(std::vector<NodeTest> &tests) override
    {
        const Frame &f = *frame_;
        const int k = options_.divisor;
        for (NodeTest &t : tests) {
            const auto footprint = f.occlusion_candidate(t);
            if (!footprint || footprint->rect.empty())
                continue;
            // The pyramid's pixels that hold the footprint's, from the
            // coarsest level enclosing them down, only where it fails.
            const PixelRect m = footprint->rect.to_map(k).clamped({0, 0, pyramid_.width(), pyramid_.height()});
            const float z = footprint->window_z_near - 1e-6f;
            // A leaf the pyramid keeps is tested again by its box's faces
            // in the skins' depth buffer, pixel by pixel, as skins does.
            if (pyramid_.occluded(m, z) || (t.leaf && !last_frame_ && raster_.faces_occluded(t.box, z)))
                t.result = Visibility::occluded;
        }
    }

    void rendered(std::uint32_t node) override { drawn_.push_back(node); }

    CullerStats stats() const override { return stats_; }

private:
    // The two-pass scheme of GPU culling: the depth of the leaves the last
    // frame drew, rendered in this frame's view, stands for this frame's
    // occluders. Drawn at full resolution into the strategy's own
    // framebuffer and read back; reduced by map-divisor to the farthest
    // depth of each block, so the test stays conservative.
    void last_frame_depth(const Frame &frame)
    {
        previous_.swap(drawn_);
        const int w = frame.width, h = frame.height, k = options_.divisor;
        if (!target_)
            target_.emplace(w, h);
        target_->resize(w, h);
        full_.resize(std::size_t(w) * std::size_t(h));
        {
            gl::Framebuffer::Bind bind(*target_);
            gl::AttribScope state(GL_ENABLE_BIT | GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_POLYGON_BIT);
            gl::MatrixScope matrices;
            gl::load_camera(frame.camera);
            glEnable(GL_DEPTH_TEST);
            glEnable(GL_CULL_FACE);
            glDepthFunc(GL_LESS);
            glDepthMask(GL_TRUE);
            glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
            glClearDepth(1.0);
            glClear(GL_DEPTH_BUFFER_BIT);
            for (std::uint32_t n : previous_)
                renderer_.draw_leaf_flat(n);
            glReadPixels(0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, full_.data());
        }
        const int mw = (w + k - 1) / k, mh = (h + k - 1) / k;
        depth_.assign(std::size_t(mw) * std::size_t(mh), 0.0f);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                float &d = depth_[std::size_t(y / k) * std::size_t(mw) + std::size_t(x / k)];
                d = std::max(d, full_[std::size_t(y) * std::size_t(w) + std::size_t(x)]);
            }
        pyramid_.build(mw, mh, depth_.data());
    }

    const SceneRenderer &renderer_;
    Settings settings_;
    bool last_frame_;
    std::size_t limit_;
    DepthRasterizer::Options options_;
    DepthRasterizer raster_;
    std::optional<DepthOccluders> occluders_;
    std::optional<gl::Framebuffer> target_;
    std::vector<float> full_, depth_;
    std::vector<std::uint32_t> drawn_, previous_;
    ZPyramid pyramid_;
    std::optional<Frame> frame_;
    CullerStats stats_;
};

}  // namespace

StrategyFamily hierarchical_z_buffer_family()
{
    using Role = SettingSpec::Role;
    StrategyFamily f;
    f.name = "hzb";
    f.paper = "Greene, Kass and Miller 1993 (Moeller and Haines, hierarchical Z-buffering)";
    f.summary = "a Z-pyramid of the skins' CPU depth, or of last frame's visible leaves, tested coarse to fine";
    f.traversal.switch_off = true;
    f.settings = {
        choice_setting("source", {"skins", "last-frame"},
                       "the occluder skins' CPU depth buffer, or the depth of the leaves the last frame drew"),
        choice_setting("depth", {"pixel", "polygon"}, "skins: depth per pixel, or one farthest depth per polygon"),
        map_size_setting(256, "pyramid pixels at level 0"),
        map_divisor_setting("pyramid pixel at level 0"),
        integer_setting("max-occluders", 256, 0, 1 << 24, Role::cost,
                        "skins rasterized per frame, largest on screen first", "0"),
    };
    f.occluder_sources = {
        {&skin_occluder_source(), [](const Settings &s) { return s.text("source") == "skins"; }},
        {&triangle_occluder_source()},
    };
    f.presets = {
        {"hzb-last-frame", "source=last-frame"},
    };
    // The scene's own triangles beside the skins, in whole depth pixels and
    // merged (which culls at least what whole pixels do).
    f.test_variants = {
        StrategyTestVariant("hzb:occluder-triangles=512"),
        StrategyTestVariant("hzb:occluder-triangles=512:coverage=merged").drawing_at_most("hzb:occluder-triangles=512"),
        StrategyTestVariant("hzb:map-size=50"),
        StrategyTestVariant("hzb:map-divisor=1"),
    };
    f.make = [](const StrategyContext &context, const Settings &settings) -> std::unique_ptr<Culler> {
        return std::make_unique<HierarchicalZBufferCuller>(context, settings);
    };
    return f;
}

}  // namespace occu::strategies
