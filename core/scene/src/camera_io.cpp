// Depth-camera files. stb_image reads PNGs (16-bit too); libpng writes them, as stb cannot write 16 bits.
#include "partreg/scene/camera_io.hpp"

#include <png.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <memory>
#include <string>

#include "partreg/core/errors.hpp"
#include "partreg/io/atomic_file.hpp"
#include "partreg/io/read_limits.hpp"
#include "stb_image_static.hpp"

namespace partreg::scene {
namespace {

double number(const nlohmann::json& json, const char* key, const std::string& file) {
  if (!json.contains(key)) throw InputError(file + ": no \"" + key + "\"");
  const nlohmann::json& value = json.at(key);
  if (!value.is_number()) throw InputError(file + ": \"" + key + "\" is not a number");
  const double x = value.get<double>();
  if (!std::isfinite(x)) throw InputError(file + ": \"" + key + "\" is not finite");
  return x;
}

int whole_number(const nlohmann::json& json, const char* key, const std::string& file) {
  const double x = number(json, key, file);
  if (x != std::floor(x) || std::abs(x) > 1e6) throw InputError(file + ": \"" + key + "\" is not a pixel count");
  return static_cast<int>(x);
}

// Open3D keeps the 3x3 matrix column-major: [fx, 0, 0, 0, fy, 0, cx, cy, 1].
void read_open3d_matrix(const nlohmann::json& matrix, Intrinsics& k, const std::string& file) {
  if (!matrix.is_array() || matrix.size() != 9)
    throw InputError(file + ": \"intrinsic_matrix\" must hold 9 numbers (column-major 3x3)");
  double m[9];
  for (int i = 0; i < 9; ++i) {
    if (!matrix[i].is_number() || !std::isfinite(matrix[i].get<double>()))
      throw InputError(file + ": \"intrinsic_matrix\" holds something other than a finite number");
    m[i] = matrix[i].get<double>();
  }
  k.fx = m[0], k.fy = m[4], k.cx = m[6], k.cy = m[7];
}

nlohmann::json parse_json_file(const std::filesystem::path& path) {
  io::checked_input_size(path);
  std::ifstream in(path);
  if (!in) throw InputError("cannot read " + path.string());
  nlohmann::json json = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (json.is_discarded() || !json.is_object())
    throw InputError(path.string() + " is not a JSON object (NaN is not JSON: write numbers)");
  return json;
}

struct StbFree {
  void operator()(void* data) const { stbi_image_free(data); }
};

// A PNG's size and channels, checked against the intrinsics before its pixels are decoded.
void check_png(const std::filesystem::path& path, const Intrinsics& k, int& channels, const char* what) {
  io::checked_input_size(path);
  int width = 0, height = 0;
  if (!stbi_info(path.string().c_str(), &width, &height, &channels))
    throw InputError("cannot read " + path.string() + " as a PNG: " + stbi_failure_reason());
  if (width != k.width || height != k.height)
    throw InputError(std::string(what) + " " + path.string() + " is " + std::to_string(width) + "x" +
                     std::to_string(height) + " pixels but the intrinsics say " + std::to_string(k.width) +
                     "x" + std::to_string(k.height));
}

DepthImage read_depth_png(const std::filesystem::path& path, const Intrinsics& k) {
  int channels = 0;
  check_png(path, k, channels, "depth image");
  if (channels != 1 || !stbi_is_16_bit(path.string().c_str()))
    throw InputError("depth image " + path.string() + " has " + std::to_string(channels) + " channel(s) of " +
                     (stbi_is_16_bit(path.string().c_str()) ? "16" : "8") +
                     " bits; a depth PNG is one 16-bit channel");
  int width = 0, height = 0, file_channels = 0;
  std::unique_ptr<stbi_us, StbFree> data(
      stbi_load_16(path.string().c_str(), &width, &height, &file_channels, 1));
  if (!data) throw InputError("cannot read " + path.string() + ": " + stbi_failure_reason());
  DepthImage depth{width, height, std::vector<float>(static_cast<std::size_t>(width) * height)};
  for (std::size_t i = 0; i < depth.metres.size(); ++i)
    depth.metres[i] = static_cast<float>(data.get()[i] / k.depth_scale);
  return depth;
}

// NumPy's format: magic, version, a little-endian header length, a Python dict literal, then the data.
DepthImage read_depth_npy(const std::filesystem::path& path, const Intrinsics& k) {
  const std::uint64_t size = io::checked_input_size(path);
  std::ifstream in(path, std::ios::binary);
  char magic[8] = {};
  in.read(magic, 8);
  if (!in || std::string(magic, 6) != "\x93NUMPY" || (magic[6] != 1 && magic[6] != 2))
    throw InputError(path.string() + " is not a NumPy .npy file");
  std::uint32_t header_length = 0;
  unsigned char bytes[4] = {};
  in.read(reinterpret_cast<char*>(bytes), magic[6] == 1 ? 2 : 4);
  for (int i = (magic[6] == 1 ? 1 : 3); i >= 0; --i) header_length = header_length * 256 + bytes[i];
  if (!in || header_length > 65536) throw InputError(path.string() + ": malformed .npy header");
  std::string header(header_length, '\0');
  in.read(header.data(), header_length);
  const bool f4 = header.find("'<f4'") != std::string::npos, f8 = header.find("'<f8'") != std::string::npos;
  if (!f4 && !f8) throw InputError(path.string() + ": a depth .npy holds float32 or float64 metres ('<f4', '<f8')");
  if (header.find("'fortran_order': False") == std::string::npos)
    throw InputError(path.string() + ": a Fortran-ordered .npy is not read; save it C-ordered");
  const std::string expected = "(" + std::to_string(k.height) + ", " + std::to_string(k.width) + ")";
  const std::size_t shape = header.find("'shape': ");
  const std::size_t close = header.find(')', shape);
  if (shape == std::string::npos || close == std::string::npos)
    throw InputError(path.string() + ": malformed .npy header");
  const std::string found = header.substr(shape + 9, close - shape - 8);
  if (found != expected)
    throw InputError("depth image " + path.string() + " has shape " + found + " but the intrinsics say " +
                     expected + " (height, width)");
  const std::size_t count = static_cast<std::size_t>(k.width) * k.height, each = f4 ? 4 : 8;
  io::check_fits(path.string(), "depth values", count, each, size - static_cast<std::uint64_t>(in.tellg()));
  DepthImage depth{k.width, k.height, std::vector<float>(count)};
  std::vector<char> raw(count * each);
  in.read(raw.data(), static_cast<std::streamsize>(raw.size()));
  if (!in) throw InputError(path.string() + ": truncated .npy data");
  for (std::size_t i = 0; i < count; ++i) {
    double z = 0;
    if (f4) { float f; std::memcpy(&f, &raw[4 * i], 4); z = f; } else { std::memcpy(&z, &raw[8 * i], 8); }
    if (z < 0) throw InputError(path.string() + " holds a negative depth");
    depth.metres[i] = std::isfinite(z) ? static_cast<float>(z) : 0.0f;
  }
  return depth;
}

// A PNG of one channel, 8 or 16 bits, through libpng.
void write_png(const std::filesystem::path& path, int width, int height, int bits,
               const std::function<void(int row, std::vector<png_byte>& out)>& fill_row) {
  io::write_atomically(path, [&](const std::filesystem::path& target) {
    std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(target.string().c_str(), "wb"), &std::fclose);
    if (!file) throw InputError("cannot write " + path.string());
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!info || setjmp(png_jmpbuf(png))) {
      png_destroy_write_struct(&png, &info);
      throw InputError("cannot write " + path.string() + " as a PNG");
    }
    png_init_io(png, file.get());
    png_set_IHDR(png, info, width, height, bits, PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    std::vector<png_byte> row(static_cast<std::size_t>(width) * bits / 8);
    for (int v = 0; v < height; ++v) {
      fill_row(v, row);
      png_write_row(png, row.data());
    }
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    if (std::fflush(file.get()) != 0) throw InputError("cannot write " + path.string());
  });
}

}  // namespace

