// SPDX-License-Identifier: MIT
// Strategies in sequence (a chain, culling/registry.h: "bsp-pvs+ou-shared"):
// each stage tests only the nodes every stage before it found visible, so
// a precomputed set (a PVS) can cut the frame first and an occlusion
// strategy cull what remains (Moeller and Haines, "Occlusion Culling
// Algorithms": the general algorithm after view-frustum and portal
// culling). A node is occluded or view-culled by the first stage that says
// so; visible when every stage says visible.
//
// Hints to leave a node's descendants untested (NodeTest::test_below) are
// dropped: the traversal draws such descendants without calling any
// stage, so the stages before the one that gave the hint would not see them.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "culling/culler.h"

namespace occu {

class ChainedCuller final : public Culler {
public:
    // The stages, first to last, each with the name its note is given under.
    explicit ChainedCuller(std::vector<std::pair<std::string, std::unique_ptr<Culler>>> stages);

    void begin_frame(const Frame &frame) override;
    void test(std::vector<NodeTest> &tests) override;
    void rendered(std::uint32_t node) override;
    CullerStats stats() const override;
    std::string note() const override;

private:
    std::vector<std::pair<std::string, std::unique_ptr<Culler>>> stages_;
    std::vector<NodeTest> remaining_;
    std::vector<std::size_t> where_;
};

}  // namespace occu
