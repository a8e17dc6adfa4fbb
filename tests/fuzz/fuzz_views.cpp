// libFuzzer: views.json listings (the viewpoint of a view's cloud). Never throws: a listing that is not
// partreg's simply gives no viewpoint.
#include <string>

#include "fuzz_support.hpp"
#include "partreg/io/views_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const auto viewpoint = partreg::io::viewpoint_in_listing(text, "view_000.ply");
  if (viewpoint && !viewpoint->allFinite()) __builtin_trap();  // promised finite
  return 0;
}
