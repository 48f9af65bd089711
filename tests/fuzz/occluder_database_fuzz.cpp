// SPDX-License-Identifier: MIT
// Fuzzes the minimum-occluder-set database loader
// (strategies/poon_wang_opacity_maps/occluder_database.h): any bytes are
// either a database or refused naming the file.
#include "fuzz_input.h"
#include "strategies/poon_wang_opacity_maps/occluder_database.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    const occu::fuzz::InputFile file(data, size, ".db");
    try {
        const occu::OccluderDatabase db = occu::OccluderDatabase::load(file.path());
        (void)db.views.size();
    } catch (const std::runtime_error &e) {
        occu::fuzz::require_named(e, file.path());
    }
    return 0;
}
