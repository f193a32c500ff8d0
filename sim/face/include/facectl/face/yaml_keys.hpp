// The mapping keys of a YAML document, checked before anything reads them.
#pragma once

#include <string>

namespace YAML {
class Node;
}

namespace facectl::face {

// Throws InputError (file:line:column) at the first key of `root`, in file
// order, that is not a plain name (`? [a, b] : 1`) or repeats an earlier key
// of its mapping. yaml-cpp keeps both copies of a repeated key, and lookups
// take the first while iteration takes the last: neither may decide.
void check_yaml_keys(const std::string& file, const YAML::Node& root);

}  // namespace facectl::face
