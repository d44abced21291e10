#pragma once
// SIGUSR1 ("save the map now") read from a signalfd: no handler and no process-wide flag. The signal is
// blocked for the calling thread and those it creates later, so construct it before any other thread.
namespace bmp::mapper {

class SaveSignal {
 public:
  SaveSignal();   // blocks SIGUSR1 and opens the descriptor; throws std::runtime_error when it cannot
  ~SaveSignal();  // closes it and restores the signal mask
  SaveSignal(const SaveSignal&) = delete;
  SaveSignal& operator=(const SaveSignal&) = delete;
  // True (once per burst of signals) when SIGUSR1 arrived since the last call. Never blocks.
  bool pending();

 private:
  int fd_ = -1;
  bool was_blocked_ = false;
};

}  // namespace bmp::mapper
