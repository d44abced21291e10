#include "bmp/lcm/wait_for_processes.hpp"

#include <memory>
#include <sstream>
#include <stdexcept>

#include <bmp/process_status_t.hpp>

#include "bmp/common/log.hpp"
#include "bmp/common/timing.hpp"

namespace bmp {

ProcessWaitList::ProcessWaitList(const std::vector<std::string>& names) {
  for (const auto& name : names) ++wanted_[name];
  missing_count_ = static_cast<int>(names.size());
}

bool ProcessWaitList::heard(const std::string& name, int64_t instance) {
  const auto it = wanted_.find(name);
  if (it == wanted_.end() || it->second == 0) return false;
  if (!counted_.insert({name, instance}).second) return false;  // the same process again
  --it->second;
  --missing_count_;
  return true;
}

std::string ProcessWaitList::missing() const {
  std::string out;
  for (const auto& [name, count] : wanted_)
    if (count > 0) out += (out.empty() ? "" : ", ") + std::to_string(count) + " more " + name;
  return out;
}

bool waitForProcesses(LcmNode& lcm, const StopSignal& stop, const std::vector<std::string>& names,
                      double timeout_s, const std::string& status_channel) {
  if (names.empty()) return true;
  // Shared with the handler, which LCM keeps to the end of the connection, long after this returns.
  const auto waiting = std::make_shared<ProcessWaitList>(names);
  lcm.subscribe<process_status_t>(status_channel,
                                  [waiting](const process_status_t& msg, const ReceivedInfo&) {
                                    waiting->heard(msg.name, msg.instance);
                                  });
  std::string list;
  for (const auto& name : names) list += (list.empty() ? "" : ",") + name;
  log::info("waiting for heartbeats of ", list);
  const Stopwatch watch;
  while (!waiting->satisfied()) {
    if (stop.requested()) return false;
    if (watch.elapsedMs() > timeout_s * 1000.0) {
      std::ostringstream message;
      message << "no heartbeat from " << waiting->missing() << " within " << timeout_s << " s";
      throw std::runtime_error(message.str());
    }
    lcm.handle(50);
  }
  return true;
}

}  // namespace bmp
