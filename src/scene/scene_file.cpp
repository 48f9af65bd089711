#include "scene/scene_file.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

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

}  // namespace

Scene load_scene(const std::string &path)
{
    Assimp::Importer importer;
    const aiScene *in = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_GenSmoothNormals |
                                                    aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
    if (!in || (in->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !in->mRootNode)
        throw std::runtime_error("cannot read scene '" + path + "': " + importer.GetErrorString());
    Scene out;
    add_node(*in, *in->mRootNode, aiMatrix4x4(), out);
    if (out.triangle_count() == 0)
        throw std::runtime_error("scene '" + path + "' holds no triangles");
    out.update_bounds();
    return out;
}

}  // namespace occu
