// The frames as channels (tools/log/frame_channel.hpp): the header fields and the table's signals, an array as
// one JSON array, integers as integers, every double back bit for bit; the JSON Schema's arrays, units and
// ranges; the frame table of `run --mcap` (every N-th tick, sized before the run, refused past the ceiling);
// the tick fan-out; the live view's growable store (doubling its span keeps every bucket exactly).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "tests/support/union_frames.hpp"
#include "tools/log/frame_channel.hpp"
#include "tools/run/frame_table.hpp"
#include "tools/view/view_store.hpp"

namespace gyrostab {
namespace frame_channel_test {

using tools::FrameDirection;

const msg::DeviceSignals& device() { return msg::kSignals; }  // the union fixture

msg::AnySensorFrame sensor_frame(std::int64_t k) {
  msg::AnySensorFrame f{};
  f.tick = static_cast<std::uint64_t>(k);
  f.time_ns = k * 1'000'000;
  f.sample_time_ns = f.time_ns - 7;
  f.sequence = static_cast<std::uint32_t>(k);
  f.status = 5;
  for (std::size_t i = 0; i < device().sensors.size(); ++i) f.signal[i] = 1.0 / 3.0 * double(k) - double(i) * 1e-17;
  return f;
}

msg::AnyActuatorFrame actuator_frame(std::int64_t k) {
  msg::AnyActuatorFrame f{};
  f.tick = static_cast<std::uint64_t>(k);
  f.time_ns = k * 1'000'000;
  f.sensor_tick = f.tick;
  f.sequence = static_cast<std::uint32_t>(k + 1);
  f.status = 1u << 9;
  for (std::size_t i = 0; i < device().commands.size(); ++i) f.signal[i] = -0.1 * double(k) * double(i + 1);
  return f;
}

TEST(FrameChannel, HeaderThenTheTablesSignalsWithTheirElements) {
  const tools::ChannelInfo c = tools::frame_channel(device(), FrameDirection::kSensor);
  EXPECT_EQ(c.topic, "/gyrostab/sensor");
  EXPECT_EQ(c.title, "gyrostab.union_fixture.sensor");
  ASSERT_EQ(c.signals.size(), tools::frame_width(device(), FrameDirection::kSensor));
  EXPECT_EQ(tools::label_of(c.signals[0]), "time_ns");
  EXPECT_TRUE(c.signals[3].integer);
  EXPECT_EQ(c.signals[3].name, "status");
  for (std::size_t i = 0; i < device().sensors.size(); ++i) {
    const msg::SignalSpec& spec = device().sensors[i];
    const tools::SignalInfo& s = c.signals[tools::kFrameHeaderValues + i];
    EXPECT_EQ(s.name, spec.name);
    EXPECT_EQ(s.unit, std::string(spec.unit));
    EXPECT_EQ(s.min, spec.min);
    EXPECT_EQ(s.max, spec.max);
    EXPECT_EQ(s.count, spec.count);
    EXPECT_EQ(s.element, spec.element);
    EXPECT_TRUE(s.declared);
  }
  EXPECT_EQ(tools::label_of(c.signals[tools::kFrameHeaderValues + 1]), "carrier_angle_rad[1]");
}

TEST(FrameChannel, JsonRowsReadBackBitForBit) {
  for (const FrameDirection d : {FrameDirection::kSensor, FrameDirection::kActuator}) {
    const tools::ChannelInfo c = tools::frame_channel(device(), d);
    std::vector<double> v(c.signals.size());
    if (d == FrameDirection::kSensor) tools::frame_values(sensor_frame(123456789), device(), v.data());
    else tools::frame_values(actuator_frame(123456789), device(), v.data());
    v.back() = std::nan("");  // JSON has no NaN: null
    std::string text;
    tools::append_json_row(text, c, 123456789, v.data());
    const nlohmann::json j = nlohmann::json::parse(text);
    EXPECT_EQ(j["tick"], 123456789);
    EXPECT_TRUE(j["time_ns"].is_number_integer()) << text;
    EXPECT_EQ(j["time_ns"].get<std::int64_t>(), 123456789LL * 1'000'000);
    for (std::size_t i = 0; i < c.signals.size(); ++i) {
      const tools::SignalInfo& s = c.signals[i];
      const nlohmann::json& f = s.count > 1 ? j[s.name][s.element] : j[s.name];
      if (i + 1 == c.signals.size()) {
        EXPECT_TRUE(f.is_null());
        continue;
      }
      EXPECT_EQ(f.get<double>(), v[i]) << tools::label_of(s);
      if (s.count > 1) {
        EXPECT_EQ(j[s.name].size(), s.count);
      }
    }
  }
}

TEST(FrameChannel, SchemaDeclaresArraysUnitsAndRanges) {
  const nlohmann::json schema =
      nlohmann::json::parse(tools::json_schema(tools::frame_channel(device(), FrameDirection::kActuator)));
  const nlohmann::json& torque = schema["properties"]["gimbal_torque_Nm"];
  EXPECT_EQ(torque["type"], "array");
  EXPECT_EQ(torque["minItems"], 2);
  EXPECT_EQ(torque["maxItems"], 2);
  EXPECT_EQ(torque["unit"], "N m");
  EXPECT_EQ(torque["items"]["maximum"], 1e7);
  EXPECT_NE(torque["description"].get<std::string>().find("[N m]"), std::string::npos);
  EXPECT_EQ(schema["properties"]["status"]["type"], "integer");
  EXPECT_EQ(schema["properties"]["precession_brake"]["type"], nlohmann::json({"number", "null"}));
}

TEST(FrameTable, KeepsEveryNthTickInATableSizedBeforeTheRun) {
  tools::FrameTable t(device(), 10, 3);
  for (std::int64_t k = 0; k < 10; ++k) EXPECT_TRUE(t.record(k, sensor_frame(k), actuator_frame(k)));
  ASSERT_EQ(t.rows(), 4u);  // 0, 3, 6, 9
  std::vector<double> want(tools::frame_width(device(), FrameDirection::kActuator));
  for (std::size_t r = 0; r < t.rows(); ++r) {
    EXPECT_EQ(t.tick(r), static_cast<std::int64_t>(3 * r));
    tools::frame_values(actuator_frame(t.tick(r)), device(), want.data());
    for (std::size_t j = 0; j < want.size(); ++j) EXPECT_EQ(t.rows_of(FrameDirection::kActuator).value(r, j), want[j]);
  }
  // Past its capacity a table ignores further ticks (the run never passes the length it was sized for).
  EXPECT_TRUE(t.record(12, sensor_frame(12), actuator_frame(12)));
  EXPECT_EQ(t.rows(), 4u);
  EXPECT_EQ(tools::FrameTable::size_problem(device(), 1'000'000, 1), "");
  const std::string big = tools::FrameTable::size_problem(device(), 100'000'000, 1);
  EXPECT_NE(big.find("--mcap-frames-every"), std::string::npos) << big;
}

TEST(TickFanOut, BothSinksSeeEveryTick) {
  tools::FrameTable a(device(), 5, 1), b(device(), 5, 2);
  tools::TickFanOut fan(&a, &b);
  for (std::int64_t k = 0; k < 5; ++k) fan.sink()->record(k, sensor_frame(k), actuator_frame(k));
  EXPECT_EQ(a.rows(), 5u);
  EXPECT_EQ(b.rows(), 3u);
  tools::TickFanOut one(nullptr, &a);
  EXPECT_EQ(one.sink(), &a);
}

TEST(ViewStore, GrowingKeepsEveryBucketExactly) {
  // A bus's run of unknown length: the store starts at 2000 ticks and doubles; at the end it must hold exactly
  // what a store sized for the final span from the start holds.
  tools::view::ViewStore grown(0, 1, 3, /*growable=*/true);
  const std::int64_t n = 12'345;
  int grew = 0;
  for (std::int64_t k = 0; k <= n; ++k) {
    const double values[3] = {0.001 * double(k), std::sin(0.01 * double(k)), double((k * 7919) % 101)};
    grew += grown.add({k, 0, 0}, values) ? 1 : 0;
  }
  EXPECT_EQ(grew, 3);  // 1999 -> 3999 -> 7999 -> 15999
  EXPECT_EQ(grown.span_ticks(), 15'999);
  tools::view::ViewStore direct(15'999, 1, 3);
  ASSERT_EQ(direct.buckets(), grown.buckets());
  for (std::int64_t k = 0; k <= n; ++k) {
    const double values[3] = {0.001 * double(k), std::sin(0.01 * double(k)), double((k * 7919) % 101)};
    direct.add({k, 0, 0}, values);
  }
  EXPECT_EQ(grown.buckets_json(0), direct.buckets_json(0));
  grown.clear();
  EXPECT_EQ(grown.rows(), 0);
  EXPECT_EQ(grown.span_ticks(), 1999);
}

}  // namespace frame_channel_test
}  // namespace gyrostab
