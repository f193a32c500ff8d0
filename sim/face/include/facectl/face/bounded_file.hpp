// Reading a whole input file with a bound on its size, so that no file (nor
// a FIFO, a device or a file that grows while read) can cost unbounded memory
// or time, and a read error is never taken for the end of the file.
#pragma once

#include <cstdint>
#include <string>

namespace facectl::face {

// The bytes of the regular file `path`. Throws InputError naming the file
// (and `what` it should be, e.g. "YAML file") for a directory, a FIFO or device, a file
// that cannot be opened or read, or one of more than `max_bytes`.
std::string read_bounded_file(const std::string& path, std::uintmax_t max_bytes,
                              const std::string& what);

}  // namespace facectl::face
