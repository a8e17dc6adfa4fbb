#include "partreg/io/mesh_io.hpp"

#include <assimp/DefaultIOSystem.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <array>
#include <assimp/Importer.hpp>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "markup_checks.hpp"
#include "off_reader.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/io/atomic_file.hpp"
#include "partreg/io/output_format.hpp"
#include "partreg/io/read_limits.hpp"
#include "ply_format.hpp"
#include "vtk_io.hpp"

namespace partreg::io {
namespace {

bool is_degenerate(const Eigen::Vector3i& t) { return t[0] == t[1] || t[1] == t[2] || t[0] == t[2]; }

// Appends every mesh under `node` with the accumulated node transform applied. Every index assimp hands
// over is checked: a file's faces may name vertices that do not exist.
void collect(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, const std::string& file,
             std::vector<Eigen::Vector3d>& vertices, std::vector<Eigen::Vector3i>& faces, int depth = 0) {
  if (depth > 256) throw InputError(file + ": its node hierarchy is deeper than 256 levels");
  const aiMatrix4x4 transform = parent * node.mTransformation;
  for (unsigned i = 0; i < node.mNumMeshes; ++i) {
    if (node.mMeshes[i] >= scene.mNumMeshes) throw InputError(file + ": a node refers to a missing mesh");
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[i]];
    check_count(file, "vertices", vertices.size() + mesh.mNumVertices, kReadBudget.max_points);
    check_count(file, "faces", faces.size() + mesh.mNumFaces, kReadBudget.max_faces);
    const int offset = static_cast<int>(vertices.size());
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D p = transform * mesh.mVertices[v];
      vertices.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines left after triangulation
      for (unsigned k = 0; k < 3; ++k)
        if (face.mIndices[k] >= mesh.mNumVertices)
          throw InputError(file + ": a face refers to vertex " + std::to_string(face.mIndices[k]) + " of " +
                           std::to_string(mesh.mNumVertices));
      const Eigen::Vector3i triangle(offset + static_cast<int>(face.mIndices[0]),
                                     offset + static_cast<int>(face.mIndices[1]),
                                     offset + static_cast<int>(face.mIndices[2]));
      if (!is_degenerate(triangle)) faces.push_back(triangle);
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c)
    collect(scene, *node.mChildren[c], transform, file, vertices, faces, depth + 1);
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

// assimp opens the files an input names (an OBJ's material library, a glTF's buffers and textures) itself:
// each passes partreg's checks first. A FIFO would block forever, "../../etc/passwd" would be read as
// vertices. A refused file is not opened; its reason is kept for the message when the reading then fails.
class CheckedIoSystem : public Assimp::DefaultIOSystem {
 public:
  CheckedIoSystem(std::filesystem::path input, std::string& problem)
      : input_(std::move(input)), problem_(problem) {}
  // assimp's own Exists() opens the file too (with fopen, which blocks on a FIFO).
  bool Exists(const char* file) const override {
    return allowed(file) && Assimp::DefaultIOSystem::Exists(file);
  }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    return allowed(file) ? Assimp::DefaultIOSystem::Open(file, mode) : nullptr;
  }

 private:
  bool allowed(const char* file) const {
    const std::string problem = referenced_file_problem(file, input_);
    if (!problem.empty() && problem_.empty()) problem_ = problem;
    return problem.empty();
  }

  std::filesystem::path input_;
  std::string& problem_;
};

// Every format assimp knows, after partreg's own checks of the formats whose headers assimp trusts.
core::Mesh read_with_assimp(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::string refused;  // why a file the input names was not opened
  // ValidateDataStructure runs first among the steps and refuses scenes with broken indices before the
  // other steps walk them.
  Assimp::Importer importer;
  importer.SetIOHandler(new CheckedIoSystem(path, refused));  // the importer owns it
  const unsigned flags = aiProcess_ValidateDataStructure | aiProcess_Triangulate |
                         aiProcess_JoinIdenticalVertices | aiProcess_FindDegenerates | aiProcess_SortByPType;
  // assimp gets the file's canonical path: looking for a missing material library, its OBJ reader opens
  // paths made from the parent folders' names relative to the working directory, and read a directory
  // ("../shared/data") as a file when the path held "..".
  std::error_code ignored;
  const std::filesystem::path canonical = std::filesystem::weakly_canonical(path, ignored);
  const aiScene* scene = importer.ReadFile(canonical.empty() ? name : canonical.string(), flags);
  if (!scene && lower_extension(path) == ".obj") scene = read_tolerant_obj(importer, path, flags);
  if (!scene || !scene->mRootNode)
    throw InputError("cannot read mesh " + name + ": " +
                     (refused.empty() ? importer.GetErrorString() : refused));
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> faces;
  collect(*scene, *scene->mRootNode, aiMatrix4x4(), name, vertices, faces);
  core::Mesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t i = 0; i < vertices.size(); ++i)
    mesh.vertices.row(static_cast<Eigen::Index>(i)) = vertices[i];
  mesh.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t i = 0; i < faces.size(); ++i) mesh.faces.row(static_cast<Eigen::Index>(i)) = faces[i];
  return mesh;
}

