// SPDX-License-Identifier: MIT
#include "scene/scene_file.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <stb/stb_image.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <stdexcept>

#include "scene/field.h"
#include "scene/palette.h"
#include "scene/pk3_archive.h"
#include "scene/quake3_look.h"
#include "scene/ply_file.h"
#include "scene/scene_file_guard.h"

namespace occu {

namespace {

// A colour of the file as an albedo: clamped to [0, 1]; `otherwise` where
// a component is not a number.
glm::vec3 usable_colour(const aiColor4D &c, const glm::vec3 &otherwise)
{
    if (!std::isfinite(c.r) || !std::isfinite(c.g) || !std::isfinite(c.b))
        return otherwise;
    return glm::clamp(glm::vec3(c.r, c.g, c.b), 0.0f, 1.0f);
}

// The diffuse colour of the mesh's material, where the file gives one; a
// facade hue of the palette, another for each mesh, where it does not
// (no material, or the importer's default material, which every mesh
// without one shares).
glm::vec3 file_colour(const aiScene &in, const aiMesh &m, std::size_t mesh_number)
{
    const glm::vec3 own = building_colours(std::uint32_t(mesh_number), 0.5f, 0.0f).wall;
    if (m.mMaterialIndex >= in.mNumMaterials)
        return own;
    const aiMaterial &material = *in.mMaterials[m.mMaterialIndex];
    aiString name;
    aiColor4D diffuse;
    if (material.Get(AI_MATKEY_COLOR_DIFFUSE, diffuse) != aiReturn_SUCCESS ||
        (material.Get(AI_MATKEY_NAME, name) == aiReturn_SUCCESS && std::strcmp(name.C_Str(), AI_DEFAULT_MATERIAL_NAME) == 0))
        return own;
    return usable_colour(diffuse, own);
}

// Where warnings go: `warnings` when given, standard error otherwise.
struct Warnings {
    std::vector<std::string> *list;
    void operator()(const std::string &w) const
    {
        if (list)
            list->push_back(w);
        else
            std::fprintf(stderr, "occu: warning: %s\n", w.c_str());
    }
};

std::string mesh_name(const aiMesh &m, unsigned number)
{
    return m.mName.length ? "'" + std::string(m.mName.C_Str()) + "'" : std::to_string(number) + " (unnamed)";
}

// The diffuse picture of `material`, as the file names it (a path, or
// "*N" for the file's N-th embedded texture); empty where it has none.
// glTF's base colour is the diffuse picture where a file gives no diffuse one.
std::string diffuse_picture(const aiMaterial &material)
{
    for (aiTextureType type : {aiTextureType_DIFFUSE, aiTextureType_BASE_COLOR}) {
        aiString path;
        if (material.GetTextureCount(type) > 0 && material.GetTexture(type, 0, &path) == aiReturn_SUCCESS &&
            path.length > 0)
            return path.C_Str();
    }
    return "";
}

// The texture coordinates channel `material`'s diffuse picture reads (0 unless the file says).
unsigned diffuse_channel(const aiMaterial &material)
{
    int channel = 0;
    if (material.Get(AI_MATKEY_UVWSRC(aiTextureType_DIFFUSE, 0), channel) != aiReturn_SUCCESS || channel < 0 ||
        channel >= AI_MAX_NUMBER_OF_TEXTURECOORDS)
        channel = 0;
    return unsigned(channel);
}

// What the look of a model needs beyond its meshes: per mesh of the scene
// (Scene::meshes), the material whose picture it shows, or -1.
struct ModelLook {
    bool wanted = false;
    std::vector<long> material;
};

void add_node(const aiScene &in, const aiNode &node, const aiMatrix4x4 &parent, Scene &out, const std::string &source,
              const Warnings &warn, ModelLook &look)
{
    const aiMatrix4x4 transform = parent * node.mTransformation;
    aiMatrix3x3 normal_matrix(transform);
    normal_matrix.Inverse().Transpose();
    for (unsigned i = 0; i < node.mNumMeshes; ++i) {
        const aiMesh &m = *in.mMeshes[node.mMeshes[i]];
        const std::string what = source + ": mesh " + mesh_name(m, node.mMeshes[i]);
        if (!(m.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) {
            warn(what + " holds " + std::to_string(m.mNumFaces) + " points or lines and no triangles; dropped");
            continue;
        }
        Mesh mesh;
        mesh.name = m.mName.C_Str();
        std::size_t bad_normals = 0;
        for (unsigned v = 0; v < m.mNumVertices; ++v) {
            const aiVector3D p = transform * m.mVertices[v];
            aiVector3D n = m.mNormals ? normal_matrix * m.mNormals[v] : aiVector3D(0, 1, 0);
            n.Normalize();
            // A zero or non-finite normal of the file, or a transform
            // that flattens the mesh: none to light with.
            if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) {
                n = aiVector3D(0, 1, 0);
                ++bad_normals;
            }
            mesh.positions.emplace_back(p.x, p.y, p.z);
            mesh.normals.emplace_back(n.x, n.y, n.z);
        }
        std::size_t not_triangles = 0, outside = 0;
        for (unsigned f = 0; f < m.mNumFaces; ++f) {
            const aiFace &face = m.mFaces[f];
            if (face.mNumIndices != 3) {
                ++not_triangles;
                continue;
            }
            if (face.mIndices[0] >= m.mNumVertices || face.mIndices[1] >= m.mNumVertices ||
                face.mIndices[2] >= m.mNumVertices) {
                ++outside;
                continue;
            }
            mesh.indices.insert(mesh.indices.end(), {face.mIndices[0], face.mIndices[1], face.mIndices[2]});
        }
        if (bad_normals)
            warn(what + ": " + std::to_string(bad_normals) + " of its " + std::to_string(m.mNumVertices) +
                 " normals are zero or not finite; (0, 1, 0) instead");
        if (not_triangles)
            warn(what + ": " + std::to_string(not_triangles) + " of its " + std::to_string(m.mNumFaces) +
                 " faces are not triangles; dropped");
        if (outside)
            warn(what + ": " + std::to_string(outside) + " of its " + std::to_string(m.mNumFaces) +
                 " faces have indices beyond its " + std::to_string(m.mNumVertices) + " vertices; dropped");
        mesh.color = file_colour(in, m, out.meshes.size());
        if (m.HasVertexColors(0))
            for (unsigned v = 0; v < m.mNumVertices; ++v)
                mesh.colors.push_back(usable_colour(m.mColors[0][v], mesh.color));
        // The look: the coordinates of the material's diffuse picture
        // (decoded later, once per picture, for the meshes kept).
        long material = -1;
        if (look.wanted && m.mMaterialIndex < in.mNumMaterials) {
            const aiMaterial &mat = *in.mMaterials[m.mMaterialIndex];
            const unsigned channel = diffuse_channel(mat);
            if (!diffuse_picture(mat).empty() && m.HasTextureCoords(channel)) {
                material = long(m.mMaterialIndex);
                std::size_t bad = 0;
                for (unsigned v = 0; v < m.mNumVertices; ++v) {
                    const aiVector3D &t = m.mTextureCoords[channel][v];
                    if (!std::isfinite(t.x) || !std::isfinite(t.y)) {
                        mesh.texcoords.emplace_back(0.0f, 0.0f);
                        ++bad;
                        continue;
                    }
                    // assimp's coordinates have v up from the picture's
                    // bottom row (OpenGL's convention); the look's pictures
                    // are uploaded top row first (scene/scene.h: Image), so t = 1 - v.
                    mesh.texcoords.emplace_back(t.x, 1.0f - t.y);
                }
                if (bad)
                    warn(what + ": " + std::to_string(bad) + " of its " + std::to_string(m.mNumVertices) +
                         " texture coordinates are not finite; read as 0");
                // A picture without a diffuse colour is shown as it is,
                // not tinted by the palette's stand-in hue.
                aiColor4D diffuse;
                if (mat.Get(AI_MATKEY_COLOR_DIFFUSE, diffuse) != aiReturn_SUCCESS)
                    mesh.color = glm::vec3(1.0f);
            }
        }
        // Triangles with no surface (scene/scene.h), as the node placed them.
        remove_collinear_triangles(mesh);
        if (mesh.indices.empty()) {
            warn(what + " holds no triangles (" + std::to_string(m.mNumVertices) + " vertices, " +
                 std::to_string(m.mNumFaces) + " faces); dropped");
        } else {
            out.meshes.push_back(std::move(mesh));
            if (look.wanted)
                look.material.push_back(material);
        }
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c)
        add_node(in, *node.mChildren[c], transform, out, source, warn, look);
}

// Decodes `bytes` (any format stb_image reads) as RGBA8, top row first;
// false with stb's reason in `why` when it cannot.
bool decode_picture(const unsigned char *bytes, std::size_t size, Image &image, std::string &why)
{
    if (size == 0 || size > std::size_t(1) << 30) {
        why = size ? "too large" : "empty";
        return false;
    }
    int w = 0, h = 0, channels = 0;
    stbi_uc *pixels = stbi_load_from_memory(bytes, int(size), &w, &h, &channels, 4);
    if (!pixels) {
        why = stbi_failure_reason() ? stbi_failure_reason() : "not a picture stb_image reads";
        return false;
    }
    image.width = w;
    image.height = h;
    image.rgba.assign(pixels, pixels + std::size_t(w) * std::size_t(h) * 4);
    stbi_image_free(pixels);
    return true;
}

// The file `name` in `directory`, matched without regard to case where no
// file has exactly that name (models made on Windows name their pictures
// in whatever case); empty when there is none.
std::filesystem::path file_in(const std::filesystem::path &directory, const std::string &name)
{
    std::error_code error;
    if (std::filesystem::is_regular_file(directory / name, error))
        return directory / name;
    auto lower = [](std::string t) {
        for (char &c : t)
            c = char(std::tolower(static_cast<unsigned char>(c)));
        return t;
    };
    const std::string wanted = lower(name);
    for (std::filesystem::directory_iterator it(directory, error), end; !error && it != end; it.increment(error))
        if (lower(it->path().filename().string()) == wanted && it->is_regular_file(error))
            return it->path();
    return {};
}

// Where the picture a material names is: the file's embedded texture
// ("*N", or one whose name matches; `embedded` set), else a file beside the
// model: the path relative to the model's directory (Windows separators
// read as '/', and a path from a Windows drive's root read as relative),
// else its bare file name in the model's directory, each file name matched
// without regard to case where no file has it exactly. Returns the place's
// name (the first place tried, when none holds a file).
std::string locate_picture(const aiScene &in, const std::string &model, const std::string &name,
                           const aiTexture *&embedded)
{
    embedded = in.GetEmbeddedTexture(name.c_str());
    if (embedded || (!name.empty() && name[0] == '*'))
        return "embedded texture " + name;
    std::string relative = name;
    const bool windows = relative.find('\\') != std::string::npos;
    std::replace(relative.begin(), relative.end(), '\\', '/');
    if (windows)
        relative.erase(0, relative.find_first_not_of('/'));
    const std::filesystem::path directory = std::filesystem::path(model).parent_path();
    const std::filesystem::path given = std::filesystem::path(relative).is_absolute() ? std::filesystem::path(relative)
                                                                                    : directory / relative;
    for (const std::filesystem::path &place : {given, directory / given.filename()}) {
        const std::filesystem::path found = file_in(place.parent_path(), place.filename().string());
        if (!found.empty())
            return found.lexically_normal().string();
    }
    return given.lexically_normal().string();
}

// Decodes the picture at `where` (locate_picture); false with why in `why`.
bool read_picture(const aiTexture *embedded, const std::string &where, Image &image, std::string &why)
{
    if (embedded) {
        if (embedded->mHeight == 0)   // compressed: mWidth bytes of a PNG, JPEG, ...
            return decode_picture(reinterpret_cast<const unsigned char *>(embedded->pcData), embedded->mWidth, image, why);
        // Raw texels, BGRA, top row first.
        image.width = int(embedded->mWidth);
        image.height = int(embedded->mHeight);
        image.rgba.clear();
        for (std::size_t i = 0; i < std::size_t(embedded->mWidth) * embedded->mHeight; ++i) {
            const aiTexel &t = embedded->pcData[i];
            image.rgba.insert(image.rgba.end(), {t.r, t.g, t.b, t.a});
        }
        return true;
    }
    if (where.rfind("embedded texture ", 0) == 0) {
        why = "the file embeds no such texture";
        return false;
    }
    std::ifstream f(where, std::ios::binary);
    if (!f) {
        why = "no such file";
        return false;
    }
    const std::vector<char> bytes{std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
    return decode_picture(reinterpret_cast<const unsigned char *>(bytes.data()), bytes.size(), image, why);
}

// Sets Mesh::image of the meshes whose material has a diffuse picture
// (look.material), decoding each picture once (by where it is, whatever
// the materials call it) and only those a kept mesh shows. A picture that
// cannot be read leaves its meshes in their materials' colours (texture
// coordinates dropped) and is named in a warning.
void read_model_pictures(const aiScene &in, const std::string &path, Scene &out, const ModelLook &look,
                         const Warnings &warn)
{
    std::map<std::string, std::int32_t> decoded;   // where the picture is -> Scene::images (-1: failed)
    std::vector<std::string> failed;
    for (std::size_t i = 0; i < out.meshes.size() && i < look.material.size(); ++i) {
        Mesh &mesh = out.meshes[i];
        if (look.material[i] < 0)
            continue;
        const std::string name = diffuse_picture(*in.mMaterials[look.material[i]]);
        const aiTexture *embedded = nullptr;
        const std::string where = locate_picture(in, path, name, embedded);
        auto [it, fresh] = decoded.emplace(where, -1);
        if (fresh) {
            Image image;
            std::string why;
            if (read_picture(embedded, where, image, why)) {
                image.name = where;
                it->second = std::int32_t(out.images.size());
                out.images.push_back(std::move(image));
            } else {
                failed.push_back("'" + name + "' (" + where + ": " + why + ")");
            }
        }
        mesh.image = it->second;
        if (mesh.image < 0)
            mesh.texcoords.clear();
    }
    if (!failed.empty()) {
        std::string names;
        for (std::size_t i = 0; i < failed.size() && i < 5; ++i)
            names += (i ? ", " : "") + failed[i];
        warn("scene '" + path + "': " + std::to_string(failed.size()) + " of its materials' pictures cannot be read (" +
             names + (failed.size() > 5 ? ", ..." : "") + "); their meshes drawn in their materials' colours");
    }
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

// Faces of the file that index beyond their mesh, before post-processing
// uses them (assimp 5.2.5's PLY importer does not check a face's indices;
// its normal generation read far past the vertices: a crash).
void require_faces_inside(const aiScene &in, const std::string &source)
{
    for (unsigned m = 0; m < in.mNumMeshes; ++m) {
        const aiMesh &mesh = *in.mMeshes[m];
        std::size_t outside = 0, empty = 0;
        for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
            if (mesh.mFaces[f].mNumIndices == 0 || !mesh.mFaces[f].mIndices)
                ++empty;
            for (unsigned k = 0; k < mesh.mFaces[f].mNumIndices; ++k)
                if (mesh.mFaces[f].mIndices[k] >= mesh.mNumVertices) {
                    ++outside;
                    break;
                }
        }
        if (empty)
            throw std::runtime_error(source + ": mesh " + mesh_name(mesh, m) + ": " + std::to_string(empty) +
                                     " of its " + std::to_string(mesh.mNumFaces) + " faces have no indices");
        if (outside)
            throw std::runtime_error(source + ": mesh " + mesh_name(mesh, m) + ": " + std::to_string(outside) +
                                     " of its " + std::to_string(mesh.mNumFaces) + " faces index beyond its " +
                                     std::to_string(mesh.mNumVertices) + " vertices");
    }
}

bool bsp_extension(const std::string &path)
{
    if (path.size() < 4)
        return false;
    std::string tail = path.substr(path.size() - 4);
    for (char &c : tail)
        c = char(std::tolower(static_cast<unsigned char>(c)));
    return tail == ".bsp";
}

Scene quake3_scene(const std::string &source, const std::vector<char> &bytes, const Quake3Options &options,
                   std::vector<std::string> *warnings)
{
    std::vector<std::string> level_warnings;
    Scene out = read_quake3_bsp(source, bytes, options, level_warnings);
    for (const std::string &w : level_warnings)
        Warnings{warnings}(w);
    return out;
}

}  // namespace

Scene load_scene(const std::string &path, std::vector<std::string> *warnings, const Quake3Options &quake3)
{
    std::string archive, member;
    if (split_pk3_path(path, archive, member)) {
        Scene level = quake3_scene(path, read_pk3_member(archive, member), quake3, warnings);
        if (quake3.look) {
            std::vector<std::string> picture_warnings;
            read_level_pictures(level, archive, picture_warnings);
            for (const std::string &w : picture_warnings)
                Warnings{warnings}(w);
        }
        return level;
    }
    // Read once: to choose occu's PLY or BSP reader, and for the guard's
    // checks. A file that cannot be opened is assimp's to name below,
    // except a level's (assimp's BSP importer is not used).
    std::vector<char> bytes;
    std::ifstream file{path, std::ios::binary};
    if (!file && bsp_extension(path))
        throw std::runtime_error("cannot read scene '" + path + "': " + std::strerror(errno));
    if (file) {
        bytes.assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
        if (bsp_extension(path) || looks_like_ibsp(bytes))
            return quake3_scene(path, bytes, quake3, warnings);
        if (assimp_would_read_as_ply(path, bytes)) {
            std::vector<std::string> ply_warnings;
            Scene out;
            out.meshes.push_back(read_ply(path, bytes, ply_warnings));
            for (const std::string &w : ply_warnings)
                Warnings{warnings}(w);
            remove_collinear_triangles(out.meshes.front());
            if (out.triangle_count() == 0)
                throw std::runtime_error("scene '" + path + "' holds no triangles");
            out.update_bounds();
            return out;
        }
        guard_scene_file(path, bytes);
    }
    Assimp::Importer importer;
    const aiScene *in = importer.ReadFile(path, 0);
    if (in && !(in->mFlags & AI_SCENE_FLAGS_INCOMPLETE) && in->mRootNode) {
        require_finite_file_vertices(*in, "scene '" + path + "'");
        require_faces_inside(*in, "scene '" + path + "'");
        // The validation first: assimp's own check of what its importer
        // made (array lengths, face sizes, primitive types), which its
        // later steps take for granted (the fuzzer: PLY files whose faces
        // or vertices the importer left inconsistent crashed them).
        in = importer.ApplyPostProcessing(aiProcess_ValidateDataStructure | aiProcess_Triangulate | aiProcess_GenSmoothNormals |
                                          aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
    }
    if (!in || (in->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !in->mRootNode)
        throw std::runtime_error("cannot read scene '" + path + "': " + importer.GetErrorString());
    Scene out;
    ModelLook look;
    look.wanted = quake3.look;
    add_node(*in, *in->mRootNode, aiMatrix4x4(), out, "scene '" + path + "'", Warnings{warnings}, look);
    if (out.triangle_count() == 0)
        throw std::runtime_error("scene '" + path + "' holds no triangles");
    if (look.wanted)
        read_model_pictures(*in, path, out, look, Warnings{warnings});
    // Node transforms can take finite vertices beyond float range.
    require_finite_vertices(out, "scene '" + path + "' (its node transforms applied)");
    out.update_bounds();
    return out;
}

bool generated_scene_name(const std::string &name)
{
    return name.empty() || name == "city" || name == "field";
}

Scene scene_by_name(const std::string &name, const CityOptions &city, const Quake3Options &quake3)
{
    if (name.empty() || name == "city")
        return generate_city(city);
    if (name == "field")
        return generate_field(FieldOptions{});
    return load_scene(name, nullptr, quake3);
}

}  // namespace occu
