#include "markup_checks.hpp"

#include <cctype>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <vector>

#include "partreg/core/errors.hpp"
#include "partreg/io/read_limits.hpp"

namespace partreg::io::detail {
namespace {

constexpr int kMaxNodeDepth = 256;  // as deep as the mesh reader walks a node hierarchy

std::string read_bytes(std::ifstream& in, std::uint64_t count, const std::string& file) {
  std::string bytes(count, '\0');
  if (!in.read(bytes.data(), static_cast<std::streamsize>(count)))
    throw InputError(file + " is truncated (it is shorter than its GLB header states)");
  return bytes;
}

std::uint32_t little_endian_u32(const std::string& bytes, std::size_t at) {
  std::uint32_t value = 0;
  for (int k = 3; k >= 0; --k) value = (value << 8) | static_cast<unsigned char>(bytes[at + k]);
  return value;
}

// The JSON of a binary glTF. Version 2: a 12-byte header (magic, version, length), then chunks of
// (length, type, data) with the JSON chunk first; version 1: a 20-byte header (magic, version, length,
// content length, content format) then the JSON. Every length is checked against the file before use.
std::string glb_json(std::ifstream& in, std::uint64_t size, const std::string& file) {
  if (size < 20) throw InputError(file + " is too short for a GLB file");
  const std::string header = read_bytes(in, 20, file);
  if (header.compare(0, 4, "glTF") != 0) throw InputError(file + " is not a GLB file (no 'glTF' magic)");
  const std::uint32_t version = little_endian_u32(header, 4), length = little_endian_u32(header, 8);
  if (version != 1 && version != 2)
    throw InputError(file + ": GLB version " + std::to_string(version) + " (not 1 or 2)");
  if (length > size || length < 20)
    throw InputError(file + ": its GLB header states " + std::to_string(length) + " bytes, the file holds " +
                     std::to_string(size));
  // Both versions: the JSON's length at byte 12, the JSON from byte 20 (v2: after its chunk's type).
  const std::uint64_t content = little_endian_u32(header, 12);
  if (version == 2 && header.compare(16, 4, "JSON") != 0)
    throw InputError(file + ": its first GLB chunk is not JSON");
  if (content > length - 20)
    throw InputError(file + ": a GLB chunk states " + std::to_string(content) +
                     " bytes, more than the file holds");
  return read_bytes(in, content, file);
}

// The children of every node, whether `nodes` is an array (glTF 2: indices) or an object (glTF 1: names).
std::map<std::string, std::vector<std::string>> node_children(const nlohmann::json& nodes,
                                                              const std::string& file) {
  std::map<std::string, std::vector<std::string>> children;
  auto add = [&](const std::string& id, const nlohmann::json& node) {
    std::vector<std::string>& list = children[id];
    if (!node.is_object() || !node.contains("children")) return;
    const nlohmann::json& named = node.at("children");
    if (!named.is_array()) throw InputError(file + ": the children of glTF node " + id + " are not a list");
    for (const nlohmann::json& child : named) {
      if (!child.is_number_unsigned() && !child.is_string())
        throw InputError(file + ": glTF node " + id + " names a child that is not a node");
      list.push_back(child.is_string() ? child.get<std::string>()
                                       : std::to_string(child.get<std::uint64_t>()));
    }
  };
  if (nodes.is_array())
    for (std::size_t i = 0; i < nodes.size(); ++i) add(std::to_string(i), nodes[i]);
  else if (nodes.is_object())
    for (const auto& [id, node] : nodes.items()) add(id, node);
  return children;
}

// Breadth first from the roots: every node reached once (a second parent or a cycle is refused, as assimp
// would copy or recurse into it without end) and no deeper than kMaxNodeDepth.
void check_node_forest(const nlohmann::json& nodes, const std::string& file) {
  const auto children = node_children(nodes, file);
  std::map<std::string, int> parents;
  for (const auto& [id, list] : children)
    for (const std::string& child : list) {
      if (!children.count(child)) throw InputError(file + ": glTF node " + id + " names a missing child");
      if (++parents[child] > 1) throw InputError(file + ": glTF node " + child + " has two parents");
    }
  std::vector<std::string> level;
  for (const auto& entry : children)
    if (!parents.count(entry.first)) level.push_back(entry.first);
  std::size_t reached = 0;
  for (int depth = 0; !level.empty(); ++depth) {
    if (depth > kMaxNodeDepth)
      throw InputError(file + ": its glTF node hierarchy is deeper than " + std::to_string(kMaxNodeDepth) +
                       " levels");
    reached += level.size();
    std::vector<std::string> next;
    for (const std::string& id : level)
      next.insert(next.end(), children.at(id).begin(), children.at(id).end());
    level = std::move(next);
  }
  if (reached != children.size()) throw InputError(file + ": its glTF node hierarchy has a cycle");
}

// An opening tag's attribute `name="N"` as a count; 0 when absent.
std::uint64_t declared_count(const std::string& tag, const std::string& name, const std::string& file) {
  const std::size_t at = tag.find(" " + name + "=");
  if (at == std::string::npos) return 0;
  std::size_t digits = at + name.size() + 2;
  if (digits < tag.size() && (tag[digits] == '"' || tag[digits] == '\'')) ++digits;
  std::uint64_t value = 0;
  for (; digits < tag.size() && tag[digits] >= '0' && tag[digits] <= '9'; ++digits) {
    if (value > kReadBudget.max_points * 1000) throw InputError(file + ": its " + name + " is out of range");
    value = value * 10 + static_cast<std::uint64_t>(tag[digits] - '0');
  }
  if (digits < tag.size() && tag[digits] == '-') throw InputError(file + ": its " + name + " is negative");
  return value;
}

void check_vtp_tag(const std::string& tag, const std::string& file) {
  for (const char* name : {"NumberOfPoints", "NumberOfTuples"})
    check_count(file, name, declared_count(tag, name, file), kReadBudget.max_points);
  for (const char* name : {"NumberOfPolys", "NumberOfVerts", "NumberOfLines", "NumberOfStrips"})
    check_count(file, name, declared_count(tag, name, file), kReadBudget.max_faces);
  check_count(file, "NumberOfComponents", declared_count(tag, "NumberOfComponents", file), 4096);
}

// Skips past `end` (e.g. "-->"); false at the end of the file.
bool skip_past(std::istream& in, const std::string& end) {
  std::string window;
  for (int c = in.get(); c != EOF; c = in.get()) {
    window += static_cast<char>(c);
    if (window.size() > end.size()) window.erase(0, 1);
    if (window == end) return true;
  }
  return false;
}

}  // namespace

void check_json_nesting(std::string_view text, const std::string& file) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kReadBudget.max_nesting)
        throw InputError(file + ": its JSON nests deeper than " + std::to_string(kReadBudget.max_nesting) +
                         " levels");
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

