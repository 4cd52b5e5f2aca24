// A copy of the log in the results: everything the program writes to std::cout and
// std::cerr (not what libraries print through C stdio) also goes to a file. Used by the
// executable on rank 0: start() at once (the lines are held in memory, up to 1 MiB, until
// there is a result folder), attach() when the staging folder exists.
#pragma once
#include <string>

namespace stentor::log_copy {

// Starts copying std::cout and std::cerr (held in memory until attach()).
void start();
// Writes what was held to `path`, then appends every later line as it is written. Does
// nothing without start(). Throws WriteError when the file cannot be written.
void attach(const std::string& path);
// Throws WriteError naming the file when a write to it has failed since attach() (the
// copy stops at the first failure; the terminal log goes on).
void check();
// Stops copying and gives std::cout and std::cerr their own buffers back.
void stop();

}  // namespace stentor::log_copy
