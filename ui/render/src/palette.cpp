#include "partreg/render/palette.hpp"

#include "partreg/io/labels_file.hpp"

namespace partreg::render {
namespace {

Color from_bytes(const std::array<std::uint8_t, 3>& rgb) {
  return Color(rgb[0] / 255.0f, rgb[1] / 255.0f, rgb[2] / 255.0f);
}

}  // namespace

Color part_color(int index) { return index < 0 ? neutral_color() : from_bytes(io::part_color(index)); }

Color file_color(int index) { return from_bytes(io::part_color(index)); }

Color observed_color() { return Color(0.86f, 0.12f, 0.12f); }

Color neutral_color() { return Color(0.7f, 0.7f, 0.7f); }

}  // namespace partreg::render
