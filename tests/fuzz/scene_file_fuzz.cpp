// SPDX-License-Identifier: MIT
// Fuzzes user scenes (scene/scene_file.h) in the five formats occu's
// users bring: Wavefront OBJ, glTF 2 (.gltf, JSON with its buffers as
// base64 data URIs) and GLB (binary glTF) through assimp, PLY (ASCII and
// binary) and Quake III levels (.bsp, IBSP version 46) through occu's own
// readers. Any bytes are either a scene occu can use -- every mesh with
// triangles, indices inside it, finite vertices, normals and colours; a
// level's faces inside their meshes, its tree descending to a leaf from
// every spawn point -- or refused naming the file; every warning
// (primitives dropped) names the file too.
//
// One target per format, built from this file with OCCU_SCENE_FORMAT set
// (tests/meson.build: occu-fuzz-scene-file-obj, -ply, -gltf, -glb, -bsp), rather
// than one target whose first byte picks the extension: each format then
// has its own seed corpus (tests/fuzz/corpus/scene_file_<format>/, real
// files of Debian's assimp-testmodels: corpus/SCENE_SEEDS.md; small
// levels of tests/fuzz/make_bsp_seeds.py) and its own
// libFuzzer dictionary (tests/fuzz/dict/scene_file_<format>.dict: "nan",
// "inf", "1e39", huge element and accessor counts, NaN and infinity as
// float bytes), which libFuzzer takes one of per run; and no input is
// spent reading a GLB as OBJ. libFuzzer's own mutations do the rest
// (truncation, bit and byte flips, insertions, crossover), combined with
// the dictionary's words.
#include <cmath>
#include <vector>

#include "fuzz_input.h"
#include "scene/quake3_bsp.h"
#include "scene/scene_file.h"

#ifndef OCCU_SCENE_FORMAT
#error "build with -DOCCU_SCENE_FORMAT=obj (or ply, gltf, glb, bsp)"
#endif
#define OCCU_STRING2(x) #x
#define OCCU_STRING(x) OCCU_STRING2(x)

namespace {

bool finite(const glm::vec3 &v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void require(bool ok, const char *what)
{
    if (!ok) {
        std::fprintf(stderr, "loaded scene breaks its contract: %s\n", what);
        std::abort();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    const occu::fuzz::InputFile file(data, size, "." OCCU_STRING(OCCU_SCENE_FORMAT));
    std::vector<std::string> warnings;
    try {
        const occu::Scene scene = occu::load_scene(file.path(), &warnings);
        require(!scene.meshes.empty(), "no meshes");
        for (const occu::Mesh &m : scene.meshes) {
            require(!m.indices.empty() && m.indices.size() % 3 == 0, "a mesh without whole triangles");
            require(m.normals.size() == m.positions.size(), "normals not one per position");
            require(m.colors.empty() || m.colors.size() == m.positions.size(), "colours not one per position");
            require(finite(m.color), "a colour not finite");
            for (const glm::vec3 &p : m.positions)
                require(finite(p), "a vertex not finite");
            for (const glm::vec3 &n : m.normals)
                require(finite(n), "a normal not finite");
            for (const glm::vec3 &c : m.colors)
                require(finite(c), "a vertex colour not finite");
            for (std::uint32_t i : m.indices)
                require(i < m.positions.size(), "an index outside its mesh");
        }
        require(finite(scene.bounds.min) && finite(scene.bounds.max), "bounds not finite");
        if (scene.level) {
            const occu::Level &level = *scene.level;
            for (const occu::Level::Face &f : level.faces)
                require(f.mesh < 0 || (std::size_t(f.mesh) < scene.meshes.size() &&
                                       std::size_t(f.first_index) + f.index_count <= scene.meshes[std::size_t(f.mesh)].indices.size()),
                        "a face's triangles outside its mesh");
            for (const occu::LevelSpawn &s : level.spawns) {
                require(finite(s.eye) && finite(s.direction), "a spawn point not finite");
                const std::int32_t leaf = level.leaf_at(s.eye);
                require(leaf < std::int32_t(level.leaves.size()), "a spawn point's leaf outside the leaves");
                if (leaf >= 0)
                    level.cluster_sees(level.leaves[std::size_t(leaf)].cluster, 0);
            }
            for (const occu::Level::Leaf &l : level.leaves)
                require(std::size_t(l.first_leaf_face) + l.leaf_face_count <= level.leaf_faces.size(),
                        "a leaf's faces outside the leaf faces");
        }
    } catch (const std::runtime_error &e) {
        occu::fuzz::require_named(e, file.path());
    }
    for (const std::string &w : warnings)
        occu::fuzz::require_named(std::runtime_error(w), file.path());
    return 0;
}
