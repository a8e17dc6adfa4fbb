#include "partreg/ui/labelling.hpp"

#include <gtest/gtest.h>

#include "partreg/core/errors.hpp"
#include "partreg/io/labels_file.hpp"
#include "partreg/ui/executor.hpp"
#include "partreg/ui/script.hpp"
#include "ui/ui_fixtures.hpp"

namespace partreg::ui {
namespace {

void run(AppState& state, const std::string& script) {
  for (const Command& command : parse_script(script)) execute(state, command);
}

// The handle's box in the mesh's frame, from the faces the fixture knows are the handle's.
std::string handle_box(Eigen::VectorXi* face_part = nullptr) {
  Eigen::VectorXi parts;
  const core::Mesh mesh = testing::merged_mug(0, &parts);
  Eigen::Vector3d low = Eigen::Vector3d::Constant(1e9), high = -low;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    if (parts[f] == 1)
      for (int c = 0; c < 3; ++c) {
        low = low.cwiseMin(mesh.vertices.row(mesh.faces(f, c)).transpose());
        high = high.cwiseMax(mesh.vertices.row(mesh.faces(f, c)).transpose());
      }
  if (face_part) *face_part = parts;
  std::ostringstream box;
  box << low.x() << ',' << low.y() << ',' << low.z() << ',' << high.x() << ',' << high.y() << ',' << high.z();
  return box.str();
}

TEST(Labelling, PartsUndoRedoAndSave) {
  AppState state;
  run(state, "load " + testing::mug_mesh_path().string() + "\ncreate_part body\ncreate_part handle");
  ASSERT_TRUE(state.labelling.loaded());
  EXPECT_EQ(state.labelling.current_part, 1);
  Eigen::VectorXi truth;
  run(state, "select_box " + handle_box(&truth));
  const Eigen::VectorXi& labels = state.labelling.labels.labels;
  int handle_hits = 0, handle_faces = 0;
  for (Eigen::Index f = 0; f < labels.size(); ++f) {
    handle_faces += truth[f] == 1;
    handle_hits += truth[f] == 1 && labels[f] == 1;
  }
  EXPECT_EQ(handle_hits, handle_faces);  // every handle face lies inside its own box
  EXPECT_TRUE(state.labelling.dirty);
  const Eigen::Index selected = (labels.array() == 1).count();

  run(state, "rename_part handle grip\nundo");
  EXPECT_EQ(state.labelling.labels.names[1], "handle");
  run(state, "redo");
  EXPECT_EQ(state.labelling.labels.names[1], "grip");

  const std::string saved = (testing::ui_fixture_folder() / "labelling_test.labels.json").string();
  run(state, "save_labels " + saved);
  EXPECT_FALSE(state.labelling.dirty);
  const io::PartLabels read = io::read_labels_file(saved);
  EXPECT_EQ(read.names, (std::vector<std::string>{"body", "grip"}));
  EXPECT_EQ(read.labels, state.labelling.labels.labels);

  run(state, "merge_part grip body");
  EXPECT_EQ(state.labelling.labels.names.size(), 1u);
  EXPECT_EQ((state.labelling.labels.labels.array() == 0).count(), selected);
  run(state, "undo");  // one undo step restores the merge
  EXPECT_EQ(state.labelling.labels.names.size(), 2u);
  run(state, "delete_part body");
  EXPECT_EQ(state.labelling.labels.names, std::vector<std::string>{"grip"});
  EXPECT_EQ((state.labelling.labels.labels.array() == 0).count(), selected);  // grip moved to index 0
}

TEST(Labelling, FillLabelsTheConnectedUnlabelledRest) {
  AppState state;
  run(state, "load " + testing::mug_mesh_path().string() + "\ncreate_part handle\nselect_box " +
                 handle_box() + "\ncreate_part body\ncamera front");
  // Fill from the pixel in the middle of the mug: the body, seen from the front.
  const Eigen::Vector2d centre = project(state.view, state.viewport, state.view.target);
  run(state, "fill " + std::to_string(centre.x()) + " " + std::to_string(centre.y()));
  const std::vector<int> counts = part_face_counts(state.labelling);
  EXPECT_GT(counts[1], 0);
  EXPECT_LT(counts[2], state.labelling.mesh.faces.rows() / 20) << "most faces are labelled after the fill";
}

TEST(Labelling, BadInputChangesNothing) {
  AppState state;
  run(state, "load " + testing::mug_mesh_path().string() + "\ncreate_part body");
  const io::PartLabels before = state.labelling.labels;
  EXPECT_THROW(run(state, "load /nonexistent/mug.obj"), InputError);
  EXPECT_EQ(state.labelling.mesh_path, testing::mug_mesh_path().string());
  // A labels file for another mesh (a different face count) is refused with the reason.
  io::PartLabels other = before;
  other.labels = Eigen::VectorXi::Zero(10);
  const std::string other_path = (testing::ui_fixture_folder() / "other.labels.json").string();
  io::write_labels_file(other_path, other);
  try {
    run(state, "load_labels " + other_path);
    FAIL() << "labels for another mesh must be refused";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("10 labels"), std::string::npos) << error.what();
  }
  EXPECT_EQ(state.labelling.labels.labels, before.labels);
  EXPECT_THROW(run(state, "select_part lid"), UsageError);
  EXPECT_FALSE(execute_reporting(state, make_command("select_part", {"lid"})));
  EXPECT_TRUE(state.status_is_error);
  EXPECT_NE(state.status.find("body"), std::string::npos) << "the message lists the parts: " << state.status;
}

}  // namespace
}  // namespace partreg::ui
