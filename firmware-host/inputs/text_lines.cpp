#include "firmware-host/inputs/text_lines.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "facectl/face/bounded_file.hpp"
#include "facectl/face/input_error.hpp"
#include "firmware-host/config/config_node.hpp"

namespace facectl {

TextLines::TextLines(std::string_view text) : rest_(text) {
  if (rest_.substr(0, 3) == "\xEF\xBB\xBF") rest_.remove_prefix(3);
}

bool TextLines::next(std::string_view& line) {
  if (rest_.empty()) return false;
  const std::size_t end = rest_.find('\n');
  line = rest_.substr(0, end);
  rest_.remove_prefix(end == std::string_view::npos ? rest_.size() : end + 1);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  ++number_;
  return true;
}

std::string_view first_line(std::string_view text) {
  TextLines lines(text);
  std::string_view first;
  lines.next(first);
  return first;
}

void fail_at_line(const std::string& file, int line, const std::string& expected,
                  std::string_view found) {
  throw ConfigError(file + ":" + std::to_string(line) + ": expected " + expected + ", found '" +
                    std::string(found.substr(0, 60)) + "'");
}

bool next_csv_row(TextLines& lines, std::size_t width, const std::string& file,
                  std::vector<std::string_view>& fields) {
  std::string_view line;
  do {
    if (!lines.next(line)) return false;
  } while (line.empty());
  fields = split_fields(line, ',');
  if (fields.size() != width) {
    fail_at_line(file, lines.number(), std::to_string(width) + " fields as the header",
                 std::to_string(fields.size()) + " fields");
  }
  return true;
}

std::vector<std::string_view> split_fields(std::string_view line, char sep) {
  std::vector<std::string_view> fields;
  for (;;) {
    const std::size_t end = line.find(sep);
    std::string_view f = line.substr(0, end);
    while (!f.empty() && (f.front() == ' ' || f.front() == '\t')) f.remove_prefix(1);
    while (!f.empty() && (f.back() == ' ' || f.back() == '\t')) f.remove_suffix(1);
    fields.push_back(f);
    if (end == std::string_view::npos) return fields;
    line.remove_prefix(end + 1);
  }
}

bool parse_number(std::string_view field, double& out) {
  if (!field.empty() && field.front() == '+') field.remove_prefix(1);
  const char* end = field.data() + field.size();
  const auto r = std::from_chars(field.data(), end, out);
  return !field.empty() && r.ec == std::errc() && r.ptr == end && std::isfinite(out);
}

std::string read_input_file(const std::string& path, const std::string& what) {
  try {
    return face::read_bounded_file(path, kMaxInputFileBytes, what);
  } catch (const face::InputError& e) {
    throw ConfigError(e.what());
  }
}

std::string read_file_head(const std::string& path, std::size_t n) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw ConfigError(
        path + ": expected a regular file, found " +
        (std::filesystem::exists(path, ec) ? "a directory, FIFO or device" : "nothing"));
  }
  std::ifstream in(path, std::ios::binary);
  std::string head(n, '\0');
  in.read(head.data(), static_cast<std::streamsize>(n));
  if (in.bad() || (!in && !in.eof())) throw ConfigError(path + ": cannot be read");
  head.resize(static_cast<std::size_t>(in.gcount()));
  return head;
}

}  // namespace facectl
