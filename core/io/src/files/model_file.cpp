#include "partreg/io/model_file.hpp"

#include <cstring>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "json_values.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/io/atomic_file.hpp"
#include "partreg/io/read_limits.hpp"
#include "partreg/version.hpp"

namespace partreg::io {
namespace {

constexpr char kMagic[8] = {'P', 'R', 'T', 'R', 'E', 'G', 'M', '\n'};

std::uint64_t fnv1a64(const char* data, std::size_t size) {
  std::uint64_t hash = 1469598103934665603ULL;
  for (std::size_t i = 0; i < size; ++i) {
    hash ^= static_cast<unsigned char>(data[i]);
    hash *= 1099511628211ULL;
  }
  return hash;
}

std::string hex(std::uint64_t value) {
  std::ostringstream out;
  out << std::hex << value;
  return out.str();
}

// The header's own checksum: FNV-1a 64 of the header text with these 16 hex digits read as zeros, so any
// language can check it on the bytes as stored.
const std::string kHeaderChecksumKey = "\"header_fnv1a64\":\"";
constexpr std::size_t kHeaderChecksumDigits = 16;

std::string hex16(std::uint64_t value) {
  std::ostringstream out;
  out << std::hex << std::setw(kHeaderChecksumDigits) << std::setfill('0') << value;
  return out.str();
}

// Where the checksum's digits start in `text`, or npos when the header has none (files written before it).
std::size_t checksum_position(const std::string& text) {
  const std::size_t found = text.find(kHeaderChecksumKey);
  if (found == std::string::npos) return found;
  return found + kHeaderChecksumKey.size();
}

std::string with_zero_checksum(std::string text, std::size_t position) {
  text.replace(position, kHeaderChecksumDigits, std::string(kHeaderChecksumDigits, '0'));
  return text;
}

// Collects arrays into one blob and describes them in the header's array table.
class ArrayWriter {
 public:
  template <typename Matrix>
  void add(const std::string& name, const Matrix& matrix) {
    // Stored row-major whatever the in-memory layout, so readers need only the shape.
    using Scalar = typename Matrix::Scalar;
    Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows = matrix;
    const std::size_t bytes = static_cast<std::size_t>(rows.size()) * sizeof(Scalar);
    const std::size_t offset = blob_.size();
    blob_.resize(offset + ((bytes + 7) / 8) * 8, '\0');
    if (bytes) std::memcpy(blob_.data() + offset, rows.data(), bytes);
    table_.push_back({{"name", name},
                      {"dtype", std::is_same_v<Scalar, double> ? "f64" : "i32"},
                      {"shape", {rows.rows(), rows.cols()}},
                      {"offset", offset},
                      {"bytes", bytes},
                      {"fnv1a64", hex(fnv1a64(blob_.data() + offset, bytes))}});
  }
  const std::string& blob() const { return blob_; }
  const nlohmann::json& table() const { return table_; }

 private:
  std::string blob_;
  nlohmann::json table_ = nlohmann::json::array();
};

}  // namespace

void write_model(const std::filesystem::path& path, const core::CategoryModel& model) {
  model.validate();
  ArrayWriter arrays;
  arrays.add("canonical", model.canonical);
  arrays.add("canonical_part", model.canonical_part);
  arrays.add("mesh_vertices", model.canonical_mesh.vertices);
  arrays.add("mesh_faces", model.canonical_mesh.faces);
  arrays.add("mesh_vertex_part", model.mesh_vertex_part);
  arrays.add("training_weights", model.training_weights);
  nlohmann::json spaces = nlohmann::json::array();
  for (const core::ShapeSpace& space : model.spaces) {
    const std::string prefix = "space." + space.name + ".";
    arrays.add(prefix + "point_indices",
               Eigen::Map<const Eigen::VectorXi>(space.point_indices.data(), space.point_indices.size()));
    arrays.add(prefix + "mean", space.mean);
    arrays.add(prefix + "basis", space.basis);
    arrays.add(prefix + "variances", space.variances);
    arrays.add(prefix + "kernel_mean", space.kernel_mean);
    arrays.add(prefix + "kernel_basis", space.kernel_basis);
    arrays.add(prefix + "training_latents", space.training_latents);
    spaces.push_back({{"name", space.name}, {"beta", space.beta}, {"total_variance", space.total_variance}});
  }
  nlohmann::json header = {
      {"format", "partreg-model"},
      {"format_version", kModelFormatVersion},
      {"partreg_version", PARTREG_VERSION},
      {"category", model.category},
      {"normalization",
       {{"centre",
         {model.normalization.centre.x(), model.normalization.centre.y(), model.normalization.centre.z()}},
        {"scale", model.normalization.scale}}},
      {"part_names", model.part_names},
      {"up", {model.up.x(), model.up.y(), model.up.z()}},
      {"training", training_record_json(model.training)},
      {"spaces", spaces},
      {"arrays", arrays.table()},
      {"blob_bytes", arrays.blob().size()},
      {"header_fnv1a64", std::string(kHeaderChecksumDigits, '0')}};
  // Only a model with a real size has the member: one without reads in older partreg versions as before.
  if (model.size) header["size"] = {{"metres", *model.size}, {"data_units", model.data_size}};
  std::string text = header.dump();
  const std::size_t checksum_at = checksum_position(text);
  text.replace(checksum_at, kHeaderChecksumDigits, hex16(fnv1a64(text.data(), text.size())));
  write_atomically(path, [&](const std::filesystem::path& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    const std::uint64_t length = text.size();
    out.write(kMagic, sizeof kMagic);
    out.write(reinterpret_cast<const char*>(&length), sizeof length);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.write(arrays.blob().data(), static_cast<std::streamsize>(arrays.blob().size()));
    if (!out.flush()) throw InputError("cannot write model file " + path.string());
  });
}

namespace {

// Reads arrays back from the blob, checking shape, type and checksum of each.
constexpr std::uint64_t kMaxExtent = 1ULL << 31;  // rows or columns of one array (Eigen::Index is signed)

class ArrayReader {
 public:
  ArrayReader(const nlohmann::json& table, std::string blob, std::string file)
      : blob_(std::move(blob)), file_(std::move(file)) {
    for (const auto& entry : table) entries_[entry.at("name").get<std::string>()] = entry;
  }

