// `gyrostab export LOG --mcap FILE`: a gyrostab bus log (tools/log/bus_log_format.hpp, read by BusLogReader)
// written as an MCAP file (tools/run/run_mcap.hpp) that Foxglove, Lichtblick and PlotJuggler open:
//   /gyrostab/scene     one message at time 0: the scene event (name, device, seed, tick_ns, the scene file
//                       as given and its text byte for byte, the log's channel suffix and version)
//   /gyrostab/sensor    every tick's sensor frame (or every N-th: --every N), the device's signals by name
//   /gyrostab/actuator  every tick's actuator frame              (tools/log/frame_channel.hpp)
//   /gyrostab/log       one message at the last tick read: whether the log was complete, its end event, and
//                       for a cut or damaged log the reader's message and the byte offset it stopped at
// A truncated or corrupt log is exported up to the last whole tick before the damage — no recorded tick is
// lost — and nothing is accepted silently: the file's /gyrostab/log message says complete: false with the
// reader's message, and the command exits 5 with it (as `gyrostab replay` does). A log whose scene event cannot
// be read writes nothing (exit 5; 2 if the file cannot be opened). Docs: docs/mcap.md.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>

namespace gyrostab::tools {

struct ExportRequest {
  std::string log_path;
  std::string mcap_path;
  std::int64_t every{1};  // the frames of every N-th tick
};

inline constexpr int kExportExitIncomplete = 5;

// Exit code: 0 complete, 2 bad options or unreadable file, 3 the MCAP file cannot be written, 5 the log is cut
// or damaged (what it held before the damage is written).
int export_log(const ExportRequest& req);

class RunMcapFile;
// The end every export shares: the /gyrostab/log channel (`what` describes it) with `log`, then the file
// committed. 0, or 3 with the message printed.
int finish_export(RunMcapFile& f, const ExportRequest& req, const nlohmann::json& log, std::int64_t last_tick,
                  const char* what);

}  // namespace gyrostab::tools
