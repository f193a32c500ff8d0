// Writing a head folder (face.yaml, landmarks.yaml, muscles.yaml) from a HeadSpec, so a
// fitted head (head_fit.hpp) loads with load_head_spec like the shipped one.
#pragma once

#include <string>

#include "facectl/face/head_spec.hpp"

namespace facectl::face {

struct HeadFolderSources {
  std::string skin_obj;     // copied byte for byte to <dir>/skin.obj
  std::string skin_units;   // m, cm or mm: how face.yaml reads it
  std::string source_head;  // the folder whose head.yaml (and retarget.yaml) are copied
  std::string note;         // a comment line at the top of face.yaml
};

// Creates `dir` if needed and writes the head: the skin copy, face.yaml (openings,
// tissue, teeth, eyelids, solver, control points of `spec`; no variants), landmarks.yaml,
// muscles.yaml, head.yaml and retarget.yaml from source_head, and every NOTICE* or
// LICEN[CS]E* file beside the OBJ. Not reduced_face.txt: `facectl face reduce` fits it.
// Throws InputError naming the file that cannot be read or written.
void write_head_folder(const std::string& dir, const HeadSpec& spec, const HeadFolderSources& src);

}  // namespace facectl::face
