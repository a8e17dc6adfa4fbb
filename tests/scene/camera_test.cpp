// Depth-camera files and the pinhole model: what is written reads back, Open3D's intrinsics read as ours, and
// every malformed input is refused with an InputError.
#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <fstream>

#include "partreg/core/errors.hpp"
#include "partreg/scene/camera_io.hpp"
#include "support/temp_dir.hpp"

namespace partreg::scene {
namespace {

using testing::TempDir;

void write_text(const std::filesystem::path& path, const std::string& text) { std::ofstream(path) << text; }

// A PNG of `channels` 8-bit channels, written with libpng directly (partreg writes only grey ones).
void write_png_8bit(const std::filesystem::path& path, int width, int height, int channels) {
  FILE* file = std::fopen(path.string().c_str(), "wb");
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  png_init_io(png, file);
  png_set_IHDR(png, info, width, height, 8, channels == 3 ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_GRAY,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  std::vector<png_byte> row(static_cast<std::size_t>(width) * channels, 100);
  for (int v = 0; v < height; ++v) png_write_row(png, row.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  std::fclose(file);
}

// A .npy of float32 (height, width), C order.
void write_npy(const std::filesystem::path& path, int width, int height, const std::vector<float>& values) {
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::to_string(height) + ", " +
                       std::to_string(width) + "), }";
  while ((10 + header.size() + 1) % 64) header += ' ';
  header += '\n';
  std::ofstream out(path, std::ios::binary);
  out.write("\x93NUMPY\x01\x00", 8);
  const std::uint16_t length = static_cast<std::uint16_t>(header.size());
  out.put(static_cast<char>(length & 0xff)).put(static_cast<char>(length >> 8));
  out << header;
  out.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(float)));
}

Intrinsics small_camera() {
  Intrinsics k;
  k.width = 8, k.height = 6, k.fx = 10, k.fy = 12, k.cx = 3.5, k.cy = 2.5;
  return k;
}

TEST(Intrinsics, OursAndOpen3dFormReadAlike) {
  TempDir dir;
  write_text(dir / "ours.json", R"({"fx": 600, "fy": 610, "cx": 320.5, "cy": 240.5, "width": 640, "height": 480,
                                   "depth_scale": 4000})");
  // As Open3D's write_pinhole_camera_intrinsic writes it: the 3x3 matrix column-major.
  write_text(dir / "open3d.json", R"({"height": 480, "intrinsic_matrix": [600.0, 0.0, 0.0, 0.0, 610.0, 0.0,
                                      320.5, 240.5, 1.0], "width": 640})");
  const Intrinsics ours = read_intrinsics(dir / "ours.json"), open3d = read_intrinsics(dir / "open3d.json");
  for (const Intrinsics& k : {ours, open3d}) {
    EXPECT_EQ(k.fx, 600);
    EXPECT_EQ(k.fy, 610);
    EXPECT_EQ(k.cx, 320.5);
    EXPECT_EQ(k.cy, 240.5);
    EXPECT_EQ(k.width, 640);
    EXPECT_EQ(k.height, 480);
  }
  EXPECT_EQ(ours.depth_scale, 4000);
  EXPECT_EQ(open3d.depth_scale, 1000);  // millimetres unless stated
  // What partreg writes reads back.
  write_text(dir / "back.json", intrinsics_json(ours).dump());
  EXPECT_EQ(read_intrinsics(dir / "back.json").fy, 610);
}

TEST(Intrinsics, RefusesNanMissingAndImpossibleValues) {
  TempDir dir;
  for (const std::string& text :
       {std::string(R"({"fx": NaN, "fy": 1, "cx": 1, "cy": 1, "width": 4, "height": 4})"),
        std::string(R"({"fx": 1, "fy": 1, "cx": 1, "width": 4, "height": 4})"),
        std::string(R"({"fx": 0, "fy": 1, "cx": 1, "cy": 1, "width": 4, "height": 4})"),
        std::string(R"({"fx": 1, "fy": 1, "cx": 1, "cy": 1, "width": 4.5, "height": 4})"),
        std::string(R"({"fx": 1, "fy": 1, "cx": 1, "cy": 1, "width": 4, "height": 4, "depth_scale": -1})"),
        std::string(R"({"width": 4, "height": 4, "intrinsic_matrix": [1, 0, 0, 0, 1, 0, 1]})")}) {
    write_text(dir / "k.json", text);
    EXPECT_THROW(read_intrinsics(dir / "k.json"), InputError) << text;
  }
}

