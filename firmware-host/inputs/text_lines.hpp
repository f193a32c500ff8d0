#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace facectl {

// Line-by-line reading of a text input (CSV, TSV), with the line number for
// errors: strips a UTF-8 byte-order mark and CR LF endings.
class TextLines {
 public:
  explicit TextLines(std::string_view text);
  bool next(std::string_view& line);  // false at the end
  int number() const { return number_; }

 private:
  std::string_view rest_;
  int number_ = 0;
};

// The first line (without BOM or CR), empty for an empty text.
std::string_view first_line(std::string_view text);

// Throws ConfigError "file:line: expected <expected>, found '<found>'", the
// found text cut at 60 characters.
[[noreturn]] void fail_at_line(const std::string& file, int line, const std::string& expected,
                               std::string_view found);

// The next non-empty line of a CSV body as its comma-separated fields;
// false at the end. A row with other than `width` fields is refused at its line.
bool next_csv_row(TextLines& lines, std::size_t width, const std::string& file,
                  std::vector<std::string_view>& fields);

// Fields split at `sep`, each trimmed of blanks (OpenFace writes ", ").
std::vector<std::string_view> split_fields(std::string_view line, char sep);

// The whole field as a finite number, or false.
bool parse_number(std::string_view field, double& out);

// The bytes of a regular file of at most `max_bytes`; ConfigError naming it otherwise.
std::string read_input_file(const std::string& path, const std::string& what);

// At most the first `n` bytes of `path` (for format detection); ConfigError
// naming it when it is not a regular file or cannot be read.
std::string read_file_head(const std::string& path, std::size_t n);

// The most an input file may hold: 64 MiB, about 3 hours of Live Link Face CSV at 60 fps.
inline constexpr std::size_t kMaxInputFileBytes = std::size_t{64} << 20;

}  // namespace facectl
