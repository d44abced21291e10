#pragma once
// Collects the output of the launched processes: every line goes to the process's log file; progress of
// capture and every warning or error of any process is also echoed to the terminal, prefixed by its name.
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace bmp::launcher {

class OutputRelay {
 public:
  // Starts following fd (a pipe's read end); lines go to log_path, and to stderr when echo_all or when
  // they carry a warning/error tag.
  void follow(int fd, const std::string& name, const std::string& log_path, bool echo_all);
  // Reads what is available, waiting up to timeout_ms; returns false once every pipe is closed.
  bool pump(int timeout_ms);

 private:
  struct Stream {
    int fd;
    std::string name;
    std::ofstream log;
    bool echo_all;
    std::string partial;
    bool open = true;
  };
  void emit(Stream& s, const std::string& line);
  std::vector<std::unique_ptr<Stream>> streams_;
};

}  // namespace bmp::launcher
