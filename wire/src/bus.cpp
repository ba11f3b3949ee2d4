#include "ccbuild/wire/bus.hpp"

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <lcm/lcm-cpp.hpp>

#include "ccbuild/common/input_error.hpp"

namespace ccbuild::wire {

std::int64_t utime_now() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::string channel(const std::string& kind, const std::string& machine_id) {
  return "CCBUILD_" + kind + "_" + machine_id;
}

Bus::Bus(const std::string& url) : lcm_(std::make_unique<lcm::LCM>(url)) {
  if (!lcm_->good())
    throw InputError("", 0, "--lcm-url",
                     "LCM cannot start at '" + url +
                         "' (udpm:// needs a network with multicast, e.g. 'ip link set lo "
                         "multicast on' and a route to 224.0.0.0/4)");
}

Bus::~Bus() = default;

void Bus::publish_bytes(const std::string& channel, const std::vector<std::uint8_t>& bytes) {
  const int status = lcm_->publish(channel, bytes.data(), static_cast<unsigned>(bytes.size()));
  CCBUILD_CHECK(status == 0, "LCM refused to publish on " + channel);
}

void Bus::subscribe_bytes(const std::string& channel, Decoder decoder) {
  // One LCM subscription per channel; several decoders may share it.
  bool known = false;
  for (const auto& d : decoders_) known = known || d.first == channel;
  decoders_.emplace_back(channel, std::move(decoder));
  if (!known) lcm_->subscribe(channel, &Bus::receive, this);
}

void Bus::receive(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  ++handled_;
  const auto* data = static_cast<const std::uint8_t*>(buffer->data);
  const int size = static_cast<int>(buffer->data_size);
  bool decoded = false;
  for (const auto& [name, decoder] : decoders_)
    if (name == channel) decoded = decoder(data, size) || decoded;
  if (!decoded) {
    ++malformed_;
    if (malformed_handler_) malformed_handler_(channel, size);
  }
}

void Bus::on_malformed(std::function<void(const std::string&, int)> handler) {
  malformed_handler_ = std::move(handler);
}

void Bus::log_to(const std::string& path) {
  log_ = std::make_unique<lcm::LogFile>(path, "w");
  if (!log_->good()) {
    log_.reset();
    throw InputError(path, 0, "--log", "cannot be created for the LCM log");
  }
  lcm_->subscribe(".*", &Bus::log_event, this);
}

void Bus::log_event(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  lcm::LogEvent event;
  event.eventnum = logged_++;
  event.timestamp = buffer->recv_utime;
  event.channel = channel;
  event.datalen = static_cast<int32_t>(buffer->data_size);
  event.data = buffer->data;
  if (!log_ || !log_error_.empty()) return;
  errno = 0;
  if (log_->writeEvent(&event) != 0 || std::fflush(log_->getFilePtr()) != 0 ||
      std::ferror(log_->getFilePtr()))
    log_error_ = errno != 0 ? std::strerror(errno) : "write failed";
}

bool Bus::close_log() {
  if (!log_) return log_error_.empty();
  errno = 0;
  if (log_error_.empty() &&
      (std::fflush(log_->getFilePtr()) != 0 || std::ferror(log_->getFilePtr())))
    log_error_ = errno != 0 ? std::strerror(errno) : "write failed";
  log_.reset();
  return log_error_.empty();
}

int Bus::handle(int timeout_ms) {
  // Waits once, then takes what has already arrived (a bounded number, so that a busy
  // bus still lets its caller step).
  handled_ = 0;
  int arrived = lcm_->handleTimeout(timeout_ms);
  for (int more = 0; arrived > 0 && more < 1000; ++more) arrived = lcm_->handleTimeout(0);
  return handled_;
}

}  // namespace ccbuild::wire
