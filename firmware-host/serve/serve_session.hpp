#pragma once

#include <memory>
#include <string>

#include "firmware-host/run/head_runtime.hpp"
#include "firmware-host/serve/event_log.hpp"
#include "firmware-host/serve/face_director.hpp"
#include "firmware-host/serve/head_service.hpp"
#include "firmware-host/serve/osc_control.hpp"
#include "firmware-host/serve/show_catalog.hpp"

namespace facectl {

// What `facectl serve` runs, without its HTTP side: the head, the event log,
// the shows, the face command source and the service over them. Declared in
// the order they are built; destroyed in reverse.
struct ServeSession {
  HeadRuntime head;
  std::unique_ptr<EventLog> log;
  std::unique_ptr<ShowCatalog> shows;
  std::unique_ptr<FaceDirector> director;
  std::unique_ptr<HeadService> service;
  std::unique_ptr<OscControl> osc;  // with an `osc:` block in the runtime file
};

// With head.cfg loaded: opens the event log, the hardware and the
// controller (with a telemetry ring for the monitor), and builds the rest.
// Nothing is started. Throws naming what cannot be opened.
void open_serve_session(ServeSession& s, const std::string& event_log_path);

// Starts the face command source, the real-time loop, the monitor and the
// OSC control. The head stays IDLE until enabled.
void start_serve_session(ServeSession& s);

// Stops the OSC control, the source and the loop, releases the outputs,
// then the monitor (which logs the last transitions).
void stop_serve_session(ServeSession& s);

}  // namespace facectl
