// SPDX-License-Identifier: MIT
// Fuzzes the occluder-skin database loader
// (occluders/occluder_skins.h): any bytes are either a
// database whose boxes are finite and not inverted, or refused naming the
// file.
#include <cmath>

#include "fuzz_input.h"
#include "occluders/occluder_skins.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    const occu::fuzz::InputFile file(data, size, ".txt");
    try {
        const occu::OccluderSkinDatabase db = occu::OccluderSkinDatabase::load(file.path());
        for (const auto &[mesh, boxes] : db.skins)
            for (const occu::Aabb &b : boxes)
                for (int axis = 0; axis < 3; ++axis)
                    if (!std::isfinite(b.min[axis]) || !std::isfinite(b.max[axis]) || b.min[axis] > b.max[axis])
                        std::abort();   // loaded a box the loader promises to refuse
    } catch (const std::runtime_error &e) {
        occu::fuzz::require_named(e, file.path());
    }
    return 0;
}
