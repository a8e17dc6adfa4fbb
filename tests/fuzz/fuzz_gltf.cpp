// libFuzzer: glTF through partreg's mesh reader (its checks of nesting, GLB chunk lengths and the node
// hierarchy, then assimp). The first byte picks .gltf (JSON) or .glb (binary); the rest is the file. A file
// the input names (buffers, images) is looked for beside it and refused outside that folder.
#include "fuzz_support.hpp"
#include "partreg/io/mesh_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const char* name = data[0] % 2 == 0 ? "input.gltf" : "input.glb";
  partreg::fuzz::read_as_file(data + 1, size - 1, name,
                              [](const auto& path) { partreg::io::read_mesh(path); });
  return 0;
}
