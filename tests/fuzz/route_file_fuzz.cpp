// SPDX-License-Identifier: MIT
// Fuzzes route files (camera/route.h): any bytes are either cameras whose
// positions and view directions are finite, or refused naming the file.
#include <cmath>

#include "camera/route.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    const occu::fuzz::InputFile file(data, size, ".route");
    const occu::Aabb bounds = occu::Aabb::of({0, 0, 0}, {100, 50, 100});
    try {
        for (const occu::Camera &c : occu::make_route(file.path(), bounds, occu::CityOptions{}, 10, 1.0f)) {
            const glm::vec3 d = c.target - c.position;
            for (int axis = 0; axis < 3; ++axis)
                if (!std::isfinite(c.position[axis]) || !std::isfinite(d[axis]))
                    std::abort();   // a camera the loader promises to refuse
        }
    } catch (const std::runtime_error &e) {
        occu::fuzz::require_named(e, file.path());
    }
    return 0;
}
