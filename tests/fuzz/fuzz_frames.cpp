// libFuzzer: frames files (JSON: positions and rotations attached to the canonical).
#include "fuzz_support.hpp"
#include "partreg/io/frames_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  partreg::fuzz::read_as_file(data, size, "input.frames.json",
                              [](const auto& path) { partreg::io::read_frames_file(path); });
  return 0;
}
