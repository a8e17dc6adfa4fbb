#include "partreg/io/mesh_io.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <fstream>
#include <sstream>

#include "partreg/core/errors.hpp"
#include "partreg/io/atomic_file.hpp"

namespace partreg::io {
namespace {

// Appends every mesh under `node` with the accumulated node transform applied.
void collect(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent,
             std::vector<Eigen::Vector3d>& vertices, std::vector<Eigen::Vector3i>& faces) {
  const aiMatrix4x4 transform = parent * node.mTransformation;
  for (unsigned i = 0; i < node.mNumMeshes; ++i) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[i]];
    const int offset = static_cast<int>(vertices.size());
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D p = transform * mesh.mVertices[v];
      vertices.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines left after triangulation
      const Eigen::Vector3i triangle(offset + static_cast<int>(face.mIndices[0]),
                                     offset + static_cast<int>(face.mIndices[1]),
                                     offset + static_cast<int>(face.mIndices[2]));
      if (triangle[0] != triangle[1] && triangle[1] != triangle[2] && triangle[0] != triangle[2])
        faces.push_back(triangle);
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c)
    collect(scene, *node.mChildren[c], transform, vertices, faces);
}

// Some exported OBJ files (trimesh's, in ShapeNet-derived sets) carry a bare "vt" line that assimp rejects.
// Such lines hold no geometry: drop them and let assimp parse the rest from memory.
const aiScene* read_tolerant_obj(Assimp::Importer& importer, const std::filesystem::path& path,
                                 unsigned flags) {
  std::ifstream in(path);
  std::string text, line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string keyword, first;
    words >> keyword >> first;
    if ((keyword == "vt" || keyword == "vn") && first.empty()) continue;
    text += line;
    text += '\n';
  }
  return importer.ReadFileFromMemory(text.data(), text.size(), flags, "obj");
}

}  // namespace

core::Mesh read_mesh(const std::filesystem::path& path) {
  const std::string name = path.string();
  if (!std::filesystem::is_regular_file(path)) throw InputError("no such file: " + name);
  if (std::filesystem::file_size(path) == 0) throw InputError(name + " is empty");
  Assimp::Importer importer;
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_FindDegenerates |
                         aiProcess_SortByPType;
  const aiScene* scene = importer.ReadFile(name, flags);
  if (!scene && lower_extension(path) == ".obj") scene = read_tolerant_obj(importer, path, flags);
  if (!scene || !scene->mRootNode)
    throw InputError("cannot read mesh " + name + ": " + importer.GetErrorString());
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> faces;
  collect(*scene, *scene->mRootNode, aiMatrix4x4(), vertices, faces);
  if (faces.empty()) throw InputError(name + " has no faces: it is a point cloud, read it as a cloud");
  core::Mesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t i = 0; i < vertices.size(); ++i)
    mesh.vertices.row(static_cast<Eigen::Index>(i)) = vertices[i];
  mesh.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t i = 0; i < faces.size(); ++i) mesh.faces.row(static_cast<Eigen::Index>(i)) = faces[i];
  if (!mesh.vertices.allFinite()) throw InputError(name + " has NaN or infinite vertex coordinates");
  return mesh;
}

void write_mesh(const std::filesystem::path& path, const core::Mesh& mesh,
                const Eigen::VectorXi* vertex_part) {
  const std::string extension = lower_extension(path);
  if (extension != ".obj" && extension != ".ply")
    throw UsageError("cannot write a mesh as '" + extension + "': use .obj or .ply");
  if (vertex_part && vertex_part->size() != mesh.vertices.rows())
    throw UsageError("one part label per mesh vertex is required");
  write_atomically(path, [&](const std::filesystem::path& temporary) {
    std::ofstream out(temporary);
    out.precision(9);
    if (extension == ".obj") {
      out << "# written by partreg\n";
      for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v)
        out << "v " << mesh.vertices(v, 0) << ' ' << mesh.vertices(v, 1) << ' ' << mesh.vertices(v, 2)
            << '\n';
      for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
        out << "f " << mesh.faces(f, 0) + 1 << ' ' << mesh.faces(f, 1) + 1 << ' ' << mesh.faces(f, 2) + 1
            << '\n';
    } else {
      out << "ply\nformat ascii 1.0\ncomment written by partreg\nelement vertex " << mesh.vertices.rows()
          << "\nproperty double x\nproperty double y\nproperty double z\n"
          << (vertex_part ? "property int part\n" : "") << "element face " << mesh.faces.rows()
          << "\nproperty list uchar int vertex_indices\nend_header\n";
      for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
        out << mesh.vertices(v, 0) << ' ' << mesh.vertices(v, 1) << ' ' << mesh.vertices(v, 2);
        if (vertex_part) out << ' ' << (*vertex_part)[v];
        out << '\n';
      }
      for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
        out << "3 " << mesh.faces(f, 0) << ' ' << mesh.faces(f, 1) << ' ' << mesh.faces(f, 2) << '\n';
    }
    if (!out.flush()) throw InputError("cannot write " + path.string());
  });
}

}  // namespace partreg::io