Intrinsics read_intrinsics(const std::filesystem::path& path) {
  return intrinsics_from_json(parse_json_file(path), path.string());
}

Intrinsics intrinsics_from_json(const nlohmann::json& json, const std::string& file) {
  if (!json.is_object()) throw InputError(file + ": intrinsics are a JSON object");
  Intrinsics k;
  k.width = whole_number(json, "width", file);
  k.height = whole_number(json, "height", file);
  if (json.contains("intrinsic_matrix")) {
    read_open3d_matrix(json.at("intrinsic_matrix"), k, file);
  } else {
    k.fx = number(json, "fx", file), k.fy = number(json, "fy", file);
    k.cx = number(json, "cx", file), k.cy = number(json, "cy", file);
  }
  if (json.contains("depth_scale")) k.depth_scale = number(json, "depth_scale", file);
  try {
    k.validate();
  } catch (const InputError& e) {
    throw InputError(file + ": " + e.what());
  }
  return k;
}

nlohmann::json intrinsics_json(const Intrinsics& k) {
  return {{"fx", k.fx}, {"fy", k.fy}, {"cx", k.cx}, {"cy", k.cy}, {"width", k.width}, {"height", k.height},
          {"depth_scale", k.depth_scale},
          {"intrinsic_matrix", {k.fx, 0.0, 0.0, 0.0, k.fy, 0.0, k.cx, k.cy, 1.0}}};
}

