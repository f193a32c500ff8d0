#pragma once

#include <string>
#include <string_view>

namespace facectl {

// Text for HTML or SVG, in an element or a double-quoted attribute: & < > "
// become entities, everything else passes as it is.
std::string escape_markup(std::string_view text);

}  // namespace facectl
