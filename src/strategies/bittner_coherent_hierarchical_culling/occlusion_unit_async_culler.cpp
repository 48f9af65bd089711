// SPDX-License-Identifier: MIT
#include "strategies/bittner_coherent_hierarchical_culling/occlusion_unit_async_culler.h"

#include <algorithm>
#include <optional>

#include "culling/adaptive_culling.h"
#include "culling/occlusion_question.h"
#include "gl/occlusion_unit.h"
#include "render/occlusion_proxy.h"

namespace occu::strategies {

namespace {

class OcclusionUnitAsyncCuller final : public AsyncCuller {
public:
    explicit OcclusionUnitAsyncCuller(const Settings &settings)
        : threshold_(settings.number("tolerance")), shared_passes_(settings.text("passes") == "shared"),
          mode_(occlusion_question(settings, threshold_))
    {
        // The unit holds at most max_tiles tiles; a batch is one pass.
        tiles_per_pass_ = std::size_t(std::clamp<long>(settings.integer("batch"), 1, std::max(unit_.max_tiles(), 1)));
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

    std::size_t batch_capacity() const override { return tiles_per_pass_; }
    bool shares_overlapping() const override { return shared_passes_; }

    // The boxes' proxies; the tile is a single box's footprint, or the union
    // of the non-empty footprints of several.
    bool prepare(AsyncTest &test) const override
    {
        const Frame &f = *frame_;
        std::vector<Aabb> proxies;
        std::optional<PixelRect> tile;
        for (const Aabb &box : test.boxes) {
            const auto footprint = f.footprint(box);
            const auto proxy = footprint ? proxy_box(box, f.camera, f.view_projection, f.height) : std::nullopt;
            if (!proxy)
                return false;
            proxies.push_back(*proxy);
            const PixelRect &r = footprint->rect;
            if (test.boxes.size() == 1)
                tile = r;
            else if (!r.empty())
                tile = tile ? PixelRect{std::min(tile->x0, r.x0), std::min(tile->y0, r.y0), std::max(tile->x1, r.x1),
                                        std::max(tile->y1, r.y1)}
                            : r;
        }
        test.boxes = std::move(proxies);
        test.area = tile.value_or(PixelRect{});
        return true;
    }

    Batch issue(std::vector<AsyncTest> tests) override
    {
        Batch b;
        if (free_.empty()) {
            b = slots_.size();
            slots_.push_back({std::make_unique<gl::AsyncOcclusionPass>(unit_), {}});
        }
        else {
            b = free_.back();
            free_.pop_back();
        }
        Slot &slot = slots_[b];
        std::vector<PixelRect> tiles;
        for (const AsyncTest &t : tests) {
            const PixelRect &r = t.area;
            tiles.push_back({r.x0 + origin_x_, r.y0 + origin_y_, r.x1 + origin_x_, r.y1 + origin_y_});
        }
        {
            const ProxyTestState proxy_state;   // render/occlusion_proxy.h
            slot.pass->begin(mode_, tiles);
            for (const AsyncTest &t : tests)
                for (const Aabb &proxy : t.boxes)
                    draw_proxy_box(proxy);
            slot.pass->end();
        }
        ++stats_.passes;
        slot.conditional.assign(tests.size(), 0);
        return b;
    }

    bool ready(Batch batch) override { return slots_[batch].pass->available(); }

    Visibility answer(Batch batch, std::size_t k) override
    {
        Slot &slot = slots_[batch];
        const gl::OcclusionRecord &r = slot.pass->records()[k];
        // A conditional draw: the GL's decision, made again on the record.
        const bool visible = slot.conditional[k] ? gl::ConditionalTileRender::passes(r, 0, float(threshold_))
                                                 : !adaptive_culling_occludes(r.nohc, r.phc, threshold_);
        return visible ? Visibility::visible : Visibility::occluded;
    }

    // GL_QUERY_WAIT: llvmpipe bins the draw with the predicate and its
    // rasterizer decides once the pass is done; the CPU does not wait.
    // Emulated, the records are there and the CPU decides (draws() false:
    // not drawn, as the records say).
    bool draw_if_visible(Batch batch, std::size_t k, const std::function<void()> &draw) override
    {
        Slot &slot = slots_[batch];
        slot.conditional[k] = 1;
        gl::ConditionalTileRender c(*slot.pass, k, 0, float(threshold_), true);
        if (c.draws())
            draw();
        return c.draws();
    }

    void release(Batch batch) override { free_.push_back(batch); }

    CullerStats stats() const override { return stats_; }

    std::string note() const override
    {
        if (unit_.native_async())
            return {};
        return "chc: GL_MESAX_occlusion_unit_async is absent, so its passes are emulated on glRenderMode and each "
               "waits for the rasterizer at its end, as ou's do";
    }

private:
    struct Slot {
        std::unique_ptr<gl::AsyncOcclusionPass> pass;
        std::vector<std::uint8_t> conditional;   // per test: drawn under its condition
    };

    gl::OcclusionUnit unit_;
    double threshold_;
    bool shared_passes_;
    gl::OcclusionMode mode_;   // conservative only where tolerance 0 needs no counts
    std::size_t tiles_per_pass_ = 64;
    std::optional<Frame> frame_;
    GLint origin_x_ = 0, origin_y_ = 0;
    CullerStats stats_;
    std::vector<Slot> slots_;
    std::vector<Batch> free_;   // slots to reuse, the last released first
};

}  // namespace

std::unique_ptr<AsyncCuller> make_occlusion_unit_async_culler(const Settings &settings)
{
    return std::make_unique<OcclusionUnitAsyncCuller>(settings);
}

}  // namespace occu::strategies
