// The tuned expression library (config/expressions/library.yaml): per expression, muscle
// contractions in head.yaml order, a mandible pose and rigid eyelid closures; plus named
// pose sequences (the chewing cycle).
#pragma once

#include <string>
#include <vector>

#include "facectl/face/face_model.hpp"

namespace facectl::face {

struct Expression {
  std::string name;
  std::vector<double> contractions;  // head.yaml order
  MandiblePose jaw;
  double eyelid_closure[2] = {0, 0};  // left, right
};

struct PoseSequence {
  std::string name;
  double period_s = 1;
  std::vector<std::string> poses;  // expression names, visited in order, evenly spaced
};

struct ExpressionLibrary {
  std::vector<Expression> expressions;
  std::vector<PoseSequence> sequences;
  const Expression* find(const std::string& name) const;
};

// Throws InputError naming file:line:column for unknown muscles, values outside [0, 1],
// mandible values outside the head's envelope or unknown pose names.
ExpressionLibrary load_expression_library(const std::string& path, const HeadSpec& head);

FaceInput face_input(const Expression& e);
// Runs the full model from rest for `frames` frames holding the expression.
void simulate_expression(const FaceModel& m, FaceData& d, const Expression& e, int frames);

}  // namespace facectl::face
