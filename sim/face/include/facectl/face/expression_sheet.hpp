// The expression pictures people read: each expression of the library beside a heat map
// of its skin's displacement from the neutral pose, labelled with its name, on one fixed
// mm scale so expressions compare, with a colour bar stating that scale.
#pragma once

#include <functional>
#include <string>

#include "facectl/face/expression_library.hpp"
#include "facectl/face/face_renderer.hpp"

namespace facectl::face {

struct SheetOptions {
  View view = View::kThreeQuarter;
  Lighting lighting = Lighting::kRaking;
  int tile_width = 240, tile_height = 300;  // each picture; a cell holds two
  int columns = 3;                          // cells per row
  double heat_max_mm = 10;                  // red from here up
  int frames = 300;                         // full-model frames per expression
};

// Throws std::invalid_argument naming the option when one is out of range.
void validate(const SheetOptions& o);
// The skin of the library's "neutral" expression after o.frames frames, or the rest skin
// when the library has none.
Points neutral_skin(const FaceModel& m, const ExpressionLibrary& lib, int frames);
// One cell: `name` above the posed skin in `d` and its displacement heat map against
// `neutral`.
Image expression_cell(const FaceModel& m, const FaceData& d, const Points& neutral,
                      const std::string& name, const SheetOptions& o);
// `picture` with the colour bar of the scale below it.
Image with_colour_bar(const Image& picture, double heat_max_mm);
// Every expression in library order, row by row, then the colour bar. `done` (if set) is
// called with each name after it is drawn.
Image expression_sheet(const FaceModel& m, const ExpressionLibrary& lib, const SheetOptions& o,
                       const std::function<void(const std::string&)>& done = {});

}  // namespace facectl::face
