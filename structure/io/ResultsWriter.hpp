#pragma once
// ResultsWriter: time series of the structure (moving mesh + fields) in one HDF5 file, indexed by an XDMF 3
// file next to it so that ParaView (Xdmf3 readers) opens the run directly.
//
// HDF5 layout:
//   /mesh/<dataset>            (n x nodesPerCell, int32), one per cell set (an element kind's cells:
//                              triangles, lines, bars, ...), written once; one XDMF grid per set with cells
//   /steps/<000000>/           attributes time (double), step (int64)
//   /steps/<000000>/coordinates (N x 3, double)
//   /steps/<000000>/<field>     (count) or (count x components), double; attribute center
//   /tables/<name>/<column>     (rows), double; attribute column (its position in the table)
//   /@restart_times             (optional) times at which a restarted run continued the series
//
// Append mode (ResultsWriter::append) continues an existing series, e.g. after a restart: steps later than
// the restart time are dropped first (a restart from an earlier time must not leave a stale future), the rest
// of the file (mesh, kept steps, tables) stays. Space of dropped steps is not reclaimed (h5repack does that).
//
// Crash safety: after every writeStep/writeTable the HDF5 file is flushed and only then is the XDMF index
// replaced (temporary file + rename), so the index never references data that is not on disk.

#include <array>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "structure/model/FieldView.hpp"

namespace fsi::structure {

class ResultsWriter {
 public:
  /// Creates (truncates) h5File and writes the connectivity of every cell set (the element kinds',
  /// ElementKind::outputCells, in their order); the XDMF index is h5File with extension .xdmf. Throws
  /// std::invalid_argument for out-of-range connectivity or a repeated set, std::runtime_error on I/O
  /// failure.
  ResultsWriter(std::filesystem::path h5File, int numNodes, std::vector<CellSet> cells);
  /// The same with the two cell sets of a membrane-and-cable mesh (surfaceAndLines).
  ResultsWriter(std::filesystem::path h5File, int numNodes, const std::vector<std::array<int, 3>>& triangles,
                const std::vector<std::array<int, 2>>& lines);
  /// Continues the series in h5File: keeps its steps with time <= keepUntil and drops the later ones, then
  /// writes further steps after them. The file's mesh must be the one given (else std::runtime_error naming
  /// the file); a missing file is created as by the constructor.
  static ResultsWriter append(std::filesystem::path h5File, int numNodes, std::vector<CellSet> cells,
                              double keepUntil);
  static ResultsWriter append(std::filesystem::path h5File, int numNodes,
                              const std::vector<std::array<int, 3>>& triangles,
                              const std::vector<std::array<int, 2>>& lines, double keepUntil);
  /// The cell sets "membranes" (Triangle, /mesh/triangles) and "cables" (Line, /mesh/lines) of plain
  /// connectivity, as the membrane and cable kinds write them (for callers without a Model: tests, tools).
  static std::vector<CellSet> surfaceAndLines(const std::vector<std::array<int, 3>>& triangles,
                                              const std::vector<std::array<int, 2>>& lines);
  ~ResultsWriter();
  ResultsWriter(ResultsWriter&&) noexcept;
  ResultsWriter& operator=(ResultsWriter&&) noexcept;
  ResultsWriter(const ResultsWriter&) = delete;
  ResultsWriter& operator=(const ResultsWriter&) = delete;

  /// Appends one output step. coordinates: 3*numNodes values, xyz interleaved. Field names must be unique,
  /// non-empty, without '/' and other than "coordinates"; violations throw std::invalid_argument.
  void writeStep(double time, long step, const double* coordinates, const std::vector<FieldView>& fields);

  /// Stores (or replaces) /tables/<name>; data[i] is the column named columns[i], all of equal length.
  void writeTable(const std::string& name, const std::vector<std::string>& columns,
                  const std::vector<std::vector<double>>& data);

  /// The table /tables/<name> as written: column names in their order and the columns (empty if absent).
  std::pair<std::vector<std::string>, std::vector<std::vector<double>>> readTable(
      const std::string& name) const;

  /// Stores (or replaces) a double-array attribute of the file's root group; rootAttribute reads it back
  /// (empty if absent).
  void writeRootAttribute(const std::string& name, const std::vector<double>& values);
  std::vector<double> rootAttribute(const std::string& name) const;

  /// Flushes and closes the file; idempotent. Later writes throw std::logic_error.
  void close();

  /// Steps in the series (in append mode including the kept ones).
  int stepsWritten() const;
  /// Time of the last step in the series; -infinity if there is none.
  double lastStepTime() const;
  const std::filesystem::path& h5Path() const;
  const std::filesystem::path& xdmfPath() const;

 private:
  struct Impl;
  ResultsWriter() = default;
  std::unique_ptr<Impl> impl_;
};

/// One frame of a results file as a later run reads it back (fsi run --start-from): the mesh, and the frame's
/// current coordinates and displacement (reference = coordinates - displacement).
struct ResultsFrame {
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::array<int, 2>> lines;
  std::vector<double> coordinates;   ///< 3 per node
  std::vector<double> displacement;  ///< 3 per node
  std::string step;                  ///< the frame's group name under /steps
  double time = 0;                   ///< its attribute `time`
  long long stepNumber = 0;          ///< its attribute `step` (the run's step or iteration)
  int numNodes() const { return int(coordinates.size() / 3); }
};

/// The last frame of h5File (written by ResultsWriter). Throws fsi::InputError naming the file and the object
/// for a file that is not such a series, holds no frame, or holds a non-finite or out-of-range value or an
/// attribute (`/@num_nodes`, the frame's `time` and `step`) that is not a scalar of its type.
ResultsFrame readLastFrame(const std::filesystem::path& h5File);

}  // namespace fsi::structure