TEST(DepthImage, SixteenBitPngRoundTripsInMillimetres) {
  TempDir dir;
  const Intrinsics k = small_camera();
  DepthImage depth{k.width, k.height, std::vector<float>(48, 0.0f)};
  for (int i = 0; i < 48; ++i) depth.metres[i] = i % 5 == 0 ? 0.0f : 0.3f + 0.0371f * float(i);
  write_depth_png(dir / "d.png", depth, k.depth_scale);
  const DepthImage back = read_depth_image(dir / "d.png", k);
  ASSERT_EQ(back.metres.size(), depth.metres.size());
  for (int i = 0; i < 48; ++i) EXPECT_NEAR(back.metres[i], depth.metres[i], 0.0005 + 1e-6) << i;  // 1 mm steps
  EXPECT_EQ(back.metres[5], 0.0f);
}

TEST(DepthImage, RefusesEightBitThreeChannelAndWrongSize) {
  TempDir dir;
  const Intrinsics k = small_camera();
  write_png_8bit(dir / "rgb.png", k.width, k.height, 3);
  write_png_8bit(dir / "grey8.png", k.width, k.height, 1);
  write_depth_png(dir / "wide.png", {k.width + 1, k.height, std::vector<float>((k.width + 1) * k.height, 1.0f)},
                  1000);
  EXPECT_THROW(read_depth_image(dir / "rgb.png", k), InputError);
  EXPECT_THROW(read_depth_image(dir / "grey8.png", k), InputError);
  try {
    read_depth_image(dir / "wide.png", k);
    FAIL() << "a depth image wider than its intrinsics was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("9x6 pixels but the intrinsics say 8x6"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_depth_image(dir / "d.tiff", k), InputError);
  // A mask may be any 8-bit PNG of the right size; a wrong size is refused.
  EXPECT_EQ(read_mask(dir / "rgb.png", k).selected.size(), 48u);
  EXPECT_THROW(read_mask(dir / "wide.png", k), InputError);
}

TEST(DepthImage, NpyFloatMetresReadWithHolesAndShapeChecked) {
  TempDir dir;
  const Intrinsics k = small_camera();
  std::vector<float> values(48, 0.75f);
  values[3] = std::nanf(""), values[4] = 0.0f;
  write_npy(dir / "d.npy", k.width, k.height, values);
  const DepthImage depth = read_depth_image(dir / "d.npy", k);
  EXPECT_FLOAT_EQ(depth.metres[0], 0.75f);
  EXPECT_EQ(depth.metres[3], 0.0f);  // NaN: nothing measured
  EXPECT_EQ(back_project(depth, k).points.rows(), 46);
  write_npy(dir / "t.npy", k.height, k.width, values);  // transposed shape
  EXPECT_THROW(read_depth_image(dir / "t.npy", k), InputError);
  values[7] = -1.0f;
  write_npy(dir / "n.npy", k.width, k.height, values);
  EXPECT_THROW(read_depth_image(dir / "n.npy", k), InputError);
}

TEST(BackProjection, OpenCvFrameXRightYDownZForward) {
  const Intrinsics k = small_camera();
  DepthImage depth{k.width, k.height, std::vector<float>(48, 0.0f)};
  depth.metres[2 * 8 + 7] = 2.0f;  // u = 7 (right of cx), v = 2 (above cy)
  const CameraPoints seen = back_project(depth, k);
  ASSERT_EQ(seen.points.rows(), 1);
  EXPECT_NEAR(seen.points(0, 0), (7 - 3.5) * 2 / 10, 1e-12);  // right: +x
  EXPECT_NEAR(seen.points(0, 1), (2 - 2.5) * 2 / 12, 1e-12);  // above the centre: -y
  EXPECT_NEAR(seen.points(0, 2), 2.0, 1e-12);
  EXPECT_EQ(seen.pixel[0], 23);
  EXPECT_EQ(project_to_pixels(seen.points, k)[0], 23);
  PixelMask none{k.width, k.height, std::vector<std::uint8_t>(48, 0)};
  EXPECT_EQ(back_project(depth, k, &none).points.rows(), 0);
  DepthImage wrong{4, 4, std::vector<float>(16, 1.0f)};
  EXPECT_THROW(back_project(wrong, k), InputError);
}

}  // namespace
}  // namespace partreg::scene
