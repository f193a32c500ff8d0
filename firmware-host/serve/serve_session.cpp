#include "firmware-host/serve/serve_session.hpp"

namespace facectl {

void open_serve_session(ServeSession& s, const std::string& event_log_path) {
  const ServeConfig& serve = s.head.cfg->runtime.serve;
  s.log = std::make_unique<EventLog>(event_log_path, serve.event_log_max_kb * 1024,
                                     static_cast<int>(serve.event_log_keep));
  s.shows = std::make_unique<ShowCatalog>(shows_folder(*s.head.cfg), *s.head.cfg);
  keep_off_realtime_cpu(s.head.cfg->runtime.realtime, s.head.rt);
  open_head(s.head, std::nullopt, true);
  s.director = std::make_unique<FaceDirector>(s.head.model().neutral, s.head.mailbox,
                                              s.head.cfg->runtime.show_rate_hz);
  s.service = std::make_unique<HeadService>(s.head, *s.director, *s.shows, *s.log);
  if (const auto& osc = s.head.cfg->runtime.osc) {
    s.osc = std::make_unique<OscControl>(*s.service, *osc);
  }
}

void start_serve_session(ServeSession& s) {
  s.director->start();
  start_head_loop(s.head);
  s.service->start_monitor();
  if (s.osc) s.osc->start();
}

void stop_serve_session(ServeSession& s) {
  if (s.osc) s.osc->stop();
  s.director->stop();
  stop_head_loop(s.head);
  s.service->stop_monitor();
}

}  // namespace facectl
