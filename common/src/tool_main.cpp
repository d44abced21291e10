#include "bmp/common/tool_main.hpp"

#include <iostream>
#include <string>

#include "bmp/common/config.hpp"

namespace bmp {

int runTool(ArgParser& args, int argc, char** argv, const std::function<int(const ArgParser&)>& body) {
  try {
    if (!args.parse(argc, argv)) {
      std::cout << args.help();
      return 0;
    }
    return body(args);
  } catch (const ArgError& e) {
    const std::string message = e.what();
    std::cerr << message << (message.find("see --help") == std::string::npos ? " (see --help)" : "") << "\n";
    return 2;
  } catch (const ConfigError& e) {
    std::cerr << args.program() << ": configuration error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << args.program() << ": " << e.what() << "\n";
    return 1;
  }
}

}  // namespace bmp
