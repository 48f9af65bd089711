// SPDX-License-Identifier: MIT
// Hierarchical occlusion maps (Zhang et al.; Moeller and Haines,
// "Hierarchical Occlusion Map"): see family.h.
#include "strategies/zhang_hierarchical_occlusion_maps/family.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "occluders/depth_occluders.h"
#include "occluders/sources.h"
#include "raster/depth_rasterizer.h"
#include "strategies/zhang_hierarchical_occlusion_maps/hierarchical_occlusion_map.h"

namespace occu::strategies {

namespace {

class HierarchicalOcclusionMapCuller final : public Culler {
public:
    HierarchicalOcclusionMapCuller(const StrategyContext &context, const Settings &settings)
        : occluders_(context.scene, settings, &context.hierarchy),
          threshold_(float(1.0 - settings.number("tolerance"))), budget_(double(settings.integer("occluders"))),
          max_budget_(double(settings.integer("occluders"))), adapt_(settings.on("adapt-budget")),
          deb_(int(settings.integer("depth-regions")), int(settings.integer("depth-regions")))
    {
        // Occluders are rasterized at the frame's resolution, white where
        // they cover a frame pixel; occlusion map 0 averages blocks of
        // map-divisor x map-divisor of them, so its opacities are the
        // covered share of each block, as in the chapter's example (a
        // 128 x 128 map of a 1024 x 1024 image, O_0 = 1 - n/64 for holes of
        // n pixels). The depth estimation buffer takes each occluder's
        // farthest depth, Zhang's estimate (the farthest vertex): one depth
        // per polygon.
        divisor_ = int(settings.integer("map-divisor"));
        options_.divisor = 1;
        options_.per_pixel_depth = false;
        // One sample a pixel: merging closes only the seams along shared
        // edges that pass within the edge margin of a pixel's centre.
        options_.merge_partial_coverage = merges_partial_coverage(settings, options_.divisor);
    }

    void begin_frame(const Frame &frame) override
    {
        adapt();
        frame_.emplace(frame);
        raster_.begin(frame.view_projection, frame.width, frame.height, options_);
        occluders_.render(frame, raster_, std::size_t(std::lround(budget_)));
        raster_.read(depth_);
        const int w = raster_.width(), h = raster_.height(), k = divisor_;
        const int mw = (w + k - 1) / k, mh = (h + k - 1) / k;
        // Occlusion map 0: the covered share of each block (a block past
        // the frame's edge averages the pixels it has).
        opacity_.assign(std::size_t(mw) * std::size_t(mh), 0.0f);
        for (int y = 0; y < h; ++y) {
            const float *row = depth_.data() + std::size_t(y) * std::size_t(w);
            float *out = opacity_.data() + std::size_t(y / k) * std::size_t(mw);
            for (int mx = 0, x = 0; mx < mw; ++mx) {
                int covered = 0;
                for (const int end = std::min(w, x + k); x < end; ++x)
                    covered += row[x] < 1.0f;
                out[mx] += float(covered);
            }
        }
        for (int my = 0; my < mh; ++my)
            for (int mx = 0; mx < mw; ++mx) {
                const int pixels = (std::min(w, (mx + 1) * k) - mx * k) * (std::min(h, (my + 1) * k) - my * k);
                opacity_[std::size_t(my) * std::size_t(mw) + std::size_t(mx)] /= float(pixels);
            }
        hom_.build(mw, mh, opacity_.data());
        deb_.build(w, h, depth_.data());
        tested_ = occluded_ = 0;
        stats_.passes = 1;
    }

    void test(std::vector<NodeTest> &tests) override
    {
        const Frame &f = *frame_;
        for (NodeTest &t : tests) {
            const auto footprint = f.occlusion_candidate(t);
            if (!footprint || footprint->rect.empty())
                continue;
            ++tested_;
            const PixelRect m = footprint->rect.to_map(divisor_).clamped({0, 0, hom_.width(), hom_.height()});
            // The overlap test, then the depth test (Zhang: both must pass).
            if (hom_.overlaps(m, threshold_) && deb_.behind(footprint->rect, footprint->window_z_near - 1e-6f)) {
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

    DepthOccluders occluders_;
    float threshold_;
    double budget_, max_budget_;
    bool adapt_;
    DepthRasterizer::Options options_;
    DepthRasterizer raster_;
    int divisor_;
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
    f.paper = "Zhang, Manocha, Hudson and Hoff 1997 (Moeller and Haines, hierarchical occlusion maps)";
    f.summary = "an opacity pyramid of the skins and a depth estimation buffer, overlap then depth test";
    f.traversal.switch_off = true;
    f.settings = {
        number_setting("tolerance", 0.0, 0.0, 1.0, Role::approximation,
                       "1 - the opacity threshold O_0: the share of a level-0 texel's frame pixels that may be holes"),
        integer_setting("occluders", 256, 1, 1 << 24, Role::cost,
                        "skins rendered into the occlusion map per frame, largest on screen first"),
        on_off_setting("adapt-budget", false, Role::cost,
                       "grow the occluder count while little is culled, shrink it while much is"),
        integer_setting("map-divisor", 4, 1, 64, Role::cost, "frame pixels per occlusion-map pixel at level 0, each way"),
        integer_setting("depth-regions", 64, 1, 4096, Role::cost, "depth estimation buffer regions, each way"),
    };
    f.occluder_sources = {{&skin_occluder_source()}, {&triangle_occluder_source()}};
    // The scene's own triangles beside the skins in the occlusion map; the
    // occluder count adapted from frame to frame along a route.
    f.test_variants = {StrategyTestVariant("hom:occluder-triangles=512"), StrategyTestVariant("hom:adapt-budget=on")};
    f.make = [](const StrategyContext &context, const Settings &settings) -> std::unique_ptr<Culler> {
        return std::make_unique<HierarchicalOcclusionMapCuller>(context, settings);
    };
    return f;
}

}  // namespace occu::strategies
