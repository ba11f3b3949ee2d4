// bus_intruder: puts hostile messages on a machine's channels during a dry-run, for
// tests/tools/dry_run_intruder.sh. It listens to CCBUILD_JOB_<machine> for a second after
// the first job, keeps the bytes of the last job it saw (one the machine has seen too),
// and then publishes: random bytes, that job cut in half, a status
// message on the job channel (another type), a job for another machine, that job again
// byte for byte (a replay), a job an hour old with an id the schedule does not have (a
// stale replay), and a pause an hour old (a stale replay). None may be executed.
// Usage: bus_intruder LCM_URL MACHINE_ID

#include <chrono>
#include <cstdio>
#include <cstring>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <thread>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "ccbuild_lcm/ccbuild_command_t.hpp"
#include "ccbuild_lcm/ccbuild_job_t.hpp"
#include "ccbuild_lcm/ccbuild_status_t.hpp"
#pragma GCC diagnostic pop

namespace {
std::int64_t now_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

template <class Message>
void publish(lcm::LCM& bus, const std::string& channel, const Message& m) {
  std::vector<std::uint8_t> bytes(m.getEncodedSize());
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  bus.publish(channel, bytes.data(), static_cast<unsigned>(bytes.size()));
}
}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: bus_intruder LCM_URL MACHINE_ID\n");
    return 2;
  }
  const std::string machine = argv[2];
  lcm::LCM bus(argv[1]);
  if (!bus.good()) return 2;
  const std::string job_channel = "CCBUILD_JOB_" + machine;
  std::vector<std::uint8_t> first;
  struct Keeper {
    std::vector<std::uint8_t>* into;
    void on(const lcm::ReceiveBuffer* b, const std::string&) {
      const auto* d = static_cast<const std::uint8_t*>(b->data);
      into->assign(d, d + b->data_size);
    }
  } keeper{&first};
  lcm::Subscription* listening = bus.subscribe(job_channel, &Keeper::on, &keeper);
  for (int k = 0; k < 600 && first.empty(); ++k) bus.handleTimeout(100);
  if (first.empty()) {
    std::fprintf(stderr, "bus_intruder: no job seen on %s\n", job_channel.c_str());
    return 1;
  }
  for (auto until = std::chrono::steady_clock::now() + std::chrono::seconds(1);
       std::chrono::steady_clock::now() < until;)
    bus.handleTimeout(20);
  bus.unsubscribe(listening);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  int sent = 0;
  // Random bytes, and the job cut in half: neither decodes.
  std::vector<std::uint8_t> garbage(64);
  for (std::size_t k = 0; k < garbage.size(); ++k)
    garbage[k] = static_cast<std::uint8_t>(k * 37 + 11);
  bus.publish(job_channel, garbage.data(), static_cast<unsigned>(garbage.size()));
  bus.publish(job_channel, first.data(), static_cast<unsigned>(first.size() / 2));
  sent += 2;
  // Another type on the job channel.
  ccbuild_lcm::ccbuild_status_t status{};
  status.utime = now_us();
  status.machine_id = machine;
  publish(bus, job_channel, status);
  ++sent;
  // A fresh job for another machine, on this machine's channel.
  ccbuild_lcm::ccbuild_job_t job;
  if (job.decode(first.data(), 0, static_cast<int>(first.size())) != static_cast<int>(first.size()))
    return 1;
  ccbuild_lcm::ccbuild_job_t foreign = job;
  foreign.utime = now_us();
  foreign.seq = 1'000'000;
  foreign.machine_id = "gantry-9";
  publish(bus, job_channel, foreign);
  ++sent;
  // The first job again, byte for byte.
  bus.publish(job_channel, first.data(), static_cast<unsigned>(first.size()));
  ++sent;
  // A job an hour old with an id the schedule does not have, and a pause an hour old.
  ccbuild_lcm::ccbuild_job_t stale = job;
  stale.utime = now_us() - 3'600'000'000LL;
  stale.seq = 1'000'001;
  stale.job_id = 999'999'990;
  stale.chunk_count = 0;
  stale.point_count = 0;
  publish(bus, job_channel, stale);
  ccbuild_lcm::ccbuild_command_t pause;
  pause.utime = now_us() - 3'600'000'000LL;
  pause.machine_id = machine;
  pause.seq = 1'000'002;
  pause.command = ccbuild_lcm::ccbuild_command_t::PAUSE;
  pause.reason = "an old pause, replayed";
  publish(bus, "CCBUILD_COMMAND_" + machine, pause);
  sent += 2;
  std::printf("bus_intruder: %d hostile messages put on %s's channels\n", sent, machine.c_str());
  return 0;
}
