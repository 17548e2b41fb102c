#pragma once
// Field output: one parallel-HDF5 file per output plus an XDMF index that
// ParaView opens directly. No HDF5 types here so includers need not see hdf5.h.
#include "core/field.hpp"
#include "core/grid.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace voigt {

// A named field handed to the output layer: 1 component (scalar) or 3 (vector).
struct OutField {
  std::string name;
  Centring centring;
  std::vector<Field> comps;
};

class FieldWriter {
 public:
  FieldWriter(const Grid& g, std::string dir); // dir must exist
  // Collective over g.comm. Writes DIR/fields_NNNNNN.h5 and rewrites
  // DIR/fields.xdmf (temporal collection of every output so far).
  // Ghost layers must be exchanged first (periodic node n is read from them).
  // Returns the .h5 path.
  std::string write(int index, double time, const std::vector<OutField>& fields);
  // The outputs written so far (the XDMF index), for checkpoints: a restarted
  // run restores them so fields.xdmf keeps listing the earlier files.
  nlohmann::json entries() const;
  void restoreEntries(const nlohmann::json& j);

 private:
  struct Entry {
    int index;
    double time;
    std::string file; // basename, relative to dir
    std::vector<std::pair<std::string, Centring>> fields;
    std::vector<int> ncomp;
  };
  void writeXdmf() const;

  Grid g_;
  std::string dir_;
  std::vector<Entry> entries_;
};

} // namespace voigt
