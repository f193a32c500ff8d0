// SHA-256 of a file's bytes as lowercase hex, what `sha256sum` prints: the reduced model
// records its head files' digests so that a model fitted to other files is refused.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "facectl/face/head_spec.hpp"

namespace facectl::face {

// Throws InputError when the file cannot be read.
std::string sha256_file_hex(const std::string& path);

// {file relative to the head folder, its SHA-256} for every file of the head.
std::vector<std::array<std::string, 2>> head_file_digests(const HeadSpec& head);

}  // namespace facectl::face