DepthImage read_depth_image(const std::filesystem::path& path, const Intrinsics& intrinsics) {
  const std::string extension = io::lower_extension(path);
  if (extension == ".png") return read_depth_png(path, intrinsics);
  if (extension == ".npy") return read_depth_npy(path, intrinsics);
  throw InputError("depth image " + path.string() + ": expected a 16-bit .png or a float .npy");
}

void write_depth_png(const std::filesystem::path& path, const DepthImage& depth, double depth_scale) {
  write_png(path, depth.width, depth.height, 16, [&](int v, std::vector<png_byte>& row) {
    for (int u = 0; u < depth.width; ++u) {
      const double units = std::round(double(depth.at(u, v)) * depth_scale);
      const auto value = static_cast<std::uint16_t>(std::isfinite(units) && units > 0 && units <= 65535 ? units : 0);
      row[2 * u] = static_cast<png_byte>(value >> 8);  // PNG stores 16-bit samples big-endian
      row[2 * u + 1] = static_cast<png_byte>(value & 0xff);
    }
  });
}

PixelMask read_mask(const std::filesystem::path& path, const Intrinsics& intrinsics) {
  int channels = 0;
  check_png(path, intrinsics, channels, "mask");
  int width = 0, height = 0, file_channels = 0;
  std::unique_ptr<stbi_uc, StbFree> data(stbi_load(path.string().c_str(), &width, &height, &file_channels, 1));
  if (!data) throw InputError("cannot read " + path.string() + ": " + stbi_failure_reason());
  PixelMask mask{width, height, std::vector<std::uint8_t>(static_cast<std::size_t>(width) * height)};
  for (std::size_t i = 0; i < mask.selected.size(); ++i) mask.selected[i] = data.get()[i] != 0;
  return mask;
}

void write_mask_png(const std::filesystem::path& path, const PixelMask& mask) {
  write_png(path, mask.width, mask.height, 8, [&](int v, std::vector<png_byte>& row) {
    for (int u = 0; u < mask.width; ++u) row[u] = mask.at(u, v) ? 255 : 0;
  });
}

}  // namespace partreg::scene
