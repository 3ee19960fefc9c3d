// `gyrostab export LOG --mcap FILE` for a candump log of the CAN bus (`--can-log`, hil/can/candump_log.hpp):
// the same channels as a bus log's export (bus_log_export.hpp), read the way the controller reads the bus.
// The log's header lines name the device and its CAN map (`# can-map TABLE FINGERPRINT`), the scene, seed and
// tick and carry the scene text; the frames are assembled into sensor and command sets with can::SetAssembler
// on the device's map (hil/can/frame_codec.hpp, the live link's decoder), and every tick with both sets becomes
// one /gyrostab/sensor and one /gyrostab/actuator message at simulated time tick x tick_ns.
// A log is complete when it holds the plant's end-of-run set (docs/protocol.md); the controller's answer to it,
// when the log holds one, is reported.
// A log cut in a line, a line that is not a candump frame, or a log without the end of the run: every whole
// tick before it is written and /gyrostab/log says incomplete and why (exit 5). A log without a gyrostab header
// (no `# device` line: candump's own) is refused (exit 2); one recorded with another map or log version, or
// without its tick, writes nothing (exit 5). Frames the decoder rejects (error frames, resends, foreign
// identifiers) are counted by cause, not exported. Docs: docs/mcap.md.
#pragma once

#include "tools/log/bus_log_export.hpp"

namespace gyrostab::tools {

int export_candump_log(const ExportRequest& req);

}  // namespace gyrostab::tools