// Degenerate triangles (a repeated corner) carry no surface; partreg's own readers drop them as assimp does.
core::Faces without_degenerate(const core::Faces& faces) {
  std::vector<int> keep;
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    if (!is_degenerate(faces.row(f).transpose())) keep.push_back(static_cast<int>(f));
  return faces(keep, Eigen::all);
}

}  // namespace

core::Mesh read_mesh(const std::filesystem::path& path) {
  const std::string name = path.string();
  const std::uint64_t size = checked_input_size(path);
  const std::string extension = lower_extension(path);
  core::Mesh mesh;
  if (extension == ".off") {
    mesh = detail::read_off(path, size);
  } else if (extension == ".vtp") {
    detail::PolyData data = detail::read_vtp(path);
    mesh.vertices = std::move(data.points);
    mesh.normals = std::move(data.normals);
    mesh.faces = std::move(data.faces);
  } else {
    if (extension == ".ply") detail::check_ply_mesh(path);  // assimp trusts PLY headers and face lists
    if (extension == ".gltf" || extension == ".glb") detail::check_gltf(path, size);
    mesh = read_with_assimp(path);
  }
  mesh.faces = without_degenerate(mesh.faces);
  if (mesh.faces.rows() == 0)
    throw InputError(name + " has no faces: it is a point cloud, read it as a cloud");
  if (!mesh.vertices.allFinite()) throw InputError(name + " has NaN or infinite vertex coordinates");
  if (mesh.vertices.cwiseAbs().maxCoeff() > 1e12)
    throw InputError(name + " holds coordinates beyond 1e12, not a sensible size");
  return mesh;
}

namespace {

void put_obj(std::ostream& out, const core::Mesh& mesh) {
  out << "# written by partreg\n";
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v)
    out << "v " << mesh.vertices(v, 0) << ' ' << mesh.vertices(v, 1) << ' ' << mesh.vertices(v, 2) << '\n';
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    out << "f " << mesh.faces(f, 0) + 1 << ' ' << mesh.faces(f, 1) + 1 << ' ' << mesh.faces(f, 2) + 1 << '\n';
}

// ASCII, so that the coordinates keep 9 significant digits; normals and every per-vertex attribute as vertex
// properties, the part names as header comments.
void put_ply(std::ostream& out, const core::Mesh& mesh, const PointAttributes& attributes) {
  const bool normals = mesh.normals.rows() == mesh.vertices.rows() && mesh.vertices.rows() > 0;
  out << "ply\nformat ascii 1.0\ncomment written by partreg\n"
      << detail::part_name_comments(attributes.part_names) << "element vertex " << mesh.vertices.rows()
      << "\nproperty double x\nproperty double y\nproperty double z\n";
  if (normals) out << "property double nx\nproperty double ny\nproperty double nz\n";
  for (const auto& entry : attributes.integers) out << "property int " << entry.first << '\n';
  for (const auto& entry : attributes.reals) out << "property double " << entry.first << '\n';
  out << "element face " << mesh.faces.rows() << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    out << mesh.vertices(v, 0) << ' ' << mesh.vertices(v, 1) << ' ' << mesh.vertices(v, 2);
    if (normals) out << ' ' << mesh.normals(v, 0) << ' ' << mesh.normals(v, 1) << ' ' << mesh.normals(v, 2);
    for (const auto& entry : attributes.integers) out << ' ' << entry.second[v];
    for (const auto& entry : attributes.reals) out << ' ' << entry.second[v];
    out << '\n';
  }
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    out << "3 " << mesh.faces(f, 0) << ' ' << mesh.faces(f, 1) << ' ' << mesh.faces(f, 2) << '\n';
}

}  // namespace

