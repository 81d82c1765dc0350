#pragma once
// CouplingCsv: structure/coupling.csv of a coupled run — a header line, then one row per accepted window
// whose first column is the time. One file per run: a restart continues it, first dropping the rows later
// than the restart (a restart from an earlier time must not leave a stale future), and marks where it
// continued with a comment line
//
//   # restart at t = <time>
//
// (readers skip lines starting with '#'). Rows are flushed one by one, so a killed run leaves every
// accepted window on disk.

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

namespace fsi::coupling {

struct CsvRestart {
  double keepUntil = 0;  ///< rows with a time above this are dropped
  std::string time;      ///< the restart time as written in the comment (the fluid's time name)
};

class CouplingCsv {
 public:
  /// Without `restart`: creates (truncates) `file` and writes `header`. With it: keeps the file's lines up
  /// to the first row later than restart->keepUntil (and none of the marks of restarts at or after
  /// restart->time) and appends the restart comment; a missing file is
  /// started with `header`. Throws fsi::InputError naming the file if its header differs from `header` (the
  /// columns changed) or a row has no time; std::runtime_error on I/O failure.
  CouplingCsv(std::filesystem::path file, const std::string& header,
              const std::optional<CsvRestart>& restart = std::nullopt);
  /// Appends one row (without the line end) and flushes it.
  void row(const std::string& line);
  const std::filesystem::path& path() const { return file_; }

 private:
  std::filesystem::path file_;
  std::ofstream os_;
};

}  // namespace fsi::coupling
