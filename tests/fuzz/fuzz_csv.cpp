// libFuzzer: the evaluation rows CSV that `eval` writes and `report` reads back (eval::read_rows_csv).
#include "fuzz_support.hpp"
#include "partreg/eval/report.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  partreg::fuzz::read_as_file(data, size, "results.csv",
                              [](const auto& path) { partreg::eval::read_rows_csv(path); });
  return 0;
}