void check_gltf(const std::filesystem::path& path, std::uint64_t size) {
  const std::string file = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot open " + file + " for reading");
  char magic[4] = {};
  in.read(magic, 4);
  in.seekg(0);
  const std::string json =
      std::memcmp(magic, "glTF", 4) == 0 ? glb_json(in, size, file) : read_bytes(in, size, file);
  check_json_nesting(json, file);
  const nlohmann::json document = nlohmann::json::parse(json, nullptr, /*allow_exceptions=*/false);
  if (document.is_discarded() || !document.is_object())
    throw InputError(file + " is not a glTF file (invalid JSON)");
  if (document.contains("nodes")) check_node_forest(document.at("nodes"), file);
}

void check_vtp(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot open " + file + " for reading");
  constexpr std::size_t kMaxTagBytes = 1 << 20;
  int depth = 0;
  for (int c = in.get(); c != EOF; c = in.get()) {
    if (c != '<') continue;
    const int next = in.peek();
    if (next == '!' || next == '?') {  // a comment, a declaration: no element
      in.get();
      const bool comment = next == '!' && in.peek() == '-';
      if (!skip_past(in, comment ? "-->" : next == '!' ? ">" : "?>")) break;
      continue;
    }
    std::string tag;
    char quote = 0;
    for (c = in.get(); c != EOF && (quote || c != '>'); c = in.get()) {
      if (quote == 0 && (c == '"' || c == '\''))
        quote = static_cast<char>(c);
      else if (quote == c)
        quote = 0;
      tag += std::isspace(c) ? ' ' : static_cast<char>(c);
      if (tag.size() > kMaxTagBytes)
        throw InputError(file + ": an XML tag is longer than 1 MiB (not a .vtp file?)");
    }
    if (tag.rfind("AppendedData", 0) == 0) return;  // raw bytes follow, not XML
    if (!tag.empty() && tag[0] == '/') {
      --depth;
      continue;
    }
    check_vtp_tag(" " + tag, file);
    if (!tag.empty() && tag.back() == '/') continue;  // <Empty/>
    if (++depth > kReadBudget.max_nesting)
      throw InputError(file + ": its XML nests deeper than " + std::to_string(kReadBudget.max_nesting) +
                       " levels");
  }
}

}  // namespace partreg::io::detail
