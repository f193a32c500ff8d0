// A FAP file (docs/FAP.md): parse_fap_text, what load_fap_file runs on the
// file's text. A sequence that parses must survive the documented round trip
// parse_fap_text(format_fap_text(s)) == s.
#include <cstdlib>

#include "firmware-host/fap/fap_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  facectl::FapSequence s;
  try {
    s = facectl::parse_fap_text(text, "fuzz.fap");
  } catch (const facectl::FapFormatError&) {  // the documented error: source:line:column
    return 0;
  }
  const facectl::FapSequence back = facectl::parse_fap_text(facectl::format_fap_text(s), "again");
  if (back.frames.size() != s.frames.size() || back.used != s.used ||
      back.header.frame_rate != s.header.frame_rate) {
    std::abort();  // the round trip lost something
  }
  for (std::size_t i = 0; i < s.frames.size(); ++i) {
    if (back.frames[i].number != s.frames[i].number || back.frames[i].mask != s.frames[i].mask ||
        back.frames[i].values != s.frames[i].values) {
      std::abort();
    }
  }
  return 0;
}