  template <typename Matrix>
  Matrix get(const std::string& name) const {
    using Scalar = typename Matrix::Scalar;
    const auto found = entries_.find(name);
    if (found == entries_.end()) fail("has no array '" + name + "'");
    const nlohmann::json& entry = found->second;
    const std::uint64_t offset = count_at(entry, "offset", name);
    const std::uint64_t bytes = count_at(entry, "bytes", name);
    const std::uint64_t rows = count_at(entry.at("shape"), 0, name);
    const std::uint64_t cols = count_at(entry.at("shape"), 1, name);
    const bool dtype_ok = entry.at("dtype") == (std::is_same_v<Scalar, double> ? "f64" : "i32");
    // Divisions, not products: values from the header must not wrap around the checks meant for them.
    const std::uint64_t elements = bytes / sizeof(Scalar);
    if (!dtype_ok || bytes % sizeof(Scalar) != 0 || (rows != 0 && cols != elements / rows) ||
        (rows == 0 && elements != 0) || (rows != 0 && elements % rows != 0) || rows > kMaxExtent ||
        cols > kMaxExtent)
      fail("array '" + name + "' has an unexpected type or shape");
    // A column count fixed by the type (points are N x 3, vectors N x 1) must be the file's.
    if (Matrix::ColsAtCompileTime != Eigen::Dynamic &&
        cols != static_cast<std::uint64_t>(Matrix::ColsAtCompileTime))
      fail("array '" + name + "' has " + std::to_string(cols) + " columns, not " +
           std::to_string(Matrix::ColsAtCompileTime));
    if (offset > blob_.size() || bytes > blob_.size() - offset)
      fail("is truncated (array '" + name + "' runs past the end of the file)");
    if (hex(fnv1a64(blob_.data() + offset, bytes)) != entry.at("fnv1a64").get<std::string>())
      fail("is corrupted (checksum of array '" + name + "' does not match)");
    Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> values(rows, cols);
    if (bytes) std::memcpy(values.data(), blob_.data() + offset, bytes);
    return Matrix(values);
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError("model file " + file_ + " " + what);
  }

  // A size or an offset: a non-negative integer (nlohmann would wrap a negative one into a huge size_t).
  template <typename Key>
  std::uint64_t count_at(const nlohmann::json& json, const Key& key, const std::string& name) const {
    const nlohmann::json& value = json.at(key);
    if (!value.is_number_unsigned())
      fail("array '" + name + "' has a negative or non-integer size or offset");
    return value.get<std::uint64_t>();
  }

