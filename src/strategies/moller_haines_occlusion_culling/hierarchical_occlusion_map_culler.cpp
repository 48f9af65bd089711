// Hierarchical occlusion maps (Zhang et al.; Moeller and Haines,
// "Hierarchical Occlusion Map"): see family.h.
#include "strategies/moller_haines_occlusion_culling/family.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "maps/hierarchical_occlusion_map.h"
#include "occluders/skin_occluders.h"
#include "raster/depth_rasterizer.h"

namespace occu::strategies {

namespace {

class HierarchicalOcclusionMapCuller final : public Culler {
public:
    HierarchicalOcclusionMapCuller(const StrategyContext &context, const Settings &settings)
        : skins_(context.scene, settings.text("skin-database"), int(settings.integer("skin-boxes"))),
          threshold_(float(1.0 - settings.number("tolerance"))), budget_(double(settings.integer("occluders"))),
          max_budget_(double(settings.integer("occluders"))), adapt_(settings.on("adapt-budget")),
          deb_(int(settings.integer("depth-regions")), int(settings.integer("depth-regions")))
    {
        options_.divisor = int(settings.integer("map-divisor"));
        // The depth estimation buffer takes each occluder's farthest depth,
        // Zhang's estimate (the farthest vertex), so one depth per polygon.
        options_.per_pixel_depth = false;
    }

    void begin_frame(const Frame &frame) override
    {
        adapt();
        frame_.emplace(frame);
        raster_.begin(frame.view_projection, frame.width, frame.height, options_);
        skins_.render(frame, raster_, std::size_t(std::lround(budget_)));
        raster_.read(depth_);
        // Occlusion map 0: white where an occluder covers the depth pixel.
        opacity_.resize(depth_.size());
        for (std::size_t i = 0; i < depth_.size(); ++i)
            opacity_[i] = depth_[i] < 1.0f ? 1.0f : 0.0f;
        hom_.build(raster_.width(), raster_.height(), opacity_.data());
        deb_.build(raster_.width(), raster_.height(), depth_.data());
        tested_ = occluded_ = 0;
        stats_.passes = 1;
    }

    void test(std::vector<NodeTest> &tests) override
    {
        const Frame &f = *frame_;
        for (NodeTest &t : tests) {
            t.result = Visibility::visible;
            if (f.frustum.classify(t.box) == Frustum::Side::outside) {
                t.result = Visibility::view_culled;
                continue;
            }
            const auto footprint = f.footprint(t.box);
            if (!footprint || footprint->rect.empty())
                continue;
            ++tested_;
            const PixelRect m =
                footprint->rect.to_map(options_.divisor).clamped({0, 0, hom_.width(), hom_.height()});
            // The overlap test, then the depth test (Zhang: both must pass).
            if (hom_.overlaps(m, threshold_) && deb_.behind(m, footprint->window_z_near - 1e-6f)) {
                t.result = Visibility::occluded;
                ++occluded_;
            }
        }
    }

    CullerStats stats() const override { return stats_; }

private:
    // Zhang's adaptive occluder count: where little of what is tested is
    // culled, more occluders; where much is, fewer (the paper also weighs
    // the frame rate; occu keeps culling decisions independent of timing,
    // so the culled share alone steers). Never above the `occluders` setting.
    void adapt()
    {
        if (!adapt_ || tested_ == 0)
            return;
        const double culled = double(occluded_) / double(tested_);
        if (culled < 0.5)
            budget_ = std::min(max_budget_, budget_ * 1.25 + 1.0);
        else if (culled > 0.8)
            budget_ = std::max(4.0, budget_ * 0.9);
    }

    SkinOccluders skins_;
    float threshold_;
    double budget_, max_budget_;
    bool adapt_;
    DepthRasterizer::Options options_;
    DepthRasterizer raster_;
    std::vector<float> depth_, opacity_;
    HierarchicalOcclusionMap hom_;
    DepthEstimationBuffer deb_;
    std::uint64_t tested_ = 0, occluded_ = 0;
    std::optional<Frame> frame_;
    CullerStats stats_;
};

}  // namespace

StrategyFamily hierarchical_occlusion_map_family()
{
    using Role = SettingSpec::Role;
    StrategyFamily f;
    f.name = "hom";
    f.paper = "Moeller and Haines, hierarchical occlusion maps (Zhang et al.)";
    f.summary = "an opacity pyramid of the skins and a depth estimation buffer, overlap then depth test";
    f.draws_occluders = true;
    f.settings = {
        number_setting("tolerance", 0.0, 0.0, 1.0, Role::approximation,
                       "1 - the opacity threshold O_0 at level 0; level k needs 1 - tolerance / 4^k"),
        integer_setting("occluders", 256, 1, 1 << 24, Role::cost,
                        "skins rendered into the occlusion map per frame, largest on screen first"),
        on_off_setting("adapt-budget", false, Role::cost,
                       "grow the occluder count while little is culled, shrink it while much is"),
        integer_setting("map-divisor", 2, 1, 64, Role::cost, "frame pixels per occlusion-map pixel, each way"),
        integer_setting("depth-regions", 64, 1, 4096, Role::cost, "depth estimation buffer regions, each way"),
        integer_setting("skin-boxes", 8, 1, 1 << 16, Role::cost, "skin boxes per mesh, the largest first"),
        path_setting("skin-database", "the skin database (occu-preprocess skins); without one, skins are made at start"),
    };
    f.make = [](const StrategyContext &context, const Settings &settings) -> std::unique_ptr<Culler> {
        return std::make_unique<HierarchicalOcclusionMapCuller>(context, settings);
    };
    return f;
}

}  // namespace occu::strategies
