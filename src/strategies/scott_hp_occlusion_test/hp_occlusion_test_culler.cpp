// SPDX-License-Identifier: MIT
#include "strategies/scott_hp_occlusion_test/family.h"

#include <optional>

#include "gl/occlusion_query.h"
#include "render/occlusion_proxy.h"
#include "render/scene_renderer.h"

namespace occu::strategies {

namespace {

class HpOcclusionTestCuller final : public Culler {
public:
    HpOcclusionTestCuller(const StrategyContext &context, const Settings &settings)
        : renderer_(context.renderer), leaf_triangles_(settings.text("proxy") == "triangles"),
          target_(gl::boolean_occlusion_query_target()), gl_(gl::QueryFunctions::load("hp"))
    {}
    ~HpOcclusionTestCuller() override
    {
        if (!queries_.empty())
            gl_.DeleteQueries(GLsizei(queries_.size()), queries_.data());
    }

    void begin_frame(const Frame &frame) override
    {
        frame_.emplace(frame);
        stats_ = {};
    }

    void test(std::vector<NodeTest> &tests) override
    {
        const Frame &f = *frame_;
        std::vector<std::size_t> queried;
        proxies_.clear();
        for (std::size_t i = 0; i < tests.size(); ++i) {
            NodeTest &t = tests[i];
            t.result = Visibility::visible;
            if (f.frustum.classify(t.box) == Frustum::Side::outside) {
                t.result = Visibility::view_culled;
            } else if (f.footprint(t.box)) {
                if (leaf_triangles_ && t.leaf) {
                    // The leaf's own triangles stand for it (no proxy box).
                    queried.push_back(i);
                    proxies_.push_back(Aabb{});
                } else if (const auto proxy = proxy_box(t.box, f.camera, f.view_projection, f.height)) {
                    // A box whose proxy cannot be drawn whole is visible untested.
                    queried.push_back(i);
                    proxies_.push_back(*proxy);
                }
            }
        }
        if (queried.empty())
            return;
        if (queries_.size() < queried.size()) {
            const std::size_t more = queried.size() - queries_.size();
            queries_.resize(queried.size());
            gl_.GenQueries(GLsizei(more), queries_.data() + (queries_.size() - more));
        }
        {
            const ProxyTestState proxy_state;
            const gl::AttribScope writes(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
            glDepthMask(GL_FALSE);
            for (std::size_t k = 0; k < queried.size(); ++k) {
                gl_.BeginQuery(target_, queries_[k]);
                const NodeTest &t = tests[queried[k]];
                if (leaf_triangles_ && t.leaf)
                    // All of them: a leaf whose see-through triangles show is visible.
                    renderer_.draw_leaf_flat(t.node, LeafPart::all);
                else
                    draw_proxy_box(proxies_[k]);
                gl_.EndQuery(target_);
            }
        }
        for (std::size_t k = 0; k < queried.size(); ++k) {
            GLuint passed = 0;   // a flag, or a count where the context has no flag
            gl_.GetQueryObjectuiv(queries_[k], GL_QUERY_RESULT, &passed);
            tests[queried[k]].result = passed == 0 ? Visibility::occluded : Visibility::visible;
        }
        stats_.passes += std::uint32_t(queried.size());
    }

    CullerStats stats() const override { return stats_; }

private:
    const SceneRenderer &renderer_;
    bool leaf_triangles_;
    GLenum target_;   // the HP test's flag (gl/occlusion_query.h)
    gl::QueryFunctions gl_;
    std::vector<GLuint> queries_;
    std::vector<Aabb> proxies_;   // of the queried boxes, in order (empty for a leaf drawn as its triangles)
    std::optional<Frame> frame_;
    CullerStats stats_;
};

}  // namespace

StrategyFamily hp_occlusion_test_family()
{
    StrategyFamily f;
    f.name = "hp";
    f.paper = "Scott, Olsen and Gannett 1998, the HP occlusion test "
              "(Moeller and Haines, VISUALIZE fx's hardware implementation)";
    f.summary = "one occlusion query per node box, front to back, the flag read before the box is drawn or opened";
    f.traversal.coherence = true;
    f.traversal.switch_off = true;
    f.settings = {
        choice_setting("proxy", {"box", "triangles"}, "what stands for a leaf in the query: its box or its triangles"),
    };
    // Leaves queried by their own triangles, which lie inside their box and
    // show nowhere it does not (so they cull at least what boxes do); the
    // switch-off's probes.
    f.test_variants = {
        StrategyTestVariant("hp:proxy=triangles").drawing_at_most("hp"),
        StrategyTestVariant("hp").with_probing_switch_off(),
    };
    f.make = [](const StrategyContext &context, const Settings &settings) -> std::unique_ptr<Culler> {
        return std::make_unique<HpOcclusionTestCuller>(context, settings);
    };
    return f;
}

}  // namespace occu::strategies
