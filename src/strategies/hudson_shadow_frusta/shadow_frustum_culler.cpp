// SPDX-License-Identifier: MIT
// Shadow frusta (Hudson et al.; Moeller and Haines, "Occlusion Culling
// Algorithms", section "Shadow Culling"): see family.h.
#include "strategies/hudson_shadow_frusta/family.h"

#include <limits>
#include <optional>
#include <vector>

#include "occluders/shadow_occluders.h"
#include "occluders/sources.h"
#include "spatial/hierarchy.h"
#include "strategies/hudson_shadow_frusta/shadow_frusta.h"

namespace occu::strategies {

namespace {

constexpr std::uint32_t no_occluder = std::numeric_limits<std::uint32_t>::max();

class ShadowFrustumCuller final : public Culler {
public:
    ShadowFrustumCuller(const StrategyContext &context, const Settings &settings)
        : occluders_(context.scene, settings),
          count_(std::size_t(settings.integer("occluders"))),
          last_culler_(context.hierarchy.nodes().size(), no_occluder), slot_(occluders_.id_limit(), -1)
    {
    }

    void begin_frame(const Frame &frame) override
    {
        frame_.emplace(frame);
        for (const Volume &v : volumes_)
            slot_[v.id] = -1;
        volumes_.clear();
        // The chapter: "At runtime the algorithms first perform view-frustum
        // culling, and then identify good occluders": the frustum is the
        // caller's; the occluders' shadow frusta are built once per frame.
        const glm::dvec3 eye(frame.camera.position);
        for (const ShadowOccluder &o : occluders_.choose(frame, count_)) {
            const Aabb &box = occluders_.boxes()[o.box];
            const auto region = o.face < 0 ? box_shadow(eye, box) : polygon_shadow(eye, box_face(box, o.face));
            if (!region)
                continue;   // the eye on one of its planes: it hides nothing for certain
            slot_[o.id] = int(volumes_.size());
            volumes_.push_back({o.id, *region});
        }
    }

    void test(std::vector<NodeTest> &tests) override
    {
        const Frame &f = *frame_;
        for (NodeTest &t : tests) {
            if (!f.occlusion_candidate(t) || volumes_.empty())
                continue;
            // Hudson et al. keep "the objects that were culled by an
            // occluder": the one that culled this node last is tried first.
            std::uint32_t &last = last_culler_[t.node];
            const int first = last == no_occluder ? -1 : slot_[last];
            if (first >= 0 && volumes_[std::size_t(first)].region.holds(t.box)) {
                t.result = Visibility::occluded;
                continue;
            }
            for (int i = 0; i < int(volumes_.size()); ++i)
                if (i != first && volumes_[std::size_t(i)].region.holds(t.box)) {
                    t.result = Visibility::occluded;
                    last = volumes_[std::size_t(i)].id;
                    break;
                }
        }
    }

    CullerStats stats() const override { return {}; }

private:
    struct Volume {
        std::uint32_t id;
        ConvexRegion region;
    };

    ShadowOccluders occluders_;
    std::size_t count_;
    std::vector<std::uint32_t> last_culler_;   // per node, the occluder that culled it last
    std::vector<int> slot_;                    // per occluder id, its place in volumes_ this frame, or -1
    std::vector<Volume> volumes_;
    std::optional<Frame> frame_;
};

}  // namespace

StrategyFamily shadow_frustum_family()
{
    StrategyFamily f;
    f.name = "shadow";
    f.paper = "Hudson et al. 1997 (Moeller and Haines, shadow culling)";
    f.summary = "boxes wholly inside the shadow frustum of one of a few large skin occluders, in object space";
    // No drawing, but every node is tested against every occluder's
    // shadow frustum: on the open route, where nothing is hidden, that costs
    // more than it saves, and the switch-off gives it back.
    f.traversal.switch_off = true;
    f.occluder_sources = {{&shadow_occluder_source()}, {&skin_occluder_source()}};
    f.presets = {
        {"shadow-faces", "aggregate=off"},
    };
    // More occluders than the paper's eight hide at least as much.
    f.test_variants = {StrategyTestVariant("shadow:occluders=64").drawing_at_most("shadow")};
    f.make = [](const StrategyContext &context, const Settings &settings) -> std::unique_ptr<Culler> {
        return std::make_unique<ShadowFrustumCuller>(context, settings);
    };
    return f;
}

}  // namespace occu::strategies
