#include "firmware-host/serve/event_log.hpp"

#include <systemd/sd-journal.h>

#include <chrono>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <system_error>

namespace facectl {
namespace {

constexpr std::size_t kRecentEntries = 1000;

std::string now_iso8601() {
  const auto now = std::chrono::system_clock::now();
  const std::time_t secs = std::chrono::system_clock::to_time_t(now);
  const auto ms =
      std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm tm{};
  gmtime_r(&secs, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S", &tm);
  char out[40];
  std::snprintf(out, sizeof out, "%s.%03dZ", buf, static_cast<int>(ms));
  return out;
}

}  // namespace

std::string EventLog::default_path() {
  if (const char* logs = std::getenv("LOGS_DIRECTORY"); logs != nullptr && *logs != '\0') {
    return std::string(logs) + "/events.jsonl";
  }
  if (const char* state = std::getenv("XDG_STATE_HOME"); state != nullptr && *state != '\0') {
    return std::string(state) + "/facectl/events.jsonl";
  }
  const char* home = std::getenv("HOME");
  return std::string(home != nullptr ? home : ".") + "/.local/state/facectl/events.jsonl";
}

EventLog::EventLog(std::string path, long max_bytes, int keep)
    : path_(std::move(path)),
      max_bytes_(max_bytes),
      keep_(keep),
      // journald hands services it captures this variable (systemd.exec(5)).
      journal_(std::getenv("JOURNAL_STREAM") != nullptr) {
  std::error_code ec;
  const std::filesystem::path parent = std::filesystem::path(path_).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  file_ = std::fopen(path_.c_str(), "a");
  if (file_ == nullptr) {
    throw std::runtime_error("event log " + path_ + ": cannot open for appending: " +
                             std::generic_category().message(errno));
  }
  size_ = static_cast<long>(std::ftell(file_));
}

EventLog::~EventLog() {
  if (file_ != nullptr) std::fclose(file_);
}

void EventLog::rotate() {
  std::fclose(file_);
  std::error_code ec;
  for (int i = keep_ - 1; i >= 1; --i) {
    std::filesystem::rename(path_ + "." + std::to_string(i), path_ + "." + std::to_string(i + 1),
                            ec);
  }
  std::filesystem::rename(path_, path_ + ".1", ec);
  file_ = std::fopen(path_.c_str(), "a");
  size_ = 0;
}

void EventLog::add(std::string kind, std::string source, std::string text) {
  Entry e{now_iso8601(), std::move(kind), std::move(source), std::move(text)};
  const std::string line =
      nlohmann::json{{"time", e.time}, {"kind", e.kind}, {"source", e.source}, {"text", e.text}}
          .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) +
      "\n";
  const std::lock_guard lock(mutex_);
  if (file_ != nullptr && size_ > 0 && size_ + static_cast<long>(line.size()) > max_bytes_) {
    rotate();
  }
  if (file_ == nullptr || std::fwrite(line.data(), 1, line.size(), file_) != line.size() ||
      std::fflush(file_) != 0) {
    ++write_errors_;
  } else {
    size_ += static_cast<long>(line.size());
  }
  if (!journal_) {
    std::fprintf(stderr, "%s %s [%s] %s\n", e.time.c_str(), e.kind.c_str(), e.source.c_str(),
                 e.text.c_str());
  } else {
    const int priority = e.kind == "fault" ? 3 : 6;  // LOG_ERR, LOG_INFO
    sd_journal_send("MESSAGE=%s: %s", e.source.c_str(), e.text.c_str(), "PRIORITY=%d", priority,
                    "FACECTL_EVENT=%s", e.kind.c_str(), nullptr);
  }
  recent_.push_back(std::move(e));
  if (recent_.size() > kRecentEntries) recent_.pop_front();
}

std::vector<EventLog::Entry> EventLog::recent(std::size_t limit) const {
  const std::lock_guard lock(mutex_);
  const std::size_t n = std::min(limit, recent_.size());
  return {recent_.end() - static_cast<std::ptrdiff_t>(n), recent_.end()};
}

std::size_t EventLog::write_errors() const {
  const std::lock_guard lock(mutex_);
  return write_errors_;
}

}  // namespace facectl
