// SPDX-License-Identifier: MIT
#include "culling/chained_culler.h"


namespace occu {

ChainedCuller::ChainedCuller(std::vector<std::pair<std::string, std::unique_ptr<Culler>>> stages)
    : stages_(std::move(stages))
{
}

void ChainedCuller::begin_frame(const Frame &frame)
{
    for (auto &stage : stages_)
        stage.second->begin_frame(frame);
}

void ChainedCuller::test(std::vector<NodeTest> &tests)
{
    for (std::size_t s = 0; s < stages_.size(); ++s) {
        Culler &stage = *stages_[s].second;
        if (s == 0) {
            stage.test(tests);
        } else {
            remaining_.clear();
            where_.clear();
            for (std::size_t i = 0; i < tests.size(); ++i)
                if (tests[i].result == Visibility::visible) {
                    NodeTest t;
                    t.node = tests[i].node;
                    t.box = tests[i].box;
                    t.leaf = tests[i].leaf;
                    remaining_.push_back(t);
                    where_.push_back(i);
                }
            if (remaining_.empty())
                break;
            stage.test(remaining_);
            for (std::size_t k = 0; k < remaining_.size(); ++k)
                tests[where_[k]].result = remaining_[k].result;
        }
    }
    for (NodeTest &t : tests)
        t.test_below = true;
}

void ChainedCuller::rendered(std::uint32_t node)
{
    for (auto &stage : stages_)
        stage.second->rendered(node);
}

CullerStats ChainedCuller::stats() const
{
    CullerStats sum;
    for (const auto &stage : stages_)
        sum.passes += stage.second->stats().passes;
    return sum;
}

std::string ChainedCuller::note() const
{
    std::string s;
    for (const auto &[name, culler] : stages_)
        if (const std::string n = culler->note(); !n.empty())
            s += (s.empty() ? "" : "; ") + name + ": " + n;
    return s;
}

}  // namespace occu
