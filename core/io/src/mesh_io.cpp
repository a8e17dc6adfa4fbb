#include "partreg/io/mesh_io.hpp"

#include <assimp/DefaultIOSystem.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <fstream>
#include <sstream>

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

void put_ply(std::ostream& out, const core::Mesh& mesh, const Eigen::VectorXi* vertex_part) {
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
  const auto part = attributes.integers.find("part");
  write_atomically(path, [&](const std::filesystem::path& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out.precision(9);
    if (format == FileFormat::obj) put_obj(out, mesh);
    if (format == FileFormat::ply)
      put_ply(out, mesh, part == attributes.integers.end() ? nullptr : &part->second);
    if (format == FileFormat::vtp) detail::write_vtp(out, {mesh.vertices, {}, mesh.faces, attributes});
    if (!out.flush()) throw InputError("cannot write " + path.string());
  });
}

}  // namespace partreg::io
