// libFuzzer: ParaView .vtp files (partreg's nesting and count checks, then VTK's XML reader), read as a
// cloud and, when they hold polygons, as a mesh.
#include "fuzz_support.hpp"
#include "partreg/io/cloud_io.hpp"
#include "partreg/io/mesh_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  partreg::fuzz::read_as_file(data, size, "input.vtp", [](const auto& path) {
    partreg::io::read_cloud_file(path);
    partreg::io::read_mesh(path);
  });
  return 0;
}
