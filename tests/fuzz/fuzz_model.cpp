// libFuzzer: the category model file (.prm): header, array table, bounds, checksums, validate().
#include "fuzz_support.hpp"
#include "partreg/io/model_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  partreg::fuzz::read_as_file(data, size, "input.prm", [](const auto& path) { partreg::io::read_model(path); });
  return 0;
}
