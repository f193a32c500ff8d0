#pragma once

#include <string>

namespace facectl {

// The service manager's protocol (sd_notify(3)): each call is a no-op unless
// systemd started us with NOTIFY_SOCKET.
void notify_ready(const std::string& status);
void notify_status(const std::string& status);
void notify_watchdog();  // only while the loop ticks: a stalled loop lets systemd restart us
void notify_stopping();

}  // namespace facectl
