#pragma once
// An eventfd another thread can signal, so a poll() loop wakes as soon as a result is ready instead of
// polling with sleeps.
namespace bmp::detector {

class Wakeup {
 public:
  Wakeup();  // throws std::system_error
  ~Wakeup();
  Wakeup(const Wakeup&) = delete;
  Wakeup& operator=(const Wakeup&) = delete;

  void notify();  // thread-safe
  void clear();   // consumes pending notifications
  int fd() const { return fd_; }

 private:
  int fd_;
};

}  // namespace bmp::detector
