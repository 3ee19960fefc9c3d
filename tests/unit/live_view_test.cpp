// The live view's parts without a server: the SPSC ring (order, drops counted on the producer side, a producer
// and a consumer thread racing), the store's buckets (min/max and their order, one row a bucket when rows are
// few), the placing of limits on signals and the units read from column names.
#include <gtest/gtest.h>

#include <map>
#include <thread>

#include "tools/log/signal_channel.hpp"
#include "tools/view/live_ring.hpp"
#include "tools/view/view_meta.hpp"
#include "tools/view/view_store.hpp"

namespace gyrostab {
namespace live_view_test {

using tools::view::LiveRing;
using tools::view::RowHeader;
using tools::view::ViewStore;

TEST(LiveRing, KeepsOrderAndCountsDropsWhenFull) {
  LiveRing ring(2, 5);  // rounded up to 8 rows
  EXPECT_EQ(ring.capacity(), 8u);
  for (int i = 0; i < 10; ++i) {
    const double v[2] = {double(i), -double(i)};
    ring.push({i, 0, 0}, v);
  }
  EXPECT_EQ(ring.dropped(), 2u);
  std::vector<std::int64_t> ticks;
  ring.drain([&](const RowHeader& h, const double* v) {
    ticks.push_back(h.tick);
    EXPECT_EQ(v[0], double(h.tick));
    EXPECT_EQ(v[1], -double(h.tick));
  });
  EXPECT_EQ(ticks, (std::vector<std::int64_t>{0, 1, 2, 3, 4, 5, 6, 7}));
  const double v[2] = {42, 43};
  EXPECT_TRUE(ring.push({42, 0, 0}, v));  // room again after the drain
}

TEST(LiveRing, ProducerAndConsumerThreads) {
  LiveRing ring(3, 64);
  constexpr std::int64_t kRows = 200'000;
  std::int64_t received = 0, last = -1;
  bool ordered = true, intact = true;
  std::atomic<bool> done{false};
  std::thread consumer([&] {
    auto take = [&](const RowHeader& h, const double* v) {
      ordered = ordered && h.tick > last;
      intact = intact && v[0] == double(h.tick) && v[1] == 2.0 * double(h.tick) && v[2] == 3.0 * double(h.tick);
      last = h.tick;
      ++received;
    };
    while (!done.load()) ring.drain(take);
    ring.drain(take);
  });
  for (std::int64_t k = 0; k < kRows; ++k) {
    const double v[3] = {double(k), 2.0 * double(k), 3.0 * double(k)};
    ring.push({k, 0, 0}, v);
  }
  done = true;
  consumer.join();
  EXPECT_TRUE(ordered);
  EXPECT_TRUE(intact);
  EXPECT_EQ(received + static_cast<std::int64_t>(ring.dropped()), kRows);
  EXPECT_GT(received, 0);
}

TEST(ViewStore, MinMaxPerBucketAndTheirOrder) {
  // 10 000 ticks, a row every tick: 10 001 rows share the 2000 buckets, about 5 rows each.
  ViewStore store(10'000, 1, 2);
  ASSERT_EQ(store.buckets(), tools::view::kMaxBuckets);
  for (std::int64_t k = 1; k <= 10'000; ++k) {
    const double row[2] = {0.001 * double(k), k % 5 == 1 ? 10.0 : -double(k % 5)};
    store.add({k, 0, 0}, row);
  }
  const nlohmann::json b = store.buckets_json(0);
  ASSERT_EQ(b.size(), 2000u);
  std::int64_t rows = 0;
  for (const auto& x : b) rows += x["n"].get<std::int64_t>();
  EXPECT_EQ(rows, 10'000);
  // Bucket 1 holds ticks 6..10 (floor(k·2000/10001) = 1), values 10, -2, -3, -4, -0: the maximum first.
  EXPECT_EQ(b[1]["i"], 1);
  EXPECT_EQ(b[1]["hi"][0], 10.0);
  EXPECT_EQ(b[1]["lo"][0], -4.0);
  EXPECT_EQ(b[1]["lo_first"][0], 0);  // the maximum came first
  EXPECT_EQ(store.bucket_of(10'000), 1999);
}

TEST(ViewStore, FewRowsOneRowPerBucket) {
  ViewStore store(900'000, 50, 2);  // the active ship: 18 001 rows > 2000: shared
  EXPECT_EQ(store.buckets(), 2000);
  ViewStore small(1000, 50, 2);     // 21 rows: one bucket each
  EXPECT_EQ(small.buckets(), 21);
  for (std::int64_t k = 50; k <= 1000; k += 50) EXPECT_EQ(small.bucket_of(k), k / 50) << k;
}

TEST(ViewMeta, LimitsPlacedOnlyWhereATableDeclaresThem) {
  // Columns no table declares: a limit is never placed by its name, it stays unplaced.
  const std::vector<std::string> ship{"t_s", "roll_rad", "precession_rad", "precession_torque_Nm"};
  const tools::ChannelInfo undeclared{"/gyrostab/signals", "t", tools::signals_of_columns(ship)};
  const nlohmann::json placed =
      tools::view::placed_limits({{"precession_stop_rad", 1.2}, {"off", 0}, {"bad", "x"}}, undeclared);
  ASSERT_EQ(placed.size(), 1u);
  EXPECT_EQ(placed[0]["label"], "end stop");
  EXPECT_TRUE(placed[0]["signal"].is_null());
  EXPECT_EQ(placed[0]["placed_by"], "");
  EXPECT_EQ(placed[0]["channel"], "/gyrostab/signals");
  EXPECT_FALSE(undeclared.signals[1].declared);
  EXPECT_FALSE(undeclared.signals[1].unit.has_value());
}

// A device converted to its own table: the columns' units, symbols and limits come from its [[column]]s.
constexpr tools::ColumnSpec kColumns[] = {
    {"tilt_rad", "φ", "rad", "", "tilt_stop_rad, tilt_soft_rad", "car body tilt"},
    {"motor_torque_Nm", "M", "N m", "", "torque_max_Nm", "gimbal motor torque"},
    {"wheel_load_N", "F", "N", "", "", "load on the guide wheel"},
};
constexpr tools::DeviceOutputs kOutputs{kColumns, {}};

TEST(SignalChannel, ColumnsFromTheSignalTable) {
  const auto s = tools::signals_of_columns({"t_s", "tilt_rad", "motor_torque_Nm", "wheel_load_N", "extra_rad"},
                                           &kOutputs);
  ASSERT_EQ(s.size(), 5u);
  EXPECT_EQ(s[1].unit, "rad");
  EXPECT_EQ(s[1].symbol, "φ");
  EXPECT_EQ(s[1].description, "car body tilt");
  EXPECT_EQ(s[1].limits, (std::vector<std::string>{"tilt_stop_rad", "tilt_soft_rad"}));
  EXPECT_TRUE(s[1].declared);
  EXPECT_EQ(s[2].unit, "N m");
  EXPECT_EQ(s[3].unit, "N");  // no suffix rule knows "_N": only the table does
  EXPECT_FALSE(s[4].declared);  // not in the table: nothing but its name is known
  EXPECT_FALSE(s[4].unit.has_value());
  // Limits go where the table says, even where a name would say otherwise ("torque_max_Nm" names no column).
  const tools::ChannelInfo c{"/gyrostab/signals", "t", s};
  const nlohmann::json placed = tools::view::placed_limits(
      {{"tilt_stop_rad", 0.3}, {"tilt_soft_rad", 0.2}, {"torque_max_Nm", 50.0}, {"extra_stop_rad", 1.0},
       {"nowhere_limit_m", 2.0}},
      c);
  std::map<std::string, std::string> where;
  for (const auto& l : placed) where[l["key"]] = l["signal"].is_null() ? "-" : l["signal"].get<std::string>() + "/" + l["placed_by"].get<std::string>();
  EXPECT_EQ(where["tilt_stop_rad"], "tilt_rad/table");
  EXPECT_EQ(where["tilt_soft_rad"], "tilt_rad/table");
  EXPECT_EQ(where["torque_max_Nm"], "motor_torque_Nm/table");
  EXPECT_EQ(where["extra_stop_rad"], "-");  // never placed by a name
  EXPECT_EQ(where["nowhere_limit_m"], "-");
}

TEST(SignalChannel, JsonNumbersRoundTrip) {
  std::string s;
  for (double v : {0.1, 1.0 / 3.0, -2.5e-300, 1e21, 123456789.123456789}) {
    s.clear();
    tools::append_json_number(s, v);
    EXPECT_EQ(std::stod(s), v) << s;
  }
  s.clear();
  tools::append_json_number(s, std::nan(""));
  EXPECT_EQ(s, "null");
}

}  // namespace live_view_test
}  // namespace gyrostab
