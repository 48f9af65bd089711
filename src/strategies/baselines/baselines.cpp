// SPDX-License-Identifier: MIT
#include "strategies/baselines/family.h"

#include <optional>
#include <stdexcept>

#include "evaluation/oracle.h"
#include "spatial/hierarchy.h"

namespace occu::strategies {

namespace {

class NoCulling final : public Culler {
public:
    void begin_frame(const Frame &) override {}
    void test(std::vector<NodeTest> &tests) override
    {
        for (NodeTest &t : tests)
            t.result = Visibility::visible;
    }
};

class FrustumCulling final : public Culler {
public:
    void begin_frame(const Frame &frame) override { frustum_.emplace(frame.frustum); }
    void test(std::vector<NodeTest> &tests) override
    {
        for (NodeTest &t : tests)
            t.result = frustum_->classify(t.box) == Frustum::Side::outside ? Visibility::view_culled
                                                                           : Visibility::visible;
    }

private:
    std::optional<Frustum> frustum_;
};

// A node is drawn or opened when a leaf below it is in the oracle's
// visible set; the rest is occluded, or view-culled outside the frustum.
class IdealCulling final : public Culler {
public:
    explicit IdealCulling(const Hierarchy &hierarchy) : hierarchy_(hierarchy) {}
    void begin_frame(const Frame &frame) override
    {
        if (!frame.truth)
            throw std::runtime_error("ideal draws the oracle's visible leaves and needs the oracle's answer "
                                     "for each frame (walkthrough: --oracle on)");
        frustum_.emplace(frame.frustum);
        shows_ = subtrees_holding(hierarchy_, frame.truth->visible);
    }
    void test(std::vector<NodeTest> &tests) override
    {
        for (NodeTest &t : tests) {
            if (shows_[t.node])
                t.result = Visibility::visible;
            else
                t.result = frustum_->classify(t.box) == Frustum::Side::outside ? Visibility::view_culled
                                                                               : Visibility::occluded;
        }
    }

private:
    const Hierarchy &hierarchy_;
    std::optional<Frustum> frustum_;
    std::vector<std::uint8_t> shows_;
};

}  // namespace

StrategyFamily no_culling_family()
{
    StrategyFamily f;
    f.name = "none";
    f.paper = "the unculled reference";
    f.summary = "draws every leaf";
    f.make = [](const StrategyContext &, const Settings &) -> std::unique_ptr<Culler> {
        return std::make_unique<NoCulling>();
    };
    return f;
}

StrategyFamily frustum_culling_family()
{
    StrategyFamily f;
    f.name = "vfc";
    f.paper = "Moeller and Haines, the general algorithm's baseline";
    f.summary = "view-frustum culling only";
    f.make = [](const StrategyContext &, const Settings &) -> std::unique_ptr<Culler> {
        return std::make_unique<FrustumCulling>();
    };
    return f;
}

StrategyFamily ideal_family()
{
    StrategyFamily f;
    f.name = "ideal";
    f.paper = "the exact-visibility oracle (Poon and Wang, section 6: the exact visible set)";
    f.summary = "draws exactly the leaves the oracle sees: the floor of any culled frame";
    f.needs_truth = true;
    f.make = [](const StrategyContext &context, const Settings &) -> std::unique_ptr<Culler> {
        return std::make_unique<IdealCulling>(context.hierarchy);
    };
    return f;
}

}  // namespace occu::strategies
