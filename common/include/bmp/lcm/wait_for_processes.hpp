#pragma once
// Holding a publisher back until its consumers are up: their PROCESS_STATUS heartbeats are counted per
// process start (name and instance), so "--wait-for bmp-tracker,bmp-tracker" waits for two trackers, and
// one tracker heard twice, or a second consumer of the same name still starting, never releases it early.
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "bmp/lcm/lcm_node.hpp"
#include "bmp/lcm/process.hpp"

namespace bmp {

// The bookkeeping of a wait, without LCM: a multiset of names ({a, a, b}: two distinct processes named a and
// one named b), each entry satisfied by one distinct process.
class ProcessWaitList {
 public:
  explicit ProcessWaitList(const std::vector<std::string>& names);
  // A heartbeat: counts when its name is still wanted and this instance has not been counted before.
  // Returns whether it counted.
  bool heard(const std::string& name, int64_t instance);
  bool satisfied() const { return missing_count_ == 0; }
  // What is still missing, e.g. "1 more bmp-tracker, 2 more bmp-detector" ("" when satisfied).
  std::string missing() const;

 private:
  std::map<std::string, int> wanted_;  // name -> processes still to hear
  std::set<std::pair<std::string, int64_t>> counted_;
  int missing_count_ = 0;
};

// Handles LCM until one distinct process per entry of names has sent a heartbeat on status_channel.
// Returns false when a stop is requested first; throws std::runtime_error naming what is missing after
// timeout_s ("no heartbeat from 1 more bmp-tracker within 30 s"). No names: returns true at once.
bool waitForProcesses(LcmNode& lcm, const StopSignal& stop, const std::vector<std::string>& names,
                      double timeout_s, const std::string& status_channel = channels::kProcessStatus);

}  // namespace bmp