void write_mesh(const std::filesystem::path& path, const core::Mesh& mesh,
                const Eigen::VectorXi* vertex_part) {
  write_mesh(path, mesh, vertex_part ? PointAttributes{{{"part", *vertex_part}}, {}} : PointAttributes{});
}

void write_mesh(const std::filesystem::path& path, const core::Mesh& mesh,
                const PointAttributes& attributes) {
  const FileFormat format = output_format(path, OutputKind::mesh);
  const Eigen::Index n = mesh.vertices.rows();
  for (const auto& [name, values] : attributes.integers)
    if (values.size() != n) throw UsageError("one '" + name + "' value per mesh vertex is required");
  for (const auto& [name, values] : attributes.reals)
    if (values.size() != n) throw UsageError("one '" + name + "' value per mesh vertex is required");
  write_atomically(path, [&](const std::filesystem::path& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out.precision(9);
    if (format == FileFormat::obj) put_obj(out, mesh);
    if (format == FileFormat::ply) put_ply(out, mesh, attributes);
    if (format == FileFormat::vtp)
      detail::write_vtp(out, {mesh.vertices, mesh.normals, mesh.faces, attributes});
    if (!out.flush()) throw InputError("cannot write " + path.string());
  });
}

namespace {

// The row of the file's vertex element (read as a cloud) at each mesh vertex, matched by position in single
// precision (the mesh reader works in floats and joins identical vertices); empty when a vertex has no match,
// as for a file whose vertices are not the mesh's.
std::vector<int> matching_rows(const core::Points& file_vertices, const core::Mesh& mesh) {
  using Key = std::array<float, 3>;
  const auto key = [](const core::Points& points, Eigen::Index i) {
    return Key{static_cast<float>(points(i, 0)), static_cast<float>(points(i, 1)),
               static_cast<float>(points(i, 2))};
  };
  std::map<Key, int> row_at;
  for (Eigen::Index i = 0; i < file_vertices.rows(); ++i) row_at[key(file_vertices, i)] = static_cast<int>(i);
  std::vector<int> rows(static_cast<std::size_t>(mesh.vertices.rows()));
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    const auto match = row_at.find(key(mesh.vertices, v));
    if (match == row_at.end()) return {};
    rows[static_cast<std::size_t>(v)] = match->second;
  }
  return rows;
}

// A PLY mesh's per-vertex normals and attributes, by the vertex rows that match the mesh's.
void read_ply_vertex_data(const std::filesystem::path& path, MeshFile& file) {
  const CloudFile vertices = read_cloud_file(path);
  const std::vector<int> rows = matching_rows(vertices.cloud.points, file.mesh);
  if (rows.empty()) return;
  for (const auto& [name, values] : vertices.attributes.integers)
    file.vertex_attributes.integers[name] = values(rows).eval();
  for (const auto& [name, values] : vertices.attributes.reals)
    file.vertex_attributes.reals[name] = values(rows).eval();
  file.vertex_attributes.part_names = vertices.attributes.part_names;
  if (vertices.cloud.normals.rows() == vertices.cloud.points.rows())
    file.mesh.normals = vertices.cloud.normals(rows, Eigen::all).eval();
}

}  // namespace

MeshFile read_mesh_file(const std::filesystem::path& path) {
  MeshFile file;
  if (lower_extension(path) != ".vtp") {
    file.mesh = read_mesh(path);
    if (lower_extension(path) == ".ply") read_ply_vertex_data(path, file);
    return file;
  }
  detail::PolyData data = detail::read_vtp(path);  // vertices as stored: the arrays need no matching
  file.mesh.vertices = std::move(data.points);
  file.mesh.normals = std::move(data.normals);
  file.mesh.faces = without_degenerate(data.faces);
  file.vertex_attributes = std::move(data.attributes);
  if (file.mesh.faces.rows() == 0)
    throw InputError(path.string() + " has no faces: it is a point cloud, read it as a cloud");
  if (!file.mesh.vertices.allFinite())
    throw InputError(path.string() + " has NaN or infinite vertex coordinates");
  return file;
}

}  // namespace partreg::io
