#pragma once
// The typed publish/subscribe seam over LCM that the dispatcher and the simulated machine
// talk through (docs/dispatch.md). Tests use "memq://" in one process; separate processes
// use "udpm://" (in their own network namespace in tests). Messages are decoded here, so
// that one that does not decode (malformed, truncated, of another type) is counted and
// reported, never handed on. Not thread-safe: one thread publishes and handles.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace lcm {
class LCM;
class LogFile;
class ReceiveBuffer;
}  // namespace lcm

namespace ccbuild::wire {

/// Now, in microseconds since the Unix epoch (every message's `utime`).
std::int64_t utime_now();

/// The channel of one kind of message for one machine: "CCBUILD_JOB_gantry-1". Kinds:
/// JOB, PATH, ACK, PROGRESS, DONE, STATUS, FAULT, COMMAND.
std::string channel(const std::string& kind, const std::string& machine_id);

/// The site clock's channel, one for every machine (ccbuild_clock_t).
inline constexpr const char* kClockChannel = "CCBUILD_CLOCK";

class Bus {
 public:
  /// Opens LCM at `url` ("" for LCM's default). Throws InputError (field `--lcm-url`)
  /// when LCM cannot start there.
  explicit Bus(const std::string& url);
  ~Bus();
  Bus(const Bus&) = delete;
  Bus& operator=(const Bus&) = delete;

  /// Publishes an lcm-gen message. Throws InternalError when LCM refuses it.
  template <class Message>
  void publish(const std::string& channel, const Message& message) {
    std::vector<std::uint8_t> bytes(message.getEncodedSize());
    message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    publish_bytes(channel, bytes);
  }

  /// Calls `on` with each message on `channel` that decodes as a `Message`; one that does
  /// not goes to the malformed handler.
  template <class Message>
  void subscribe(const std::string& channel, std::function<void(const Message&)> on) {
    subscribe_bytes(channel, [on](const std::uint8_t* data, int size) {
      Message message;
      if (message.decode(data, 0, size) != size) return false;
      on(message);
      return true;
    });
  }

  /// Called with the channel and the size of every message that did not decode.
  void on_malformed(std::function<void(const std::string& channel, int size)> handler);
  /// Messages that did not decode, so far.
  long malformed_count() const { return malformed_; }

  /// Writes every message on the bus (whatever its channel, whoever sent it) to an LCM
  /// log at `path`, in the format lcm-logger writes, so that lcm-logplayer and lcm-spy
  /// replay it. Each message is flushed as it is logged, so that a write error (a full
  /// disk, /dev/full) shows at once in log_error(). Throws InputError (field `--log`) when
  /// the file cannot be created.
  void log_to(const std::string& path);
  long logged() const { return logged_; }
  /// Why writing the log failed (the system's words), empty while it has not.
  const std::string& log_error() const { return log_error_; }
  /// Flushes and closes the log; returns false (and sets log_error()) when that failed.
  bool close_log();

  /// Handles the messages that arrive within `timeout_ms` (at least one if any does);
  /// returns how many were handled.
  int handle(int timeout_ms);

 private:
  using Decoder = std::function<bool(const std::uint8_t* data, int size)>;
  void publish_bytes(const std::string& channel, const std::vector<std::uint8_t>& bytes);
  void subscribe_bytes(const std::string& channel, Decoder decoder);
  void receive(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void log_event(const lcm::ReceiveBuffer* buffer, const std::string& channel);

  std::unique_ptr<lcm::LCM> lcm_;
  std::unique_ptr<lcm::LogFile> log_;
  long logged_ = 0;
  std::string log_error_;
  std::vector<std::pair<std::string, Decoder>> decoders_;
  std::function<void(const std::string&, int)> malformed_handler_;
  long malformed_ = 0;
  int handled_ = 0;
};

}  // namespace ccbuild::wire
