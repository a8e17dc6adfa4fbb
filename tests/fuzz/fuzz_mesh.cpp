// libFuzzer: mesh import. The first byte picks the extension (so the format partreg and assimp assume),
// the rest is the file: OBJ, PLY, OFF and STL, the formats the data sets and users bring.
#include "fuzz_support.hpp"
#include "partreg/io/geometry_io.hpp"
#include "partreg/io/mesh_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const char* const names[] = {"input.obj", "input.ply", "input.off", "input.stl"};
  partreg::fuzz::read_as_file(data + 1, size - 1, names[data[0] % 4], [](const auto& path) {
    if (partreg::io::is_mesh_file(path)) partreg::io::read_mesh(path);
  });
  return 0;
}
