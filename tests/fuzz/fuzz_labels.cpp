// libFuzzer: part labels files (JSON).
#include "fuzz_support.hpp"
#include "partreg/io/labels_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  partreg::fuzz::read_as_file(data, size, "input.labels.json",
                              [](const auto& path) { partreg::io::read_labels_file(path); });
  return 0;
}
