#pragma once
// Checkpoints: every allocated field of a FieldStore (owned cells and nodes,
// written as global arrays with parallel HDF5, so a checkpoint restarts on any
// rank count) plus one JSON document with everything else a run carries from
// step to step (time, step, dt, counters, diagnostics, output bookkeeping and
// each effect's saveState). No HDF5 types here.
//
// Files in the output directory:
//   checkpoint.h5.tmp      being written (never read)
//   checkpoint_<step>.h5   complete checkpoints, the newest `keep` are kept
//   latest                 name of the newest complete checkpoint (replaced by rename)
// A checkpoint becomes visible under its final name only after the file is
// closed and synced, so a crash (even SIGKILL) mid-write leaves the previous
// one intact and `latest` pointing at it.
#include <nlohmann/json.hpp>

#include <string>

#include "core/field.hpp"
#include "core/grid.hpp"

namespace voigt {

class Checkpointer {
 public:
  Checkpointer(const Grid& g, std::string dir, int keep = 2);
  // Collective over g.comm. Writes the checkpoint of `step` (see above) and
  // returns its path. On failure the temporary file is removed, earlier
  // checkpoints are untouched, and the exception says why (disk full, ...).
  std::string write(long step, const FieldStore& fields, const nlohmann::json& meta);
  double lastSeconds() const { return seconds_; }
  long long lastBytes() const { return bytes_; }

 private:
  Grid g_;
  std::string dir_;
  int keep_;
  double seconds_ = 0;
  long long bytes_ = 0;
};

// Collective. The checkpoint file to restart from: `path` itself if it is a
// file, else the newest readable checkpoint in directory `path` (the one
// `latest` names, or failing that the highest-numbered checkpoint_*.h5 that
// opens). Throws if there is none.
std::string findCheckpoint(MPI_Comm comm, const std::string& path);

// Collective. Reads the owned points of every allocated field of `fields`
// from the checkpoint (ghost layers are left to the caller) and returns its
// JSON document. The grid must match the checkpoint's; a field the store has
// but the checkpoint lacks is an error naming it.
nlohmann::json readCheckpoint(const Grid& g, FieldStore& fields, const std::string& path);

// Rank 0 helper for restarts: cuts each file DIR/<name> of `sizes` ({name:
// bytes}, recorded in the checkpoint) back to that size, dropping what a
// crashed run appended after its checkpoint (the restarted run writes it
// again); a file recorded as empty is removed.
void truncateOutputs(const std::string& dir, const nlohmann::json& sizes);

} // namespace voigt
