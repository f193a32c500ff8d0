#pragma once

#include <array>
#include <bitset>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "firmware-host/config/config_node.hpp"
#include "firmware-host/fap/fap_table.hpp"

namespace facectl {

// A FAP file or stream is unusable. The message names source:line:column, what
// was expected and what was found.
class FapFormatError : public ConfigError {
 public:
  FapFormatError(const std::string& message, int line) : ConfigError(message), line_(line) {}
  int line() const { return line_; }

 private:
  int line_;
};

// FAP 1: two visemes of the table (0..14) blended by blend/63 towards the second.
struct VisemeParams {
  int select1 = 0, select2 = 0, blend = 0, def = 0;
};

// FAP 2: two expressions (0 none, 1 joy .. 6 surprise), each at intensity/63.
struct ExpressionParams {
  int select1 = 0, intensity1 = 0, select2 = 0, intensity2 = 0, init_face = 0, def = 0;
};

using FapMask = std::bitset<kFapCount>;  // bit n-1 is FAP n

struct FapFrame {
  long number = 0;
  FapMask mask;
  std::array<double, kFapCount> values{};  // FAPU units, index n-1; only masked ones are set
  VisemeParams viseme;                     // valid when mask[0]
  ExpressionParams expression;             // valid when mask[1]
  // Read but not played: Greta's one-value FAP 1 and 2 (bit 0, 1), which are
  // not the standard's viseme and expression fields (docs/FAP.md, leniencies).
  FapMask unplayed;
  int line = 0;  // line of the values
};

struct FapHeader {
  std::string version;      // "2.0" or "2.1"
  std::string name;         // may hold spaces (Greta writes its file path there)
  double frame_rate = 0.0;  // frames per second
  long frame_count = 0;
};

// A whole FAP file: the header and every frame, frame numbers strictly increasing.
struct FapSequence {
  std::string source;
  FapHeader header;
  std::vector<FapFrame> frames;
  FapMask used;      // FAPs that some frame transmits
  FapMask unplayed;  // FAPs that some frame carries in a form that is not played
  double time_of(const FapFrame& f) const {
    return static_cast<double>(f.number) / header.frame_rate;
  }
};

// The ASCII FAP format (docs/FAP.md): a header line "version name rate count",
// then per frame a mask line of 68 0/1 entries and a values line "frame v...",
// FAP 1 taking 4 integers and FAP 2 six. Lines starting with '#' and blank lines
// are skipped. One reader serves files and the UDP stream, line by line.
// It also reads what Greta writes: a name with spaces, and masks of 69 entries
// whose last is 0 and whose FAP 1 and 2 take one value each.
class FapReader {
 public:
  explicit FapReader(std::string source) : source_(std::move(source)) {}

  // Consumes one line (without its newline). Returns a frame when the line
  // completed one. Throws FapFormatError; the reader is then unusable.
  std::optional<FapFrame> feed(std::string_view line, int line_number);

  bool has_header() const { return header_.has_value(); }
  const FapHeader& header() const { return *header_; }
  bool mid_frame() const { return state_ == State::kValues; }
  int mask_line() const { return mask_line_; }
  long frames_read() const { return frames_; }
  std::optional<long> last_frame_number() const { return last_number_; }
  const std::string& source() const { return source_; }
  void set_source(std::string source) { source_ = std::move(source); }
  // For streams: a new header starts a new sequence (numbering restarts).
  void allow_new_header(bool allow) { allow_new_header_ = allow; }

  [[noreturn]] void fail(int line, int column, std::string_view expected,
                         std::string_view found) const;

 private:
  enum class State { kHeader, kMask, kValues };
  void read_header(std::string_view line, int line_number);
  void read_mask(std::string_view line, int line_number);
  FapFrame read_values(std::string_view line, int line_number);

  std::string source_;
  State state_ = State::kHeader;
  std::optional<FapHeader> header_;
  FapMask mask_;
  bool greta_mask_ = false;  // the mask had Greta's 69 entries
  int mask_line_ = 0;
  long frames_ = 0;
  std::optional<long> last_number_;
  bool allow_new_header_ = false;
};

// Parses a whole FAP text: everything or a FapFormatError, never part of it.
FapSequence parse_fap_text(std::string_view text, const std::string& source);
// Writes a sequence in the same text format (values with up to 17 significant
// digits, so parse_fap_text(format_fap_text(s)) gives s back).
std::string format_fap_text(const FapSequence& sequence);
// The largest FAP file load_fap_file reads: about 5 hours of Greta's frames
// at 25 fps, and at most about 500 MB once parsed and mapped (docs/FAP.md).
inline constexpr std::uintmax_t kMaxFapFileBytes = 64u << 20;

// Reads and parses a file. Throws FapFormatError, or ConfigError naming the
// file if it is unreadable, not a regular file or over kMaxFapFileBytes.
FapSequence load_fap_file(const std::string& path);

}  // namespace facectl
