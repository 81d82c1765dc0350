#include "coupling/CouplingCsv.hpp"

#include <cstdlib>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "structure/model/Error.hpp"

namespace fsi::coupling {

namespace fs = std::filesystem;

CouplingCsv::CouplingCsv(fs::path file, const std::string& header, const std::optional<CsvRestart>& restart)
    : file_(std::move(file)) {
  if (file_.has_parent_path()) fs::create_directories(file_.parent_path());
  std::vector<std::string> keep{header};
  std::error_code ec;
  if (restart && fs::exists(file_, ec)) {
    std::ifstream is(file_);
    if (!is) throw std::runtime_error("cannot read " + file_.string());
    std::string line;
    int lineNo = 0;
    const double restartTime = std::strtod(restart->time.c_str(), nullptr);
    bool future = false;
    while (!future && std::getline(is, line)) {
      ++lineNo;
      if (lineNo == 1) {
        if (line != header)
          throw InputError(file_.string() + " has the columns\n  " + line + "\nbut this run writes\n  " +
                           header + "\n(the scene's probes changed?): move the file away to start a new one");
        continue;
      }
      if (line.empty()) continue;
      // The mark of an earlier restart at or after this one's time is superseded by this one.
      const std::string mark = "# restart at t = ";
      if (line.rfind(mark, 0) == 0 && std::strtod(line.c_str() + mark.size(), nullptr) >= restartTime)
        continue;
      if (line[0] != '#') {
        char* end = nullptr;
        const double t = std::strtod(line.c_str(), &end);
        if (end == line.c_str() || (*end != ',' && *end != '\0'))
          throw InputError(file_.string() + ", line " + std::to_string(lineNo) +
                           ": no time in the first column");
        // Rows are in time order: from the first later one on, everything is the discarded future.
        future = t > restart->keepUntil;
        if (future) break;
      }
      keep.push_back(line);
    }
  }
  if (restart) keep.push_back("# restart at t = " + restart->time);

  // Replace the file whole (temporary + rename), then append to it.
  fs::path tmp = file_;
  tmp += ".tmp";
  {
    std::ofstream os(tmp, std::ios::trunc);
    for (const std::string& l : keep) os << l << '\n';
    os.close();
    if (!os) throw std::runtime_error("cannot write " + tmp.string());
  }
  fs::rename(tmp, file_);
  os_.open(file_, std::ios::app);
  if (!os_) throw std::runtime_error("cannot append to " + file_.string());
}

void CouplingCsv::row(const std::string& line) {
  os_ << line << '\n';
  os_.flush();
  if (!os_) throw std::runtime_error("cannot write " + file_.string());
}

}  // namespace fsi::coupling
