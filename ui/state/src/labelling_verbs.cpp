// The labelling verbs: parts, the brush and fill, the geometric selectors, undo and redo.
#include <functional>
#include <string>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/part_selection.hpp"
#include "partreg/ui/labelling.hpp"
#include "verb_support.hpp"

namespace partreg::ui::detail {
namespace {

using Handler = std::function<Outcome(AppState&, const Command&)>;

Outcome paint(AppState& state, const Command& command) {
  const Hit hit = pick(state, command);
  const double radius_px =
      number(command.option("radius", std::to_string(state.labelling.brush_radius_px)), "radius");
  if (radius_px <= 0.0) throw UsageError("radius must be positive");
  const double radius = radius_px * pixel_size_at(state.view, state.viewport, hit.distance);
  state.mode = Mode::labelling;
  const int changed = paint_faces(state.labelling, hit.face, hit.point, radius);
  return message("painted " + std::to_string(changed) + " faces");
}

Outcome fill(AppState& state, const Command& command) {
  const Hit hit = pick(state, command);
  state.mode = Mode::labelling;
  return message("filled " + std::to_string(fill_faces(state.labelling, hit.face)) + " faces");
}

template <typename Parse>
Handler selector(Parse parse) {
  return [parse](AppState& state, const Command& command) {
    const int changed = select_faces(state.labelling, parse(command.arguments[0]));
    return message("selected " + std::to_string(changed) + " faces");
  };
}

}  // namespace

std::vector<Verb> labelling_verbs() {
  return {
      {"create_part",
       1,
       1,
       {},
       "NAME",
       [](AppState& s, const Command& c) {
         create_part(s.labelling, c.arguments[0]);
         return message("created part " + c.arguments[0]);
       }},
      {"select_part",
       1,
       1,
       {},
       "NAME",
       [](AppState& s, const Command& c) {
         s.labelling.current_part = find_part(s.labelling, c.arguments[0]);
         return message("painting " + c.arguments[0]);
       }},
      {"rename_part",
       2,
       2,
       {},
       "NAME NEW_NAME",
       [](AppState& s, const Command& c) {
         rename_part(s.labelling, c.arguments[0], c.arguments[1]);
         return message("renamed " + c.arguments[0] + " to " + c.arguments[1]);
       }},
      {"recolor_part",
       4,
       4,
       {},
       "NAME R G B  (0-255)",
       [](AppState& s, const Command& c) {
         recolor_part(s.labelling, c.arguments[0], integer(c.arguments[1], "R"), integer(c.arguments[2], "G"),
                      integer(c.arguments[3], "B"));
         return message("");
       }},
      {"merge_part",
       2,
       2,
       {},
       "FROM INTO",
       [](AppState& s, const Command& c) {
         merge_parts(s.labelling, c.arguments[0], c.arguments[1]);
         return message("merged " + c.arguments[0] + " into " + c.arguments[1]);
       }},
      {"delete_part",
       1,
       1,
       {},
       "NAME",
       [](AppState& s, const Command& c) {
         delete_part(s.labelling, c.arguments[0]);
         return message("deleted " + c.arguments[0]);
       }},
      {"paint", 2, 2, {"radius"}, "X Y [radius=PIXELS]  (pixels from the top-left corner)", paint},
      {"fill", 2, 2, {}, "X Y", fill},
      {"select_box", 1, 1, {}, "X0,Y0,Z0,X1,Y1,Z1", selector(core::parse_box)},
      {"select_plane", 1, 1, {}, "PX,PY,PZ,NX,NY,NZ", selector(core::parse_plane)},
      {"select_sphere", 1, 1, {}, "CX,CY,CZ,R", selector(core::parse_sphere)},
      {"brush",
       1,
       1,
       {},
       "RADIUS_PIXELS",
       [](AppState& s, const Command& c) {
         const double radius = number(c.arguments[0], "RADIUS_PIXELS");
         if (radius <= 0.0) throw UsageError("the brush radius must be positive");
         s.labelling.brush_radius_px = radius;
         return message("");
       }},
      {"undo",
       0,
       0,
       {},
       "",
       [](AppState& s, const Command&) { return message(undo(s.labelling) ? "undone" : "nothing to undo"); }},
      {"redo",
       0,
       0,
       {},
       "",
       [](AppState& s, const Command&) { return message(redo(s.labelling) ? "redone" : "nothing to redo"); }},
  };
}

}  // namespace partreg::ui::detail
