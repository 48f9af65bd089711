// SPDX-License-Identifier: MIT
// Fuzzes the PVS database loader (strategies/wonka_view_cells/
// pvs_database.h): any bytes are either a database whose cells are finite
// triangles with area, whose sets name cells that exist with leaves in
// ascending order, and whose cells a ViewCells accepts, or refused naming the
// file.
#include <cmath>

#include "fuzz_input.h"
#include "strategies/wonka_view_cells/pvs_database.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    const occu::fuzz::InputFile file(data, size, ".pvs");
    try {
        const occu::PvsDatabase db = occu::PvsDatabase::load(file.path());
        for (const auto &t : db.cells)
            for (const glm::dvec2 &p : t)
                if (!std::isfinite(p.x) || !std::isfinite(p.y))
                    std::abort();   // loaded a corner the loader promises to refuse
        for (const auto &[cell, leaves] : db.visible) {
            if (cell >= db.cells.size())
                std::abort();
            for (std::size_t i = 1; i < leaves.size(); ++i)
                if (leaves[i] <= leaves[i - 1])
                    std::abort();
        }
        // The run time builds its locator from them: it must take them.
        const occu::ViewCells cells(db.cells, db.cell_options);
        (void)cells.locate(glm::vec3(0.0f));
    } catch (const std::runtime_error &e) {
        occu::fuzz::require_named(e, file.path());
    }
    return 0;
}