 private:
  std::string blob_;
  std::string file_;
  std::map<std::string, nlohmann::json> entries_;
};

// Every member the header may have: a bit flipped in a name (the checksum's own included) is damage.
void check_header_checksum(const nlohmann::json& header, const std::string& text, const std::string& file) {
  static const std::set<std::string> known = {
      "format",   "format_version", "partreg_version", "category",   "normalization",  "part_names",
      "training", "spaces",         "arrays",          "blob_bytes", "header_fnv1a64", "up",
      "size"};
  for (const auto& member : header.items())
    if (!known.count(member.key()))
      throw InputError("model file " + file + " is damaged (unknown header member '" + member.key() + "')");
  const std::size_t position = checksum_position(text);
  if (!header.contains("header_fnv1a64") && position == std::string::npos)
    return;  // written before checksums
  if (position == std::string::npos || position + kHeaderChecksumDigits > text.size() ||
      text.substr(position, kHeaderChecksumDigits) !=
          hex16(fnv1a64(with_zero_checksum(text, position).data(), text.size())))
    throw InputError("model file " + file + " is corrupted (checksum of its header does not match)");
}

nlohmann::json read_header(std::ifstream& in, const std::string& file, std::uint64_t file_size) {
  char magic[sizeof kMagic] = {};
  std::uint64_t length = 0;
  in.read(magic, sizeof magic);
  if (!in || std::memcmp(magic, kMagic, sizeof kMagic) != 0)
    throw InputError(file + " is not a partreg model file (no model header)");
  in.read(reinterpret_cast<char*>(&length), sizeof length);
  if (!in || length > file_size) throw InputError("model file " + file + " is truncated (in its header)");
  std::string text(length, '\0');
  in.read(text.data(), static_cast<std::streamsize>(length));
  if (!in) throw InputError("model file " + file + " is truncated (in its header)");
  nlohmann::json header = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (header.is_discarded() || !header.is_object() || header.value("format", "") != "partreg-model")
    throw InputError(file + " is not a partreg model file (unreadable header)");
  const int version = header["format_version"].is_number_integer() ? header["format_version"].get<int>() : -1;
  if (version != kModelFormatVersion)
    throw InputError("model file " + file + " has format version " + std::to_string(version) +
                     " (written by partreg " + header.value("partreg_version", std::string("?")) +
                     "); this partreg " + PARTREG_VERSION + " reads version " +
                     std::to_string(kModelFormatVersion) + ": retrain the model");
  check_header_checksum(header, text, file);
  return header;
}

core::TrainingRecord training_from_json(const nlohmann::json& json) {
  core::TrainingRecord record;
  record.instances = json.at("instances").get<std::vector<std::string>>();
  record.canonical = json.at("canonical").get<std::string>();
  record.canonical_choice = json.at("canonical_choice").get<std::string>();
  record.canonical_points = detail::integer_of<int>(json.at("canonical_points"));
  // Absent in files written before the floor.
  record.min_part_points =
      json.contains("min_part_points") ? detail::integer_of<int>(json.at("min_part_points")) : 0;
  // Absent in files written before the part spaces agreed at their seams.
  record.seam_band = json.contains("seam_band") ? json.at("seam_band").get<double>() : 0.0;
  // Null without parts; absent in files written before training chose the coupled variant's seam weight.
  if (json.contains("seam_weight") && !json.at("seam_weight").is_null())
    record.seam_weight = json.at("seam_weight").get<double>();
  record.seam_weight_choice = json.value("seam_weight_choice", std::string());
  if (json.contains("seam_weight_trials"))
    for (const nlohmann::json& trial : json.at("seam_weight_trials"))
      record.seam_weight_trials.push_back(
          {trial.at("weight").get<double>(), trial.at("error").get<double>()});
  record.beta = json.at("beta").get<double>();
  record.lambda = json.at("lambda").get<double>();
  record.outlier_weight = json.at("outlier_weight").get<double>();
  record.latent_dimensions = detail::integer_of<int>(json.at("latent_dimensions"));
  record.seed = detail::integer_of<std::uint64_t>(json.at("seed"));
  return record;
}

core::CategoryModel model_from(const nlohmann::json& header, const ArrayReader& arrays) {
  core::CategoryModel model;
  model.category = header.at("category").get<std::string>();
  const auto& centre = header.at("normalization").at("centre");
  model.normalization.centre = {centre.at(0).get<double>(), centre.at(1).get<double>(),
                                centre.at(2).get<double>()};
  model.normalization.scale = header.at("normalization").at("scale").get<double>();
  model.part_names = header.at("part_names").get<std::vector<std::string>>();
  if (header.contains("up"))  // files from before the up axis was kept: +y, the default
    model.up = {header.at("up").at(0).get<double>(), header.at("up").at(1).get<double>(),
                header.at("up").at(2).get<double>()};
  if (header.contains("size")) {  // models trained with a real size (train --size)
    model.size = header.at("size").at("metres").get<double>();
    model.data_size = header.at("size").at("data_units").get<double>();
  }
  model.training = training_from_json(header.at("training"));
  model.canonical = arrays.get<core::Points>("canonical");
  model.canonical_part = arrays.get<Eigen::VectorXi>("canonical_part");
  model.canonical_mesh.vertices = arrays.get<core::Points>("mesh_vertices");
  model.canonical_mesh.faces = arrays.get<core::Faces>("mesh_faces");
  model.mesh_vertex_part = arrays.get<Eigen::VectorXi>("mesh_vertex_part");
  model.training_weights = arrays.get<Eigen::MatrixXd>("training_weights");
  for (const auto& entry : header.at("spaces")) {
    core::ShapeSpace space;
    space.name = entry.at("name").get<std::string>();
    space.beta = entry.at("beta").get<double>();
    space.total_variance = entry.at("total_variance").get<double>();
    const std::string prefix = "space." + space.name + ".";
    const Eigen::VectorXi indices = arrays.get<Eigen::VectorXi>(prefix + "point_indices");
    space.point_indices.assign(indices.data(), indices.data() + indices.size());
    space.mean = arrays.get<Eigen::VectorXd>(prefix + "mean");
    space.basis = arrays.get<Eigen::MatrixXd>(prefix + "basis");
    space.variances = arrays.get<Eigen::VectorXd>(prefix + "variances");
    space.kernel_mean = arrays.get<Eigen::VectorXd>(prefix + "kernel_mean");
    space.kernel_basis = arrays.get<Eigen::MatrixXd>(prefix + "kernel_basis");
    space.training_latents = arrays.get<Eigen::MatrixXd>(prefix + "training_latents");
    model.spaces.push_back(std::move(space));
  }
  for (core::ShapeSpace& space : model.spaces) {
    for (int index : space.point_indices)
      if (index < 0 || index >= model.canonical.rows()) arrays.fail("has a space index out of range");
    space.canonical.resize(static_cast<Eigen::Index>(space.point_indices.size()), 3);
    for (std::size_t i = 0; i < space.point_indices.size(); ++i)
      space.canonical.row(static_cast<Eigen::Index>(i)) = model.canonical.row(space.point_indices[i]);
  }
  return model;
}

}  // namespace

core::CategoryModel read_model(const std::filesystem::path& path) {
  const std::string file = path.string();
  const std::uint64_t file_size = checked_input_size(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot open model file " + file);
  try {
    const nlohmann::json header = read_header(in, file, file_size);
    const nlohmann::json& blob_entry = header.at("blob_bytes");
    if (!blob_entry.is_number_unsigned())
      throw InputError("model file " + file + " has a malformed blob size");
    const auto blob_bytes = blob_entry.get<std::uint64_t>();
    const auto start = static_cast<std::uint64_t>(in.tellg());
    if (start > file_size || blob_bytes != file_size - start)
      throw InputError("model file " + file + " is " +
                       (blob_bytes > file_size - start ? "truncated" : "damaged") +
                       ": its header describes " + std::to_string(blob_bytes) +
                       " bytes of arrays, the file holds " + std::to_string(file_size - start));
    std::string blob(blob_bytes, '\0');
    in.read(blob.data(), static_cast<std::streamsize>(blob_bytes));
    if (!header.at("arrays").is_array())
      throw InputError("model file " + file + " has a malformed array table");
    const ArrayReader arrays(header.at("arrays"), std::move(blob), file);
    core::CategoryModel model = model_from(header, arrays);
    model.validate();
    return model;
  } catch (const nlohmann::json::exception& e) {
    throw InputError("model file " + file + " has a malformed header: " + e.what());
  }
}

nlohmann::json training_record_json(const core::TrainingRecord& record) {
  nlohmann::json trials = nlohmann::json::array();
  for (const core::SeamWeightTrial& trial : record.seam_weight_trials)
    trials.push_back({{"weight", trial.weight}, {"error", trial.error}});
  return {{"instances", record.instances},
          {"canonical", record.canonical},
          {"canonical_choice", record.canonical_choice},
          {"canonical_points", record.canonical_points},
          {"min_part_points", record.min_part_points},
          {"seam_band", record.seam_band},
          {"seam_weight", record.seam_weight ? nlohmann::json(*record.seam_weight) : nlohmann::json()},
          {"seam_weight_choice", record.seam_weight_choice},
          {"seam_weight_trials", trials},
          {"beta", record.beta},
          {"lambda", record.lambda},
          {"outlier_weight", record.outlier_weight},
          {"latent_dimensions", record.latent_dimensions},
          {"seed", record.seed}};
}

}  // namespace partreg::io
