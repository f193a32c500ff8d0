#pragma once

#include <cstdio>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

namespace facectl {

// What happened to the head, for the operator and for later: every state
// transition, fault, reset and API command with its source. Appended as JSON
// lines to a file that survives restarts and rotates by size
// (events.jsonl -> events.jsonl.1 ...); also sent to the journal under
// systemd, else printed on stderr.
// The last entries stay in memory for GET /api/v1/events. Thread-safe; never
// called from the real-time thread.
class EventLog {
 public:
  struct Entry {
    std::string time;    // ISO 8601, UTC, milliseconds
    std::string kind;    // "transition", "fault", "command", "service"
    std::string source;  // "loop", "api 127.0.0.1", "signal"
    std::string text;
  };

  // Opens (creating its folder) or throws naming the path.
  EventLog(std::string path, long max_bytes, int keep);
  ~EventLog();
  EventLog(const EventLog&) = delete;
  EventLog& operator=(const EventLog&) = delete;

  void add(std::string kind, std::string source, std::string text);
  std::vector<Entry> recent(std::size_t limit) const;
  const std::string& path() const { return path_; }
  // Rows the file refused (a full disk): the entries stay in memory and the journal.
  std::size_t write_errors() const;

  // $LOGS_DIRECTORY/events.jsonl under systemd, else the XDG state folder.
  static std::string default_path();

 private:
  void rotate();  // caller holds mutex_

  std::string path_;
  long max_bytes_;
  int keep_;
  bool journal_;
  mutable std::mutex mutex_;
  std::FILE* file_ = nullptr;
  long size_ = 0;
  std::size_t write_errors_ = 0;
  std::deque<Entry> recent_;
};

}  // namespace facectl
