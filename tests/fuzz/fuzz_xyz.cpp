// libFuzzer: XYZ text clouds.
#include "fuzz_support.hpp"
#include "partreg/io/cloud_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  partreg::fuzz::read_as_file(data, size, "input.xyz", [](const auto& path) { partreg::io::read_cloud_file(path); });
  return 0;
}
