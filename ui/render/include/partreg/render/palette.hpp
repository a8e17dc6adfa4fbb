#pragma once
/// \file
/// The fixed colours of partreg's pictures. Parts and files take the colour-blind-safe Okabe-Ito palette
/// that labels files use (partreg::io::part_color), so a part has the same colour in the GUI, in label files
/// and in figures.

#include <Eigen/Core>

namespace partreg::render {

/// An sRGB colour with channels in [0, 1].
using Color = Eigen::Vector3f;

/// The palette colour of part `index` (Okabe-Ito, repeating after 8); grey for a negative (unlabelled) index.
Color part_color(int index);

/// The colour of the `index`-th file of a `partreg render` command (the same palette).
Color file_color(int index);

/// The red of observed clouds in comparison figures (distinct from every palette colour).
Color observed_color();

/// The grey of uncoloured geometry.
Color neutral_color();

}  // namespace partreg::render
