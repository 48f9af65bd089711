#include "scene/scene_file.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cmath>
#include <stdexcept>

namespace occu {

namespace {

void add_node(const aiScene &in, const aiNode &node, const aiMatrix4x4 &parent, Scene &out)
{
    const aiMatrix4x4 transform = parent * node.mTransformation;
    aiMatrix3x3 normal_matrix(transform);
    normal_matrix.Inverse().Transpose();
    for (unsigned i = 0; i < node.mNumMeshes; ++i) {
        const aiMesh &m = *in.mMeshes[node.mMeshes[i]];
        if (!(m.mPrimitiveTypes & aiPrimitiveType_TRIANGLE))
            continue;
        Mesh mesh;
        mesh.name = m.mName.C_Str();
        for (unsigned v = 0; v < m.mNumVertices; ++v) {
            const aiVector3D p = transform * m.mVertices[v];
            aiVector3D n = m.mNormals ? normal_matrix * m.mNormals[v] : aiVector3D(0, 1, 0);
            n.Normalize();
            mesh.positions.emplace_back(p.x, p.y, p.z);
            mesh.normals.emplace_back(n.x, n.y, n.z);
        }
        for (unsigned f = 0; f < m.mNumFaces; ++f)
            if (m.mFaces[f].mNumIndices == 3)
                mesh.indices.insert(mesh.indices.end(),
                                    {m.mFaces[f].mIndices[0], m.mFaces[f].mIndices[1], m.mFaces[f].mIndices[2]});
        aiColor4D diffuse(0.8f, 0.8f, 0.8f, 1.0f);
        if (m.mMaterialIndex < in.mNumMaterials)
            in.mMaterials[m.mMaterialIndex]->Get(AI_MATKEY_COLOR_DIFFUSE, diffuse);
        mesh.color = {diffuse.r, diffuse.g, diffuse.b};
        if (!mesh.indices.empty())
            out.meshes.push_back(std::move(mesh));
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c)
        add_node(in, *node.mChildren[c], transform, out);
}

// The file's own vertices, before post-processing: joining identical
// vertices compares positions, and a NaN vertex of an OBJ file is merged
// into a finite one there, leaving no trace to check afterwards.
void require_finite_file_vertices(const aiScene &in, const std::string &source)
{
    for (unsigned m = 0; m < in.mNumMeshes; ++m) {
        const aiMesh &mesh = *in.mMeshes[m];
        for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
            const aiVector3D &p = mesh.mVertices[v];
            if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))
                continue;
            // The mesh as the file has it, for the message (this throws).
            Mesh copy;
            copy.name = mesh.mName.C_Str();
            for (unsigned w = 0; w < mesh.mNumVertices; ++w)
                copy.positions.emplace_back(mesh.mVertices[w].x, mesh.mVertices[w].y, mesh.mVertices[w].z);
            require_finite_vertices(copy, m, source);
        }
    }
}

}  // namespace

Scene load_scene(const std::string &path)
{
    Assimp::Importer importer;
    const aiScene *in = importer.ReadFile(path, 0);
    if (in && !(in->mFlags & AI_SCENE_FLAGS_INCOMPLETE) && in->mRootNode) {
        require_finite_file_vertices(*in, "scene '" + path + "'");
        in = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_GenSmoothNormals |
                                          aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
    }
    if (!in || (in->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !in->mRootNode)
        throw std::runtime_error("cannot read scene '" + path + "': " + importer.GetErrorString());
    Scene out;
    add_node(*in, *in->mRootNode, aiMatrix4x4(), out);
    if (out.triangle_count() == 0)
        throw std::runtime_error("scene '" + path + "' holds no triangles");
    // Node transforms can take finite vertices beyond float range.
    require_finite_vertices(out, "scene '" + path + "' (its node transforms applied)");
    out.update_bounds();
    return out;
}

}  // namespace occu
