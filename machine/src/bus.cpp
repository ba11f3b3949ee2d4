#include "ccbuild/machine/bus.hpp"

#include <chrono>
#include <lcm/lcm-cpp.hpp>

#include "ccbuild/common/input_error.hpp"

namespace ccbuild::machine {

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

int Bus::handle(int timeout_ms) {
  handled_ = 0;
  while (lcm_->handleTimeout(handled_ == 0 ? timeout_ms : 0) > 0) {
  }
  return handled_;
}

}  // namespace ccbuild::machine
