// The geometric part selectors: what they select, and errors that name the value (the command line adds
// its flag, so the same message reads right in `partreg label` and in the app's scripts).
#include "partreg/core/geometry/part_selection.hpp"

#include <gtest/gtest.h>

#include "partreg/core/errors.hpp"

namespace partreg::core {
namespace {

std::string usage_error_of(PartSelector (*parse)(const std::string&), const std::string& text) {
  try {
    parse(text);
  } catch (const UsageError& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(PartSelection, SelectsTheBoxTheHalfSpaceAndTheBall) {
  Points points(4, 3);
  points << 0, 0, 0, 1, 1, 1, 2, 0, 0, 0.5, 0.5, 2;
  EXPECT_EQ(select_points(points, parse_box("1,1,1,-0.1,-0.1,-0.1")), std::vector<bool>({1, 1, 0, 0}));
  EXPECT_EQ(select_points(points, parse_plane("1.5,0,0,2,0,0")), std::vector<bool>({0, 0, 1, 0}));
  EXPECT_EQ(select_points(points, parse_sphere("0.5,0.5,1.5,0.6")), std::vector<bool>({0, 0, 0, 1}));
}

TEST(PartSelection, ErrorsNameTheValueNotAFlag) {
  EXPECT_EQ(usage_error_of(parse_plane, "0,0,0,0,0,0"),
            "the plane's normal 0,0,0 has zero length: it selects no side");
  EXPECT_EQ(usage_error_of(parse_sphere, "1,2,3,-0.5"), "the sphere's radius -0.5 is not positive");
  EXPECT_EQ(usage_error_of(parse_box, "1,2,3"),
            "the box x0,y0,z0,x1,y1,z1 needs 6 comma-separated numbers; '1,2,3' has 3");
  EXPECT_EQ(usage_error_of(parse_sphere, "1,x,3,1"),
            "the sphere cx,cy,cz,r: 'x' in '1,x,3,1' is not a finite number");
  EXPECT_EQ(usage_error_of(parse_plane, "0,0,0,nan,0,1"),
            "the plane px,py,pz,nx,ny,nz: 'nan' in '0,0,0,nan,0,1' is not a finite number");
  for (const auto parse : {parse_box, parse_plane, parse_sphere})
    EXPECT_EQ(usage_error_of(parse, "1,2,3,4,5,6,7").find("--"), std::string::npos);
}

}  // namespace
}  // namespace partreg::core
