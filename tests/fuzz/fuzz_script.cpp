// libFuzzer: the app's script parser (verbs, quotes, key=value options).
#include <string>

#include "fuzz_support.hpp"
#include "partreg/ui/script.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    partreg::ui::parse_script(std::string(reinterpret_cast<const char*>(data), size));
  } catch (const partreg::UsageError&) {
  } catch (const partreg::InputError&) {
  }
  return 0;
}
