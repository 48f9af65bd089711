// Fuzzes user scenes (scene/scene_file.h) as Wavefront OBJ text through
// assimp: any bytes are either a scene with finite vertices and indices
// inside its meshes, or refused naming the file.
#include <cmath>

#include "fuzz_input.h"
#include "scene/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    const occu::fuzz::InputFile file(data, size, ".obj");
    try {
        const occu::Scene scene = occu::load_scene(file.path());
        for (const occu::Mesh &m : scene.meshes) {
            for (const glm::vec3 &p : m.positions)
                if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                    std::abort();
            for (std::uint32_t i : m.indices)
                if (i >= m.positions.size())
                    std::abort();
        }
    } catch (const std::runtime_error &e) {
        occu::fuzz::require_named(e, file.path());
    }
    return 0;
}
