// PLY through Assimp's importer, from memory.
#include "core/scene/ply_reader.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>

#include "absl/strings/str_cat.h"

namespace pf {

absl::StatusOr<TriangleMesh> ReadPly(std::string_view bytes, const std::string& name,
                                     const SceneLimits& limits) {
    Assimp::Importer importer;
    // Only what a PLY file holds: no lines or points, no generated normals or merging.
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                                aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    const aiScene* scene = importer.ReadFileFromMemory(
        bytes.data(), bytes.size(), aiProcess_Triangulate | aiProcess_SortByPType, "ply");
    if (scene == nullptr || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0)
        return absl::InvalidArgumentError(
            absl::StrCat(name, ": not a valid PLY mesh (", importer.GetErrorString(), ")"));
    TriangleMesh mesh;
    uint64_t triangles = 0;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) triangles += scene->mMeshes[m]->mNumFaces;
    if (triangles > limits.max_triangles)
        return absl::ResourceExhaustedError(absl::StrCat(name, ": PLY mesh has ", triangles,
                                                         " triangles, over the limit of ",
                                                         limits.max_triangles));
    bool all_normals = true, all_uvs = true;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m)
        all_normals &= scene->mMeshes[m]->HasNormals(),
            all_uvs &= scene->mMeshes[m]->HasTextureCoords(0);
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
        const aiMesh& source = *scene->mMeshes[m];
        if ((source.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0) continue;
        const auto base = static_cast<uint32_t>(mesh.positions.size());
        for (unsigned v = 0; v < source.mNumVertices; ++v) {
            const aiVector3D& p = source.mVertices[v];
            mesh.positions.emplace_back(p.x, p.y, p.z);
            if (all_normals)
                mesh.normals.emplace_back(source.mNormals[v].x, source.mNormals[v].y,
                                          source.mNormals[v].z);
            if (all_uvs)
                mesh.uvs.push_back({source.mTextureCoords[0][v].x, source.mTextureCoords[0][v].y});
        }
        for (unsigned f = 0; f < source.mNumFaces; ++f) {
            const aiFace& face = source.mFaces[f];
            if (face.mNumIndices != 3) continue;
            for (int k = 0; k < 3; ++k) mesh.indices.push_back(base + face.mIndices[k]);
        }
    }
    if (mesh.indices.empty())
        return absl::InvalidArgumentError(absl::StrCat(name, ": PLY file has no triangles"));
    return mesh;
}

}  // namespace pf
