// libFuzzer target for the link's session and authentication layer (hil/link/link_guard.hpp through the
// endpoint every transport uses, hil/link/frame_endpoint.hpp): arbitrary bytes cut into datagrams and put on
// the in-memory bus of a plant and a controller. Beyond "no crash / no sanitizer report":
//   - with a link key the input does not know, no datagram is ever returned as a frame (every one fails its
//     MAC, or is refused before it): a frame that passes is a forgery that got through;
//   - without a key, a frame returned after the handshake is of the bound session and the bound peer, and no
//     frame of session 0 (a recording) is ever returned;
//   - every datagram that decodes is counted exactly once: returned, or refused by the guard.
// Built only with -DGYROSTAB_FUZZ=ON and clang; run it with tools/fuzz/run-link-guard-fuzz or run-all.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>

#include "hil/lcm/frame_codec.hpp"
#include "hil/link/frame_endpoint.hpp"
#include "hil/link/link_guard.hpp"
#include "hil/link/memory_bus.hpp"
#include "gyrostab_signals/monorail_frames.hpp"

namespace {

using namespace gyrostab;

constexpr std::uint64_t kSession = 0x1234abcd;
constexpr std::uint64_t kControllerId = 0x0badf00d;

firmware::link::Key128 secret_key() {
  firmware::link::Key128 k;
  for (std::size_t i = 0; i < k.bytes.size(); ++i) k.bytes[i] = static_cast<std::uint8_t>(0x5c ^ (i * 37));
  return k;
}

template <class Frame>
void feed(hil::FrameEndpoint<hil::MemoryTransport>& ep, hil::MemoryQueue& q, const std::uint8_t* data, int n,
          bool keyed, bool& bound) {
  if (!q.push(data, n)) return;
  Frame f{};
  const std::uint64_t before = ep.guard().counters().rejected();
  const hil::RxStatus s = ep.receive(0, f);  // already due: the datagram is in the queue
  if (s != hil::RxStatus::kMessage) return;
  if (keyed) __builtin_trap();  // a forgery without the key was accepted
  const hil::LinkEnvelope& e = ep.last_envelope();
  if (e.session == 0) __builtin_trap();  // a recorded frame was accepted
  if (ep.guard().counters().rejected() != before) __builtin_trap();
  if (e.sender == 0) __builtin_trap();  // no live end has id 0
  if (bound) {
    if (e.session != ep.guard().session() || e.sender != ep.guard().peer()) __builtin_trap();
  } else {
    ep.bind_to_last();
    bound = ep.guard().bound();
    if (!bound) __builtin_trap();  // a frame that passed must name a peer to bind to
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const bool keyed = (data[0] & 1) != 0;
  const std::optional<firmware::link::Key128> key = keyed ? std::optional(secret_key()) : std::nullopt;
  static auto bus = std::make_unique<hil::MemoryBus>();
  // Empty both queues of an earlier input.
  std::uint8_t sink[hil::kMaxMessageBytes];
  while (bus->to_plant.pop(sink, 0) >= 0) {
  }
  while (bus->to_controller.pop(sink, 0) >= 0) {
  }
  hil::MemoryTransport plant_side{bus->to_controller, bus->to_plant};
  hil::MemoryTransport controller_side{bus->to_plant, bus->to_controller};
  hil::FrameEndpoint<hil::MemoryTransport> plant(plant_side, hil::plant_guard(kSession, key),
                                                 msg::monorail::kSignals);
  hil::FrameEndpoint<hil::MemoryTransport> controller(controller_side, hil::controller_guard(kControllerId, 0, key),
                                                      msg::monorail::kSignals);
  bool plant_bound = false, controller_bound = false;
  // Datagrams: a length byte (its low bit picks the direction, the rest n gives the length 2n + 2, 2 to 256),
  // then that many bytes; the monorail's frames, 128 and 104 bytes, are n = 63 and n = 51.
  std::size_t i = 1;
  while (i < size) {
    const int len = 2 * (data[i] >> 1) + 2;
    const bool to_plant = (data[i] & 1) != 0;
    ++i;
    const int n = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(len), size - i));
    if (to_plant) {
      feed<msg::monorail::ActuatorFrame>(plant, bus->to_plant, data + i, n, keyed, plant_bound);
    } else {
      feed<msg::monorail::SensorFrame>(controller, bus->to_controller, data + i, n, keyed, controller_bound);
    }
    i += static_cast<std::size_t>(n);
  }
  return 0;
}
