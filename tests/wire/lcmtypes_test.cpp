// The LCM messages between the dispatcher and the machines (wire/lcmtypes/): they
// round-trip, the largest path chunk stays under the 64 kB LCM would fragment, a
// truncated or foreign message does not decode, and they travel over memq:// in-process.

#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>
#include <string>
#include <vector>

// lcm-gen's decoders read a hash GCC cannot prove initialised once inlined here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "ccbuild_lcm/ccbuild_ack_t.hpp"
#include "ccbuild_lcm/ccbuild_job_t.hpp"
#include "ccbuild_lcm/ccbuild_path_chunk_t.hpp"
#include "ccbuild_lcm/ccbuild_status_t.hpp"
#pragma GCC diagnostic pop

namespace {

using ccbuild_lcm::ccbuild_job_t;
using ccbuild_lcm::ccbuild_path_chunk_t;

// A chunk holding `n` waypoints with long names, as large as this many points make it.
ccbuild_path_chunk_t chunk_of(int n) {
  ccbuild_path_chunk_t c;
  c.utime = 1'700'000'000'000'000;
  c.machine_id = std::string(64, 'm');
  c.job_id = 42;
  c.seq = 7;
  c.chunk_index = 0;
  c.chunk_count = 1;
  c.n = n;
  for (int k = 0; k < n; ++k) {
    c.t_s.push_back(k * 0.5);
    c.x_m.push_back(k * 0.01);
    c.y_m.push_back(-k * 0.02);
    c.z_m.push_back(3.0);
    c.heading_rad.push_back(k * 1e-3);
    c.extruding.push_back(k % 2 == 0);
    c.wall.push_back(k % 2 == 0 ? 999'999'999 : 0);
    c.piece.push_back(k % 2 == 0 ? 3 : 0);
  }
  return c;
}

TEST(LcmTypes, AFullPathChunkStaysUnder64kB) {
  const ccbuild_path_chunk_t full = chunk_of(ccbuild_path_chunk_t::MAX_POINTS);
  // LCM sends a message in one UDP datagram when it fits 65,507 bytes, its channel name
  // and a 12-byte header included; beyond that it fragments.
  EXPECT_LE(full.getEncodedSize() + 64 + 12, 65'507);
  // One point more per chunk would still fit, so MAX_POINTS leaves room for names.
  EXPECT_GT(full.getEncodedSize(), 40'000);
}

TEST(LcmTypes, JobsAndChunksRoundTrip) {
  ccbuild_job_t job;
  job.utime = 1;
  job.machine_id = "gantry-1";
  job.job_id = 12;
  job.seq = 3;
  job.kind = ccbuild_job_t::DEPOSIT;
  job.floor = 2;
  job.layer = 17;
  job.nozzle = 0;
  job.start_s = 12345.5;
  job.duration_s = 2451.9;
  job.plan = "g3n1";
  job.detail = "floor 2 layer 17";
  job.chunk_count = 2;
  job.point_count = 1500;
  std::vector<uint8_t> bytes(job.getEncodedSize());
  ASSERT_EQ(job.encode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));
  ccbuild_job_t back;
  ASSERT_EQ(back.decode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));
  EXPECT_EQ(back.job_id, 12);
  EXPECT_EQ(back.kind, +ccbuild_job_t::DEPOSIT);  // + : the constant has no definition to bind
  EXPECT_EQ(back.plan, "g3n1");
  EXPECT_DOUBLE_EQ(back.duration_s, 2451.9);

  const ccbuild_path_chunk_t chunk = chunk_of(10);
  std::vector<uint8_t> cb(chunk.getEncodedSize());
  ASSERT_GT(chunk.encode(cb.data(), 0, static_cast<int>(cb.size())), 0);
  ccbuild_path_chunk_t c2;
  ASSERT_GT(c2.decode(cb.data(), 0, static_cast<int>(cb.size())), 0);
  EXPECT_EQ(c2.n, 10);
  EXPECT_EQ(c2.wall[4], 999'999'999);
  EXPECT_DOUBLE_EQ(c2.t_s[9], 4.5);
}

TEST(LcmTypes, ATruncatedOrForeignMessageDoesNotDecode) {
  const ccbuild_path_chunk_t chunk = chunk_of(10);
  std::vector<uint8_t> bytes(chunk.getEncodedSize());
  chunk.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  ccbuild_path_chunk_t back;
  // One byte short, and the first byte (of the type's fingerprint) changed.
  EXPECT_LT(back.decode(bytes.data(), 0, static_cast<int>(bytes.size()) - 1), 0);
  bytes[0] ^= 0x5a;
  EXPECT_LT(back.decode(bytes.data(), 0, static_cast<int>(bytes.size())), 0);
  // A job's bytes are not a chunk.
  ccbuild_job_t job;
  job.chunk_count = 0;
  job.point_count = 0;
  std::vector<uint8_t> jb(job.getEncodedSize());
  job.encode(jb.data(), 0, static_cast<int>(jb.size()));
  EXPECT_LT(back.decode(jb.data(), 0, static_cast<int>(jb.size())), 0);
}

struct AckSink {
  std::vector<ccbuild_lcm::ccbuild_ack_t> received;
  void on_ack(const lcm::ReceiveBuffer*, const std::string&, const ccbuild_lcm::ccbuild_ack_t* m) {
    received.push_back(*m);
  }
};

TEST(LcmTypes, TravelOverMemqInOneProcess) {
  lcm::LCM bus("memq://");
  ASSERT_TRUE(bus.good());
  AckSink sink;
  bus.subscribe("CCBUILD_ACK_gantry-1", &AckSink::on_ack, &sink);
  ccbuild_lcm::ccbuild_ack_t ack;
  ack.utime = 5;
  ack.machine_id = "gantry-1";
  ack.job_id = 12;
  ack.seq = 1;
  ack.accepted = true;
  ack.duplicate = true;
  ack.reason = "";
  ASSERT_EQ(bus.publish("CCBUILD_ACK_gantry-1", &ack), 0);
  ASSERT_GE(bus.handleTimeout(1000), 0);
  ASSERT_EQ(sink.received.size(), 1u);
  EXPECT_EQ(sink.received[0].job_id, 12);
  EXPECT_TRUE(sink.received[0].duplicate);
}

}  // namespace
